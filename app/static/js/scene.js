// 3D animation of the body rolling (data from POST /api/scene, solvers/models/kinematics.py):
// the body's mesh turned by Q(t) and moved to x_G(t), its axes, and the contact point's
// path on the plane or the sphere.
"use strict";

import { CONFIG, FONT, sphereMesh } from "./plots.js";

const BODY_COLORS = ["#2b5d8a", "#f0c419"];
const AXIS_COLORS = ["#c21c2c", "#2a8a3e", "#1f5f99"];

function transform(Q, x, v) {
  return [
    Q[0] * v[0] + Q[1] * v[1] + Q[2] * v[2] + x[0],
    Q[3] * v[0] + Q[4] * v[1] + Q[5] * v[2] + x[1],
    Q[6] * v[0] + Q[7] * v[1] + Q[8] * v[2] + x[2],
  ];
}

export class Scene {
  constructor(el, data, { onFrame } = {}) {
    this.el = el;
    this.d = data;
    this.onFrame = onFrame || (() => {});
    this.frame = 0;
    this.playing = false;
    this.timer = null;
    const V = data.mesh.vertices;
    this.size = Math.max(...V.map((v) => Math.hypot(v[0], v[1], v[2])));
    this.axisLen = 1.35 * this.size;
    // on the plane the body may roll far away: by default the view follows it (the floor's
    // checker pattern moves under it); on a sphere the whole support stays in view
    this.follow = !data.support_radius;
    this.W = Math.max(3.2 * this.size, 2);
    this.cell = this.W / 5;
  }

  offset(f) {
    if (!this.follow) return [0, 0, 0];
    const x = this.d.x_G[f];
    return [x[0], x[1], 0];
  }

  bodyXYZ(f) {
    const Q = this.d.Q[f], o = this.offset(f), g = this.d.x_G[f];
    const x = [g[0] - o[0], g[1] - o[1], g[2] - o[2]];
    const X = [], Y = [], Z = [];
    for (const v of this.d.mesh.vertices) {
      const p = transform(Q, x, v);
      X.push(p[0]); Y.push(p[1]); Z.push(p[2]);
    }
    return [X, Y, Z];
  }

  axesXYZ(f) {
    const Q = this.d.Q[f], o = this.offset(f), g = this.d.x_G[f], L = this.axisLen;
    const x = [g[0] - o[0], g[1] - o[1], g[2] - o[2]];
    return [0, 1, 2].map((i) => {
      const e = [0, 0, 0];
      e[i] = L;
      const p = transform(Q, x, e);
      return [[x[0], p[0]], [x[1], p[1]], [x[2], p[2]]];
    });
  }

  bounds() {
    if (this.follow) {
      const top = Math.max(...this.d.x_G.map((p) => p[2])) + 1.5 * this.size;
      return [[-this.W, -this.W, -0.05 * this.W], [this.W, this.W, Math.max(top, 0.6 * this.W)]];
    }
    const pts = [...this.d.contact, ...this.d.x_G];
    const lo = [0, 1, 2].map((i) => Math.min(...pts.map((p) => p[i])) - 1.15 * this.size);
    const hi = [0, 1, 2].map((i) => Math.max(...pts.map((p) => p[i])) + 1.15 * this.size);
    if (this.d.support_radius) {
      const R = this.d.support_radius;
      for (let i = 0; i < 3; i++) {
        lo[i] = Math.min(lo[i], -R * 1.05);
        hi[i] = Math.max(hi[i], R * 1.05);
      }
    } else {
      lo[2] = Math.min(lo[2], -0.05 * this.size);
    }
    return [lo, hi];
  }

  supportTrace(lo, hi) {
    if (this.d.support_radius) {
      const s = sphereMesh(this.d.support_radius, 40);
      const inside = this.d.k > 0 && !this.d.support_inside_body; // a cavity around the body
      return { type: "surface", ...s, showscale: false, hoverinfo: "skip", name: "support",
        opacity: inside ? 0.12 : 0.45, colorscale: [[0, "#9aa5b1"], [1, "#c9d1d9"]],
        surfacecolor: s.z, lighting: { ambient: 0.7 } };
    }
    const n = 40;
    const xs = Array.from({ length: n + 1 }, (_, i) => lo[0] + ((hi[0] - lo[0]) * i) / n);
    const ys = Array.from({ length: n + 1 }, (_, i) => lo[1] + ((hi[1] - lo[1]) * i) / n);
    const z = ys.map(() => xs.map(() => 0));
    this.floor = { xs, ys, z };
    return { type: "surface", x: xs, y: ys, z, surfacecolor: this.checker([0, 0, 0]), showscale: false,
      hoverinfo: "skip", cmin: 0, cmax: 1, colorscale: [[0, "#e9ecef"], [1, "#cfd5db"]], opacity: 0.95,
      name: "plane", lighting: { ambient: 0.9, diffuse: 0.2 } };
  }

