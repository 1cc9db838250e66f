// 3D animation of the body rolling (data from POST /api/scene, solvers/models/kinematics.py):
// the body's mesh turned by Q(t) and moved to x_G(t), its axes, and the contact point's
// path on the plane or the sphere.
"use strict";

import { CONFIG, FONT } from "./plots.js";

const BODY_COLORS = ["#2b5d8a", "#f0c419"];
const AXIS_COLORS = ["#c21c2c", "#2a8a3e", "#1f5f99"];

function transform(Q, x, v) {
  return [
    Q[0] * v[0] + Q[1] * v[1] + Q[2] * v[2] + x[0],
    Q[3] * v[0] + Q[4] * v[1] + Q[5] * v[2] + x[1],
    Q[6] * v[0] + Q[7] * v[1] + Q[8] * v[2] + x[2],
  ];
}

// The server's mesh is a grid over the normals (solvers/models/kinematics.py body_mesh):
// each pole is a whole ring of copies of one point. Smooth shading averages a vertex's
// normal over its faces, so the copies (and the empty triangles between them) left dark
// spokes and a jagged rim at the poles: one vertex per point, no empty triangle.
export function weld(mesh) {
  const index = new Map(), vertices = [], remap = [];
  for (const v of mesh.vertices) {
    const key = v.map((c) => c.toFixed(9)).join(",");
    if (!index.has(key)) { index.set(key, vertices.length); vertices.push(v); }
    remap.push(index.get(key));
  }
  const faces = [], pattern = [];
  mesh.faces.forEach((f, n) => {
    const [a, b, c] = f.map((i) => remap[i]);
    if (a === b || b === c || a === c) return;
    faces.push([a, b, c]);
    pattern.push(mesh.pattern[n]);
  });
  return { vertices, faces, pattern };
}

// a sphere of radius R as a triangle mesh: one vertex at each pole, rings between
function ballMesh(R, nt = 18, nf = 36) {
  const x = [0], y = [0], z = [R], i = [], j = [], k = [];
  for (let a = 1; a < nt; a++) {
    const th = (Math.PI * a) / nt;
    for (let b = 0; b < nf; b++) {
      const ph = (2 * Math.PI * b) / nf;
      x.push(R * Math.sin(th) * Math.cos(ph)); y.push(R * Math.sin(th) * Math.sin(ph));
      z.push(R * Math.cos(th));
    }
  }
  x.push(0); y.push(0); z.push(-R);
  const ring = (a, b) => 1 + (a - 1) * nf + (b % nf), south = x.length - 1;
  for (let b = 0; b < nf; b++) {
    i.push(0); j.push(ring(1, b)); k.push(ring(1, b + 1));
    i.push(south); j.push(ring(nt - 1, b + 1)); k.push(ring(nt - 1, b));
    for (let a = 1; a < nt - 1; a++) {
      i.push(ring(a, b), ring(a, b)); j.push(ring(a + 1, b), ring(a + 1, b + 1));
      k.push(ring(a + 1, b + 1), ring(a, b + 1));
    }
  }
  return { x, y, z, i, j, k };
}

// frames the view is fitted to (every frame of a long run costs more than it tells)
const FIT_FRAMES = 60;

export class Scene {
  constructor(el, data, { onFrame, present = false } = {}) {
    this.el = el;
    this.d = data;
    this.mesh = weld(data.mesh);
    this.onFrame = onFrame || (() => {});
    this.frame = 0;
    this.playing = false;
    this.timer = null;
    // frames shown per tick of the clock (below 1: a frame every few ticks)
    this.speed = 1;
    this.acc = 0;
    // presentation: a contact path and body axes thick enough for a projector
    this.present = present;
    // a playing scene draws only while it can be seen: not in a hidden tab, nor scrolled
    // out of view (without a GPU each frame costs the browser much CPU:
    // docs/performance.md); it goes on from the same frame when seen again
    this.inView = true;
    this.seen = typeof IntersectionObserver === "function" ? new IntersectionObserver(
      (entries) => { this.inView = entries[entries.length - 1].isIntersecting; }) : null;
    if (this.seen) this.seen.observe(el);
    const V = this.mesh.vertices;
    this.size = Math.max(...V.map((v) => Math.hypot(v[0], v[1], v[2])));
    // on the plane the body may roll far away: by default the view follows it (the floor's
    // checker pattern moves under it); on a sphere the whole support stays in view
    this.follow = !data.support_radius;
    this.fit();
  }

  // Each body axis drawn a little beyond the body along it (a long stone's e1 longer than
  // its e3; a thin coin's e3 still visible); in presentation far enough out of a ball to be
  // seen from the back of a room. The body's own reach (its mesh and its axes, turned as in
  // the frames) sets the view: a flat body (the rattleback) is not framed as if it could
  // stand on its tip.
  fit() {
    const V = this.mesh.vertices;
    const out = this.present ? 1.45 : 1.15;
    this.axisLen = [0, 1, 2].map((i) =>
      out * Math.max(0.5 * this.size, ...V.map((v) => Math.abs(v[i]))));
    const ext = this.extent();
    this.ext = ext;
    this.W = 1.1 * Math.max(ext.horizontal, 0.5 * this.size);
    this.top = ext.top;
    this.cell = this.W / 3;
  }

