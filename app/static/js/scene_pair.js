// Two bodies rolled side by side in one time (a teaching scene with `beside`: a marble ball
// and a rubber ball from the same start): two 3D views of the explorer's Scene class, each
// with its label, driven by one clock. The pair answers as one Scene does (render, play,
// pause, show, stepBy, speed, setPresent, destroy, frame, d), so /scenes' play bar, time
// cursors and presentation mode work on it unchanged.
"use strict";

import { Scene } from "./scene.js";

export class ScenePair {
  // el: the view's element; a, b: POST /api/scene answers of the two runs; labels: their names
  constructor(el, a, b, labels, { onFrame, present = false } = {}) {
    this.el = el;
    el.classList.add("pair");
    el.innerHTML = "";
    const half = (label, side) => {
      const box = document.createElement("div");
      box.className = "pair-half";
      box.dataset.side = side;
      const cap = document.createElement("p");
      cap.className = "pair-label";
      cap.dataset.testid = "pair-label";
      cap.textContent = label;
      const view = document.createElement("div");
      view.className = "pair-view";
      box.append(cap, view);
      el.appendChild(box);
      return view;
    };
    const left = half(labels[0], "main"), right = half(labels[1], "beside");
    // the second view follows the first: one frame index for both (same output times; a
    // run that stopped early stands at its last frame)
    this.b = new Scene(right, b, { present });
    this.a = new Scene(left, a, { present, onFrame: (f, t) => {
      this.b.show(Math.min(f, b.t.length - 1));
      (onFrame || (() => {}))(f, t);
    } });
  }

  get d() { return this.a.d; }
  get frame() { return this.a.frame; }
  get playing() { return this.a.playing; }
  get speed() { return this.a.speed; }
  set speed(v) { this.a.speed = v; }

  async render() {
    await this.b.render();
    await this.a.render();
  }

  play() { this.a.play(); }
  pause() { this.a.pause(); }
  show(f) { this.a.show(f); }
  stepBy(k) { this.a.stepBy(k); }

  async setPresent(on) {
    await this.b.setPresent(on);
    await this.a.setPresent(on);
  }

  destroy() {
    this.a.destroy();
    this.b.destroy();
    this.el.classList.remove("pair");
    this.el.innerHTML = "";
  }
}
