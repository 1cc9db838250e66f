// The time cursor of every plot of a teaching scene (/scenes): a line or a marker over the
// plot that stands at the 3D animation's time. Each check's plot says where its cursor goes
// (solvers/scenes/scene_checks.py `cursor`):
//   {axis: "t"}                 a vertical line at x = t (plots against time);
//   {axis: "x", t: [...], x}    a vertical line at the x of the last sample with t_i <= t
//                               (the returns of a map, counted along the run);
//   {axis: "point", t, x, y}    a marker at (x, y) of the sample nearest t (where the body is
//                               now in the map's coordinates).
// The cursor is a DOM element over the plot (moving it costs no redraw of the plot).
"use strict";

// index of the last t_i <= t (0 if none), t sorted
function lastBefore(ts, t) {
  let lo = 0, hi = ts.length - 1;
  if (!(t >= ts[0])) return 0;
  while (lo < hi) {
    const mid = (lo + hi + 1) >> 1;
    if (ts[mid] <= t) lo = mid; else hi = mid - 1;
  }
  return lo;
}

export class TimeCursor {
  constructor(plotEl, spec) {
    this.el = plotEl;
    this.spec = spec || { axis: "t" };
    this.mark = document.createElement("div");
    this.mark.className = this.spec.axis === "point" ? "time-cursor point" : "time-cursor line";
    this.mark.dataset.testid = "time-cursor";
    this.mark.setAttribute("aria-hidden", "true");
    plotEl.parentElement.appendChild(this.mark);
    this.t = 0;
  }

  // where (x, y) of the data lands in px, relative to the plot's wrapper; null outside
  place(x, y) {
    const fl = this.el._fullLayout;
    const area = this.el.querySelector(".nsewdrag");
    if (!fl || !area || x === null || x === undefined) return null;
    const box = area.getBoundingClientRect(), wrap = this.el.parentElement.getBoundingClientRect();
    const [x0, x1] = fl.xaxis.range;
    const px = box.left - wrap.left + ((x - x0) / (x1 - x0)) * box.width;
    let py = null;
    if (y !== undefined) {
      const [y0, y1] = fl.yaxis.range;
      py = box.top - wrap.top + (1 - (y - y0) / (y1 - y0)) * box.height;
    }
    if (px < box.left - wrap.left - 1 || px > box.right - wrap.left + 1) return null;
    return { px, py, top: box.top - wrap.top, height: box.height };
  }

  /** Put the cursor at the animation's time t. */
  at(t) {
    this.t = t;
    const s = this.spec;
    let where;
    if (s.axis === "point") {
      const i = lastBefore(s.t, t);
      where = this.place(s.x[i], s.y[i]);
    } else if (s.axis === "x") {
      where = this.place(s.x[lastBefore(s.t, t)]);
    } else {
      where = this.place(t);
    }
    const m = this.mark;
    m.hidden = !where;
    if (!where) return;
    m.dataset.t = t.toFixed(3);
    m.style.left = `${where.px.toFixed(1)}px`;
    if (s.axis === "point") {
      m.style.top = `${where.py.toFixed(1)}px`;
    } else {
      m.style.top = `${where.top.toFixed(1)}px`;
      m.style.height = `${where.height.toFixed(1)}px`;
    }
  }

  remove() {
    this.mark.remove();
  }
}

// Font sizes of a claim plot: on a screen as plots.js draws them; in presentation, tick
// labels and legend of 18 px and axis titles of 20 px, readable from the back of a room.
export function claimFonts(el, present) {
  const tick = present ? 18 : 13, title = present ? 20 : 13;
  return window.Plotly.relayout(el, {
    "font.size": tick, "xaxis.tickfont.size": tick, "yaxis.tickfont.size": tick,
    "xaxis.title.font.size": title, "yaxis.title.font.size": title,
    "legend.font.size": present ? 18 : 12,
  });
}