  // how far the body and its axes reach from x_G horizontally, and how high above the
  // floor they go, over FIT_FRAMES frames of the run
  extent() {
    const n = this.d.t.length, step = Math.max(1, Math.floor(n / FIT_FRAMES));
    const L = this.axisLen;
    const pts = [...this.mesh.vertices, [L[0], 0, 0], [0, L[1], 0], [0, 0, L[2]]];
    let horizontal = 0;
    const lo = [Infinity, Infinity, Infinity], hi = [-Infinity, -Infinity, -Infinity];
    for (let f = 0; f < n; f += step) {
      const Q = this.d.Q[f], g = this.d.x_G[f];
      for (const v of pts) {
        const p = transform(Q, g, v);
        horizontal = Math.max(horizontal, Math.abs(p[0] - g[0]), Math.abs(p[1] - g[1]));
        for (let i = 0; i < 3; i++) { lo[i] = Math.min(lo[i], p[i]); hi[i] = Math.max(hi[i], p[i]); }
      }
    }
    return { horizontal, top: hi[2], lo, hi };
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
    for (const v of this.mesh.vertices) {
      const p = transform(Q, x, v);
      X.push(p[0]); Y.push(p[1]); Z.push(p[2]);
    }
    return [X, Y, Z];
  }

  axesXYZ(f) {
    const Q = this.d.Q[f], o = this.offset(f), g = this.d.x_G[f];
    const x = [g[0] - o[0], g[1] - o[1], g[2] - o[2]];
    return [0, 1, 2].map((i) => {
      const e = [0, 0, 0];
      e[i] = this.axisLen[i];
      const p = transform(Q, x, e);
      return [[x[0], p[0]], [x[1], p[1]], [x[2], p[2]]];
    });
  }

  bounds() {
    if (this.follow) {
      // the floor just wider than the body's reach, the box just taller than its top:
      // no empty space above a small body
      return [[-this.W, -this.W, -0.02 * this.W], [this.W, this.W, 1.04 * this.top]];
    }
    // on a sphere: where the body and its axes go over the run, the contact path and the
    // support ball, and no more
    const lo = [...this.ext.lo], hi = [...this.ext.hi];
    const R = this.d.support_radius;
    for (const p of [...this.d.contact, [-R, -R, -R], [R, R, R]]) {
      for (let i = 0; i < 3; i++) { lo[i] = Math.min(lo[i], p[i]); hi[i] = Math.max(hi[i], p[i]); }
    }
    const pad = 0.03 * Math.max(...hi.map((h, i) => h - lo[i]));
    return [lo.map((v) => v - pad), hi.map((v) => v + pad)];
  }

  // The support as a triangle mesh (a Plotly surface costs several times more to draw
  // and to move in a browser without a GPU): a sphere, or the floor's checker board.
  supportTrace() {
    if (this.d.support_radius) {
      const inside = this.d.k > 0 && !this.d.support_inside_body; // a cavity around the body
      return { type: "mesh3d", ...ballMesh(this.d.support_radius), color: "#b3bcc6",
        opacity: inside ? 0.12 : 0.45, hoverinfo: "skip", name: "support",
        lighting: { ambient: 0.7, diffuse: 0.5, specular: 0.05 } };
    }
    this.floor = this.floorFaces();
    return { type: "mesh3d", ...this.floorXYZ(this.offset(0)), ...this.floor, hoverinfo: "skip",
      name: "plane", flatshading: true, lighting: { ambient: 0.95, diffuse: 0.1, specular: 0 } };
  }

  // The checker board's lines are k*cell shifted by the body's offset modulo two cells and
  // clamped into [-W, W]: the vertices move, the colour of each square never changes and
  // the board always covers the floor (squares beyond the edge shrink to nothing).
  floorLines(o) {
    const c = this.cell, K = Math.ceil(this.W / c);
    const r = ((o % (2 * c)) + 2 * c) % (2 * c);
    const out = [];
    for (let k = -K; k <= K + 2; k++) out.push(Math.min(this.W, Math.max(-this.W, k * c - r)));
    return out;
  }

  floorXYZ(o) {
    const xs = this.floorLines(o[0]), ys = this.floorLines(o[1]);
    const x = [], y = [], z = [];
    for (const yv of ys) for (const xv of xs) { x.push(xv); y.push(yv); z.push(0); }
    return { x, y, z };
  }

