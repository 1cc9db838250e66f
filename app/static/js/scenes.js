// The teaching scenes (GET /api/scenes, catalogue/scenes.yaml): a card per scene; Play
// draws what the scene claims, as its checks measured it, then computes the animation
// (POST /api/scene) and plays it with the explorer's Scene class.
// /scenes#ID opens scene ID and plays it at once (the home page links there).
"use strict";

import { api, escapeHtml } from "./api.js";
import { plotClaim, purge } from "./plots.js";
import { Scene } from "./scene.js";

let current = null;
let presets = [];
const $ = (id) => document.getElementById(id);

function card(s) {
  const el = document.createElement("article");
  el.className = "scene-card";
  el.id = `card-${s.id}`;
  el.innerHTML = `<h3>${escapeHtml(s.title)}</h3>
    <p>${escapeHtml(s.explanation)}</p>
    <p><strong>Shows:</strong> ${escapeHtml(s.claim)}</p>
    <p class="status">${escapeHtml(s.scene.case)} · t = 0 … ${s.scene.t_end} · ${escapeHtml((s.paper_numbers || []).join(", "))}</p>
    <a class="button" href="#${s.id}" data-scene="${s.id}">Play</a>`;
  return el;
}

let playToken = 0;

// The claim first, from the data its check measured (GET /api/scenes/{id}/checks/{k}),
// one plot per check as each arrives; the 3D animation's data fetched beside them and
// drawn after the first plot, so the first plot never waits for the 3D.
async function play(id) {
  const s = presets.find((p) => p.id === id);
  if (!s) return;
  const token = ++playToken;
  const live = () => token === playToken;
  // performance marks (the browser's timeline): from the click to the 3D view
  performance.clearMarks();
  performance.mark("scene:play");
  $("player").hidden = false;
  $("h-player").textContent = s.title;
  $("scene-claim").textContent = s.claim;
  $("scene-text").innerHTML = `<p>${escapeHtml(s.explanation)}</p>
    <p class="status">Parameters: ${escapeHtml(Object.entries(s.scene.params).map(([k, v]) => `${k} = ${v}`).join(", "))}
    · ${escapeHtml(s.scene.case)} · t = 0 … ${s.scene.t_end} · ${escapeHtml((s.paper_numbers || []).join(", "))}</p>`;
  setStatus("");
  if (current) current.destroy();
  current = null;
  delete document.body.dataset.playing;
  delete document.body.dataset.drawn;
  delete document.body.dataset.claimed;
  const box = $("scene-checks");
  box.querySelectorAll(".claim-plot").forEach((el) => purge(el));
  box.innerHTML = "";
  $("player").scrollIntoView({ block: "start" });
  const n = s.checks.length;
  let anim = null;
  // the animation's data is asked for at once, beside the checks (the checks are kept by
  // the server, the scene is computed by a worker); it is drawn after the first plot
  const sc = s.scene;
  performance.mark("scene:3d-request");
  const data = api("/api/scene", { method: "POST", body: {
    case: sc.case, params: sc.params, state: sc.state, t_end: sc.t_end, frames: sc.samples,
  } }).then((d) => { performance.mark("scene:3d-data"); return d; });
  data.catch(() => {});      // a failure is shown by animate(), not as an unhandled rejection
  for (let k = 0; k < n; k++) {
    $("claim-progress").textContent = `Checking the claim on the scene's run: check ${k + 1} of ${n}…`;
    let d;
    try {
      d = await api(`/api/scenes/${encodeURIComponent(s.id)}/checks/${k}`);
    } catch (e) {
      if (!live()) return;
      $("claim-progress").textContent = `Check ${k + 1} of ${n} failed: ${e.message}`;
      $("claim-progress").classList.add("error");
      break;
    }
    if (!live()) return;
    const fig = document.createElement("figure");
    fig.className = "claim";
    fig.dataset.kind = d.kind;
    fig.innerHTML = `<figcaption><strong>${escapeHtml(d.plot ? d.plot.title : d.kind)}</strong>
      <span class="verdict ${d.passed ? "pass" : "fail"}">${d.passed ? "✓" : "✗"} ${escapeHtml(d.plot ? d.plot.headline : "")}</span></figcaption>
      <div class="claim-plot" data-testid="claim-plot" data-kind="${escapeHtml(d.kind)}"></div>
      <p class="caption">${escapeHtml(d.caption)}</p>
      <details><summary>What the check measured</summary><p class="status">${escapeHtml(d.detail)}</p></details>`;
    box.appendChild(fig);
    if (d.plot) await plotClaim(fig.querySelector(".claim-plot"), d.plot);
    if (k === 0) {
      performance.mark("scene:first-plot");
      document.body.dataset.claimed = s.id;
      anim = animate(data, live, s.id);      // the 3D is drawn once the first plot is
    }
  }
  if (live()) $("claim-progress").textContent = "";
  if (anim) await anim;
}

function setStatus(text, error = false) {
  $("scene-status").textContent = text;
  $("scene-status").classList.toggle("error", error);
}

async function animate(data, live, id) {
  setStatus("Computing the 3D animation…");
  try {
    const d = await data;
    if (!live()) return;
    const note = (d.status !== "ok" ? `${d.status}: ${d.message}. ` : "") + `${d.t.length} frames.`;
    // the second stage: the run is here, WebGL draws the body (slow without a GPU)
    setStatus(`Drawing the 3D view (${d.t.length} frames computed)…`);
    current = new Scene($("scene-plot"), d, {
      onFrame: (f, t) => {
        $("scrub").value = String(f);
        $("scene-time").textContent = `t = ${t.toFixed(2)}`;
      },
    });
    await current.render();
    setStatus(note);
    performance.mark("scene:3d-drawn");
    $("scrub").max = String(d.t.length - 1);
    document.body.dataset.drawn = id;
    // it plays at once, unless the reader's system asks for reduced motion (WCAG 2.3.3):
    // then the first frame stands until Play
    if (matchMedia("(prefers-reduced-motion: reduce)").matches) {
      $("play").textContent = "Play";
      setStatus(`${note} Paused at the start (your system asks for reduced motion): Play runs it.`);
      return;
    }
    current.play();
    $("play").textContent = "Pause";
    performance.mark("scene:3d-playing");
    document.body.dataset.playing = id;
  } catch (e) {
    if (live()) setStatus(`The 3D animation failed: ${e.message}`, true);
  }
}

function route() {
  const id = decodeURIComponent(location.hash.slice(1));
  if (id) play(id);
}

async function main() {
  try {
    presets = await api("/api/scenes");
  } catch (e) {
    $("scene-list").innerHTML = `<p class="error">Could not load the scenes: ${escapeHtml(e.message)}</p>`;
    return;
  }
  const list = $("scene-list");
  list.innerHTML = "";
  presets.forEach((s) => list.appendChild(card(s)));
  $("play").addEventListener("click", () => {
    if (!current) return;
    if (current.playing) { current.pause(); $("play").textContent = "Play"; }
    else {
      current.play();
      $("play").textContent = "Pause";
      document.body.dataset.playing = document.body.dataset.drawn;
    }
  });
  $("scrub").addEventListener("input", () => {
    if (!current) return;
    current.pause();
    $("play").textContent = "Play";
    current.show(Number($("scrub").value));
  });
  window.addEventListener("hashchange", route);
  route();
}

main();
