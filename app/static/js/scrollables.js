// A box that scrolls sideways (a wide formula, a table on a phone) must be reachable with
// the keyboard, or its hidden part is lost to anyone without a mouse (WCAG 2.1.1, axe
// "scrollable-region-focusable"). Every page loads this (app/services/site_shell.py): it
// makes each such box focusable whenever it overflows, after the scripts drew the page
// and when the window is resized.
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

let queued = false;
function soon() {
  if (queued) return;
  queued = true;
  requestAnimationFrame(() => { queued = false; mark(); });
}

new MutationObserver(soon).observe(document.documentElement, { childList: true, subtree: true });
addEventListener("resize", soon);
soon();
