// Plots of a run (plotly.js served from the installed plotly package): the state against
// time, the relative drift of every invariant on a log scale, and the path of gamma on
// the unit sphere (for the flat-base bodies: the contact point on the flat face).
"use strict";

// plotGlPixelRatio: the WebGL plots (the 3D scenes, the 3D maps) drawn at the screen's own
// pixel density. Plotly's default, 2, draws them at twice the width and height of a
// 1x screen (a projector, most laptops): four times the pixels, which a browser without
// a GPU rasterizes in software at every frame of an animation, for a picture the screen
// then shrinks back (docs/performance.md)
const CONFIG = { responsive: true, displaylogo: false, toImageButtonOptions: { scale: 2 },
  plotGlPixelRatio: Math.min(4, Math.max(1, window.devicePixelRatio || 1)) };
// Where the parts of a plot go so that none covers another (tests/e2e/
// test_plot_layout_browser.py): the title top left, the toolbar standing upright at the
// right edge (lying flat it ran over the title on a phone), the legend at the very
// bottom of the figure, under the x-axis title, pushing the bottom margin as it wraps.
const LEGEND_BELOW = { orientation: "h", x: 0, xanchor: "left", yref: "container", y: 0,
  yanchor: "bottom" };
const MODEBAR = { orientation: "v" };
const FONT = { family: "system-ui, -apple-system, Segoe UI, Roboto, sans-serif", size: 13, color: "#1b1f24" };
const COLORS = ["#1f5f99", "#c2571a", "#2a8a3e", "#8e3ea8", "#b8860b", "#0f7f8a", "#c21c2c"];
const PRETTY = { g1: "γ₁", g2: "γ₂", g3: "γ₃", M1: "M₁", M2: "M₂", M3: "M₃", r1: "r₁", r2: "r₂" };
const INVARIANT_NAMES = {
  energy: "energy H", gamma_squared: "γ²", area: "(M, γ)", M_squared: "M²", M_plus_S_squared: "(M+S)²",
  gyro_area: "(M+S, γ)", unbalanced_F: "unbalanced-ball integral", jellett: "Jellett",
  routh: "Routh", borisov_fedorov: "Borisov–Fedorov",
  // the rubber cases (catalogue/glossary.yaml): the no-spin constraint, zero on their
  // motions, and their integrals
  spin: "(ω, γ)", rubber_ball_F: "|M × γ|²", rubber_routh: "N ω₃ (rubber Routh)",
};

function base(title, extra = {}) {
  return {
    title: { text: title, x: 0.02, font: { size: 15 } },
    font: FONT,
    margin: { l: 64, r: 18, t: 44, b: 48 },
    paper_bgcolor: "#fff",
    plot_bgcolor: "#fff",
    legend: LEGEND_BELOW,
    modebar: MODEBAR,
    ...extra,
  };
}

// Plotly pushes the bottom margin for a legend under the plot and for the x axis's tick
// labels and title each on its own, the larger push winning: a legend of two or three rows
// (a phone) then lay on the tick labels. Once the legend's height is known the bottom margin
// becomes the sum of the two, and the figure grows by it so that the axes keep their room;
// again after every redraw (a resized window rewraps the legend).
function roomForLegend(el, height, axisRoom = 48) {
  const fit = () => {
    const lg = el.querySelector(".legend .bg");
    if (!lg) return undefined;
    const h = Math.ceil(lg.getBoundingClientRect().height);
    const b = axisRoom + h + 6;
    if (Math.abs(((el.layout || {}).margin || {}).b - b) <= 2) return undefined;
    return window.Plotly.relayout(el, { "margin.b": b, height: height + h });
  };
  if (!el.dataset.legendRoom) {
    el.dataset.legendRoom = "1";
    el.on("plotly_afterplot", fit);
  }
  return fit();
}

export function invariantName(n) {
  return INVARIANT_NAMES[n] || n;
}