  floorFaces() {
    const n = this.floorLines(0).length;
    const i = [], j = [], k = [], facecolor = [];
    for (let b = 0; b + 1 < n; b++) {
      for (let a = 0; a + 1 < n; a++) {
        const v = b * n + a, col = (a + b) & 1 ? "#cfd5db" : "#eceff2";
        i.push(v, v); j.push(v + 1, v + n + 1); k.push(v + n + 1, v + n);
        facecolor.push(col, col);
      }
    }
    return { i, j, k, facecolor };
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
    const F = this.mesh.faces;
    const full = this.pathXYZ(0, false);
    const translucent = d.support_inside_body;
    const traces = [
      this.supportTrace(),
      { type: "scatter3d", mode: "lines", x: full[0], y: full[1], z: full[2], name: "contact path",
        line: this.lines().path, hoverinfo: "skip", connectgaps: false },
      { type: "scatter3d", mode: "lines", x: [full[0][0]], y: [full[1][0]], z: [full[2][0]],
        name: "travelled", line: this.lines().travelled, hoverinfo: "skip" },
      { type: "mesh3d", x: X, y: Y, z: Z, i: F.map((f) => f[0]), j: F.map((f) => f[1]),
        k: F.map((f) => f[2]), facecolor: this.mesh.pattern.map((p) => BODY_COLORS[p]),
        // smooth shading over the welded mesh: no facets, no seams
        flatshading: false, opacity: translucent ? 0.35 : 1, name: "body", hoverinfo: "skip",
        lighting: { ambient: 0.6, diffuse: 0.65, specular: 0.1, roughness: 0.6, fresnel: 0.1 } },
      ...this.axesXYZ(0).map((a, i) => ({ type: "scatter3d", mode: "lines", x: a[0], y: a[1], z: a[2],
        name: ["e₁", "e₂", "e₃ (body axes)"][i], line: { width: this.lines().axis, color: AXIS_COLORS[i] },
        hoverinfo: "skip" })),
    ];
    const span = hi.map((h, i) => h - lo[i]);
    const m = Math.max(...span);
    // no axis box, ticks or axis titles: the floor (or the support) is the scale, and
    // WebGL text is most of the first draw's cost in a browser without a GPU
    const ax = (i) => ({ range: [lo[i], hi[i]], visible: false });
    // close enough that the box (fitted to the body above) fills the view
    const eye = this.follow ? { x: 0.85, y: -1.0, z: 0.56 } : { x: 0.92, y: -1.06, z: 0.6 };
    const layout = {
      font: FONT, margin: { l: 0, r: 0, t: 0, b: 0 }, showlegend: true,
      legend: { orientation: "h", y: 0.02, font: { size: this.present ? 18 : 13 } },
      paper_bgcolor: "#fff",
      scene: { xaxis: ax(0), yaxis: ax(1), zaxis: ax(2), aspectmode: "manual",
        aspectratio: { x: span[0] / m, y: span[1] / m, z: span[2] / m },
        // look a little below the middle of the box: the floor seen from above takes the
        // lower part of the view, the body the middle, no empty band above it
        camera: { eye, center: { x: 0, y: 0, z: this.follow ? -0.12 : -0.04 } } },
      uirevision: "scene",
    };
    // the traces above are frame 0 already: drawing it again would double the first draw
    return window.Plotly.react(this.el, traces, layout, CONFIG).then(() => this.onFrame(0, d.t[0]));
  }

  // the widths of the contact path, the travelled part and the body axes: dark and thick
  // enough for a projector in presentation, still plain on a screen
  lines() {
    const p = this.present;
    return { path: { width: p ? 7 : 4, color: p ? "#3d4550" : "#57606a" },
      travelled: { width: p ? 12 : 7, color: "#d97706" }, axis: p ? 11 : 6 };
  }

  // presentation on or off: longer, thicker axes and path, the view fitted again to them,
  // drawn again at the same frame
  setPresent(on) {
    this.present = on;
    this.fit();
    return this.render().then(() => this.show(this.frame));
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
      const board = this.floorXYZ(this.offset(f));
      upd.x.unshift(board.x, full[0]);
      upd.y.unshift(board.y, full[1]);
      upd.z.unshift(board.z, full[2]);
      idx.unshift(0, 1);
    }
    window.Plotly.restyle(this.el, upd, idx);
    this.onFrame(f, this.d.t[f]);
  }

  play() {
    if (this.playing) return;
    this.playing = true;
    const step = () => {
      if (!this.playing) return;
      if (document.hidden || !this.inView) {     // unseen: look again in a quarter second
        this.timer = setTimeout(step, 250);
        return;
      }
      this.acc += this.speed;
      const k = Math.floor(this.acc);
      if (k > 0) {
        this.acc -= k;
        const n = this.d.t.length;
        this.show(this.frame + k >= n ? (this.frame + k) % n : this.frame + k);
      }
      this.timer = setTimeout(() => requestAnimationFrame(step), 40);
    };
    // the next frame after the browser has shown this one, not in the same task
    this.timer = setTimeout(() => requestAnimationFrame(step), 40);
  }

  // one frame on (k = 1) or back (k = -1), paused
  stepBy(k) {
    this.pause();
    const n = this.d.t.length;
    this.show(Math.min(n - 1, Math.max(0, this.frame + k)));
  }

  pause() {
    this.playing = false;
    clearTimeout(this.timer);
  }

  destroy() {
    this.pause();
    if (this.seen) this.seen.disconnect();
    if (window.Plotly) window.Plotly.purge(this.el);
  }
}