  checker(o) {
    const c = this.cell;
    const { xs, ys } = this.floor;
    return ys.map((y) => xs.map((x) => (Math.floor((x + o[0]) / c) + Math.floor((y + o[1]) / c)) & 1));
  }

  pathXYZ(f, upto) {
    const o = this.offset(f);
    const pts = upto ? this.d.contact.slice(0, f + 1) : this.d.contact;
    const inside = (p) => !this.follow || (Math.abs(p[0] - o[0]) <= this.W && Math.abs(p[1] - o[1]) <= this.W);
    return [0, 1, 2].map((k) => pts.map((p) => (inside(p) ? p[k] - o[k] : null)));
  }

  render() {
    const d = this.d;
    const [lo, hi] = this.bounds();
    const [X, Y, Z] = this.bodyXYZ(0);
    const F = d.mesh.faces;
    const full = this.pathXYZ(0, false);
    const translucent = d.support_inside_body;
    const traces = [
      this.supportTrace(lo, hi),
      { type: "scatter3d", mode: "lines", x: full[0], y: full[1], z: full[2], name: "contact path",
        line: { width: 3, color: "#8c959f" }, hoverinfo: "skip", connectgaps: false },
      { type: "scatter3d", mode: "lines", x: [full[0][0]], y: [full[1][0]], z: [full[2][0]],
        name: "travelled", line: { width: 6, color: "#d97706" }, hoverinfo: "skip" },
      { type: "mesh3d", x: X, y: Y, z: Z, i: F.map((f) => f[0]), j: F.map((f) => f[1]),
        k: F.map((f) => f[2]), facecolor: d.mesh.pattern.map((p) => BODY_COLORS[p]),
        flatshading: true, opacity: translucent ? 0.35 : 1, name: "body", hoverinfo: "skip",
        lighting: { ambient: 0.55, diffuse: 0.7, specular: 0.15 } },
      ...this.axesXYZ(0).map((a, i) => ({ type: "scatter3d", mode: "lines", x: a[0], y: a[1], z: a[2],
        name: ["e₁", "e₂", "e₃"][i] + " (body axes)", line: { width: 6, color: AXIS_COLORS[i] }, hoverinfo: "skip" })),
    ];
    const span = hi.map((h, i) => h - lo[i]);
    const m = Math.max(...span);
    const ax = (i, t) => ({ range: [lo[i], hi[i]], title: { text: t }, backgroundcolor: "#fff",
      gridcolor: "#eef0f2", zeroline: false });
    const layout = {
      font: FONT, margin: { l: 0, r: 0, t: 0, b: 0 }, showlegend: true,
      legend: { orientation: "h", y: 0.02 }, paper_bgcolor: "#fff",
      scene: { xaxis: ax(0, "x"), yaxis: ax(1, "y"), zaxis: ax(2, "z"), aspectmode: "manual",
        aspectratio: { x: span[0] / m, y: span[1] / m, z: span[2] / m },
        camera: { eye: this.follow ? { x: 1.1, y: -1.3, z: 0.75 } : { x: 1.05, y: -1.2, z: 0.7 } } },
      uirevision: "scene",
    };
    return window.Plotly.react(this.el, traces, layout, CONFIG).then(() => this.show(0));
  }

  show(f) {
    this.frame = f;
    const [X, Y, Z] = this.bodyXYZ(f);
    const axes = this.axesXYZ(f);
    const upto = this.pathXYZ(f, true);
    const idx = [2, 3, 4, 5, 6];
    const upd = {
      x: [upto[0], X, ...axes.map((a) => a[0])],
      y: [upto[1], Y, ...axes.map((a) => a[1])],
      z: [upto[2], Z, ...axes.map((a) => a[2])],
    };
    if (this.follow) {
      // the floor and the whole path move under the body
      const full = this.pathXYZ(f, false);
      const { xs, ys, z } = this.floor;
      upd.x.unshift(xs, full[0]);
      upd.y.unshift(ys, full[1]);
      upd.z.unshift(z, full[2]);
      upd.surfacecolor = [this.checker(this.offset(f)), null];
      idx.unshift(0, 1);
      upd.surfacecolor.push(...idx.slice(2).map(() => null));
    }
    window.Plotly.restyle(this.el, upd, idx);
    this.onFrame(f, this.d.t[f]);
  }

  play() {
    if (this.playing) return;
    this.playing = true;
    const step = () => {
      if (!this.playing) return;
      const next = this.frame + 1 >= this.d.t.length ? 0 : this.frame + 1;
      this.show(next);
      this.timer = setTimeout(() => requestAnimationFrame(step), 40);
    };
    step();
  }

  pause() {
    this.playing = false;
    clearTimeout(this.timer);
  }

  destroy() {
    this.pause();
    if (window.Plotly) window.Plotly.purge(this.el);
  }
}
