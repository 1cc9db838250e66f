// What every page does (loaded by the shared head, app/services/site_shell.py).
//
// 1. A box that scrolls sideways (a wide formula, a table on a phone) must be reachable with
// the keyboard, or its hidden part is lost to anyone without a mouse (WCAG 2.1.1, axe
// "scrollable-region-focusable"): each such box becomes focusable whenever it overflows,
// after the scripts drew the page and when the window is resized.
// 2. The pinned site header wraps to one, two or three rows with the width: its height goes
// to --header-h, so that a page's own pinned bar (.pagenav) sits just under it.
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

new MutationObserver(soon).observe(document.documentElement, { childList: true, subtree: true });
addEventListener("resize", soon);
soon();