export function plotState(el, run) {
  const labels = run.state_labels;
  const t = run.t;
  const col = (j) => run.state.map((row) => row[j]);
  const traces = labels.map((lab, j) => ({
    x: t, y: col(j), name: PRETTY[lab] || lab, type: "scatter", mode: "lines",
    line: { width: 1.8, color: COLORS[j % COLORS.length] },
    yaxis: j < 3 ? "y" : "y2",
  }));
  const second = labels.length === 6 ? "γ" : "r₁, r₂";
  const layout = base("State against time", {
    grid: { rows: 2, columns: 1, subplots: [["xy"], ["xy2"]], roworder: "top to bottom" },
    xaxis: { title: { text: "t" }, zeroline: false },
    yaxis: { title: { text: "M" }, domain: [0.55, 1], zeroline: false },
    yaxis2: { title: { text: second }, domain: [0, 0.45], zeroline: false },
    height: 420,
  });
  return window.Plotly.react(el, traces, layout, CONFIG).then(() => roomForLegend(el, 420));
}

export function plotDrift(el, run) {
  const t = run.t.slice(1);
  const traces = Object.entries(run.invariants).map(([name, v], j) => {
    const f0 = v[0];
    const scale = Math.max(Math.abs(f0), 1);
    // exact zeros have no logarithm: left out rather than clipped to a made-up floor
    const y = v.slice(1).map((f) => (f === null ? null : Math.abs(f - f0) / scale || null));
    return { x: t, y, name: invariantName(name), type: "scatter", mode: "lines",
      line: { width: 1.6, color: COLORS[j % COLORS.length] } };
  });
  const rtol = run.stats && run.stats.rtol;
  if (rtol) {
    traces.push({ x: [t[0], t[t.length - 1]], y: [rtol, rtol], name: "rtol", mode: "lines",
      line: { dash: "dot", color: "#8c959f", width: 1 }, hoverinfo: "skip" });
  }
  const layout = base("Relative drift |F(t) − F(0)| / max(|F(0)|, 1)", {
    xaxis: { title: { text: "t" } },
    yaxis: { title: { text: "relative drift" }, type: "log", exponentformat: "power" },
    height: 420,
  });
  return window.Plotly.react(el, traces, layout, CONFIG).then(() => roomForLegend(el, 420));
}

export function sphereMesh(radius = 1, n = 36, centre = [0, 0, 0]) {
  const x = [], y = [], z = [];
  for (let i = 0; i <= n; i++) {
    const th = (Math.PI * i) / n;
    const rx = [], ry = [], rz = [];
    for (let j = 0; j <= 2 * n; j++) {
      const ph = (Math.PI * j) / n;
      rx.push(centre[0] + radius * Math.sin(th) * Math.cos(ph));
      ry.push(centre[1] + radius * Math.sin(th) * Math.sin(ph));
      rz.push(centre[2] + radius * Math.cos(th));
    }
    x.push(rx); y.push(ry); z.push(rz);
  }
  return { x, y, z };
}

