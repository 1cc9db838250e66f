// The home page's tables keep their column headings in view while the page scrolls
// (on a phone too). A table inside an overflow-x wrapper cannot use position: sticky
// (the wrapper, not the page, is then its scroll container), so a copy of the heading row
// is pinned under the site's header while the table passes under it: same column widths,
// moved sideways with the wrapper's own scroll. The copy is aria-hidden and out of the tab
// order: the table's own heading row stays the accessible one.
"use strict";

// the height of the site header when it stays on screen (sticky on a wide screen, static
// on a phone: reader.css)
function coveredTop() {
  const head = document.querySelector("header.site");
  if (!head) return 0;
  const pos = getComputedStyle(head).position;
  return pos === "sticky" || pos === "fixed" ? Math.max(0, head.getBoundingClientRect().bottom) : 0;
}

export function pinHeader(wrap) {
  const box = document.createElement("div");
  box.className = "pinned-head";
  box.setAttribute("aria-hidden", "true");
  box.hidden = true;
  wrap.before(box);
  let src = null;

  const widths = () => {
    const copy = box.firstElementChild;
    if (!copy || !src) return;
    copy.style.width = `${src.getBoundingClientRect().width}px`;
    const a = src.tHead.rows[0].cells, b = copy.tHead.rows[0].cells;
    for (let i = 0; i < a.length && i < b.length; i++) {
      const w = `${a[i].getBoundingClientRect().width}px`;
      Object.assign(b[i].style, { width: w, minWidth: w, maxWidth: w });
    }
  };

  const build = () => {
    src = wrap.querySelector("table");
    box.textContent = "";
    if (!src || !src.tHead) return;
    const copy = document.createElement("table");
    copy.className = src.className;
    copy.appendChild(src.tHead.cloneNode(true));
    copy.querySelectorAll("[id]").forEach((e) => e.removeAttribute("id"));
    copy.querySelectorAll("a, button, input, select, [tabindex]")
      .forEach((e) => e.setAttribute("tabindex", "-1"));
    box.appendChild(copy);
    widths();
  };

  const update = () => {
    if (wrap.querySelector("table") !== src) build();     // a table drawn again (new marks)
    if (!src || !src.tHead) { box.hidden = true; return; }
    const top = coveredTop();
    const h = src.tHead.getBoundingClientRect(), t = src.getBoundingClientRect();
    const show = h.top < top && t.bottom > top + h.height;
    if (show && box.hidden) widths();
    box.hidden = !show;
    if (!show) return;
    const w = wrap.getBoundingClientRect();
    Object.assign(box.style, { top: `${top}px`, left: `${w.left + wrap.clientLeft}px`,
      width: `${wrap.clientWidth}px` });
    box.firstElementChild.style.transform = `translateX(${-wrap.scrollLeft}px)`;
  };

  addEventListener("scroll", update, { passive: true });
  wrap.addEventListener("scroll", update, { passive: true });
  addEventListener("resize", () => { widths(); update(); });
  build();
  update();
}
