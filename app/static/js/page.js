// What every page does (loaded by the shared head, app/services/site_shell.py).
//
// 1. A box that scrolls sideways (a wide formula, a table on a phone) must be reachable with
// the keyboard, or its hidden part is lost to anyone without a mouse (WCAG 2.1.1, axe
// "scrollable-region-focusable"): each such box becomes focusable whenever it overflows,
// after the scripts drew the page and when the window is resized.
// 2. The pinned site header wraps to one, two or three rows with the width: its height goes
// to --header-h, so that a page's own pinned bar (.pagenav) sits just under it.
// 3. The site's menu button (a phone: app/services/site_shell.py MENU) opens and closes the
// navigation's links; Escape closes them and gives the focus back to the button.
// 4. A disclosure marked data-open-wide (the home page's legend) is open on a wide screen
// and closed on a phone, where it would push the tables off the first screen.
"use strict";

const BOXES = ".katex-display, .table-wrap, .scroll-x, pre, #cells, #map-table, .printed";

function mark() {
  for (const el of document.querySelectorAll(BOXES)) {
    if (el.scrollWidth > el.clientWidth + 1 && !el.hasAttribute("tabindex")) {
      const style = getComputedStyle(el);
      if (style.overflowX === "auto" || style.overflowX === "scroll") el.setAttribute("tabindex", "0");
    }
  }
}

function headerHeight() {
  const h = document.querySelector("header.site");
  const pinned = h && getComputedStyle(h).position === "sticky";
  document.documentElement.style.setProperty("--header-h", pinned ? `${h.offsetHeight}px` : "0px");
}

let queued = false;
function soon() {
  if (queued) return;
  queued = true;
  requestAnimationFrame(() => { queued = false; mark(); headerHeight(); });
}

function menu() {
  const button = document.querySelector("header.site .navmenu");
  if (!button) return;
  const set = (open) => { button.setAttribute("aria-expanded", String(open)); soon(); };
  button.addEventListener("click", () => set(button.getAttribute("aria-expanded") !== "true"));
  document.addEventListener("keydown", (e) => {
    if (e.key !== "Escape" || button.getAttribute("aria-expanded") !== "true") return;
    set(false);
    button.focus();
  });
}

const WIDE = window.matchMedia("(min-width: 701px)");
function disclosures() {
  for (const d of document.querySelectorAll("details[data-open-wide]")) d.open = WIDE.matches;
}

menu();
disclosures();
new MutationObserver(soon).observe(document.documentElement, { childList: true, subtree: true });
addEventListener("resize", soon);
soon();