export function plotGamma(el, run) {
  const labels = run.state_labels;
  const t = run.t;
  if (labels.length !== 6) {
    // flat base: gamma = e3 is fixed; what moves is the contact point r = (r1, r2, z)
    const trace = { x: run.state.map((r) => r[3]), y: run.state.map((r) => r[4]), mode: "lines+markers",
      type: "scatter", name: "contact point", line: { width: 1, color: "#8c959f" },
      marker: { color: t, colorscale: "Viridis", size: 4, showscale: true, colorbar: { title: { text: "t" } } } };
    const layout = base("Contact point on the flat base (r₁, r₂), body axes", {
      xaxis: { title: { text: "r₁" }, scaleanchor: "y" }, yaxis: { title: { text: "r₂" } }, height: 460,
      showlegend: false,
    });
    return window.Plotly.react(el, [trace], layout, CONFIG);
  }
  const g = (j) => run.state.map((row) => row[j]);
  const s = sphereMesh(1, 30);
  const traces = [
    { type: "surface", ...s, opacity: 0.18, showscale: false, hoverinfo: "skip",
      colorscale: [[0, "#c9d6e3"], [1, "#c9d6e3"]], name: "unit sphere" },
    { type: "scatter3d", mode: "lines", x: g(3), y: g(4), z: g(5), name: "γ(t)",
      line: { width: 5, color: t, colorscale: "Viridis", showscale: true, colorbar: { title: { text: "t" }, len: 0.6 } } },
    { type: "scatter3d", mode: "markers", x: [g(3)[0]], y: [g(4)[0]], z: [g(5)[0]], name: "start",
      marker: { size: 5, color: "#c21c2c" } },
  ];
  const ax = (title) => ({ title: { text: title }, range: [-1.1, 1.1], backgroundcolor: "#fff", gridcolor: "#e5e7eb" });
  const layout = base("Path of γ on the unit sphere (body axes)", {
    scene: { xaxis: ax("γ₁"), yaxis: ax("γ₂"), zaxis: ax("γ₃"), aspectmode: "cube",
      camera: { eye: { x: 1.5, y: 1.3, z: 0.9 } } },
    margin: { l: 0, r: 0, t: 44, b: 0 }, height: 460, showlegend: false,
  });
  return window.Plotly.react(el, traces, layout, CONFIG);
}

// A teaching scene's check as it was measured (GET /api/scenes/{id}/checks/{k},
// solvers/scenes/scene_checks.py): the traces are the very data of the verdict. The
// title is the HTML heading above the plot and the legend sits on top of the plot area,
// so no axis title, legend or toolbar is drawn over another (tests/e2e layout test).
const ROLE = {
  claim: (j) => ({ mode: "lines", line: { width: 2.4, color: COLORS[j % COLORS.length] } }),
  contrast: () => ({ mode: "lines", line: { width: 1.6, color: "#8c959f", dash: "dash" } }),
  limit: () => ({ mode: "lines", line: { width: 1.5, color: "#c21c2c", dash: "dot" }, hoverinfo: "skip" }),
  raw: () => ({ mode: "lines", line: { width: 1, color: "#9fb7cf" } }),
  event: () => ({ mode: "markers", marker: { size: 11, color: "#c21c2c", symbol: "diamond",
    line: { width: 1, color: "#fff" } } }),
};

export function plotClaim(el, plot) {
  let j = 0;
  const traces = plot.traces.map((tr) => {
    const style = (ROLE[tr.role] || ROLE.claim)(tr.role === "claim" ? j++ : 0);
    const t = { type: "scatter", x: tr.x, y: tr.y, name: tr.name, ...style };
    if (tr.mode === "markers") {
      Object.assign(t, { mode: "markers", marker: { size: 4, color: style.line ? style.line.color : undefined } });
      delete t.line;
    }
    return t;
  });
  const shapes = plot.vline ? [{ type: "line", xref: "x", yref: "paper", x0: plot.vline.x, x1: plot.vline.x,
    y0: 0, y1: 1, line: { color: "#c21c2c", dash: "dot", width: 1.5 } }] : [];
  const layout = {
    font: FONT, paper_bgcolor: "#fff", plot_bgcolor: "#fff",
    margin: { l: 72, r: 14, t: 8, b: 46 },
    xaxis: { title: { text: plot.x_title, standoff: 6 }, zeroline: false, automargin: true },
    yaxis: { title: { text: plot.y_title, standoff: 6 }, automargin: true,
      ...(plot.log_y ? { type: "log", exponentformat: "power" } : { zeroline: true }),
      ...(plot.y_range ? { range: plot.y_range } : {}) },
    showlegend: true,
    legend: { orientation: "h", x: 0, xanchor: "left", y: 1.02, yanchor: "bottom", font: { size: 12 } },
    shapes,
  };
  // teaching plots: no toolbar over the legend (a class reads them, zooming is not the point)
  return window.Plotly.react(el, traces, layout, { ...CONFIG, displayModeBar: false });
}

export function purge(el) {
  if (window.Plotly && el) window.Plotly.purge(el);
}

export { CONFIG, FONT, LEGEND_BELOW, MODEBAR, base };
