// The teaching scenes (GET /api/scenes, catalogue/scenes.yaml): a card per scene; Play
// computes the animation (POST /api/scene) and plays it with the explorer's Scene class.
// /scenes#ID opens scene ID and plays it at once (the home page links there).
"use strict";

import { api, escapeHtml } from "./api.js";
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

async function play(id) {
  const s = presets.find((p) => p.id === id);
  if (!s) return;
  $("player").hidden = false;
  $("h-player").textContent = s.title;
  $("scene-text").innerHTML = `<p>${escapeHtml(s.explanation)}</p>
    <p><strong>Shows:</strong> ${escapeHtml(s.claim)}</p>
    <p class="status">Parameters: ${escapeHtml(Object.entries(s.scene.params).map(([k, v]) => `${k} = ${v}`).join(", "))}</p>`;
  $("scene-status").classList.remove("error");
  $("scene-status").textContent = "Computing the scene…";
  if (current) current.destroy();
  current = null;
  $("player").scrollIntoView({ behavior: "smooth" });
  try {
    const sc = s.scene;
    const d = await api("/api/scene", { method: "POST", body: {
      case: sc.case, params: sc.params, state: sc.state, t_end: sc.t_end, frames: sc.samples,
    } });
    $("scene-status").textContent = (d.status !== "ok" ? `${d.status}: ${d.message}. ` : "") +
      `${d.t.length} frames.`;
    current = new Scene($("scene-plot"), d, {
      onFrame: (f, t) => {
        $("scrub").value = String(f);
        $("scene-time").textContent = `t = ${t.toFixed(2)}`;
      },
    });
    await current.render();
    await plotSeries(s, d);
    $("scrub").max = String(d.t.length - 1);
    current.play();
    $("play").textContent = "Pause";
    document.body.dataset.playing = s.id;
  } catch (e) {
    $("scene-status").textContent = `The scene failed: ${e.message}`;
    $("scene-status").classList.add("error");
  }
}

// What the scene's text promises, against time, beside the 3D view (scenes.yaml `plot`)
const SERIES = {
  vertical_spin: { title: "Spin about the vertical against time",
    y: "spin −(ω, γ) (1 / time unit; > 0 counterclockwise from above)" },
  tilt: { title: "Tilt of the disk against time",
    y: "sin θ = √(γ₁² + γ₂²), θ axis to vertical" },
};

async function plotSeries(s, d) {
  const el = $("scene-series");
  const ys = s.plot ? (d.series || {})[s.plot] : null;
  el.hidden = !ys;
  if (!ys) { window.Plotly.purge(el); return; }
  const meta = SERIES[s.plot];
  const range = s.plot === "tilt" ? { range: [0, 1.05] } : {};
  const t = d.t.slice(0, ys.length);
  const traces = [{ x: t, y: ys, mode: "lines", name: "per frame", line: { color: "#1f5f99", width: 1.5 } }];
  const rev = (s.checks || []).find((c) => c.kind === "spin_reversal");
  if (s.plot === "vertical_spin" && rev && t.length > 2) {
    // averaged over the check's window, as the spin_reversal check does: the rocking
    // oscillation hides the slow spin that reverses
    const k = Math.max(1, Math.round(rev.window / (t[1] - t[0])));
    const avg = [], ta = [];
    for (let i = 0; i + k <= ys.length; i++) {
      avg.push(ys.slice(i, i + k).reduce((a, b) => a + b, 0) / k);
      ta.push(t[i + Math.floor(k / 2)]);
    }
    traces.push({ x: ta, y: avg, mode: "lines", name: `averaged over ${rev.window} time units`,
      line: { color: "#c2571a", width: 3 } });
  }
  await window.Plotly.react(el, traces, {
    title: { text: meta.title, font: { size: 14 }, x: 0.02 },
    xaxis: { title: { text: "time t (scene's time units)" } },
    yaxis: { title: { text: meta.y }, zeroline: true, ...range },
    margin: { l: 64, r: 12, t: 40, b: 48 }, showlegend: traces.length > 1,
    legend: { orientation: "h", y: -0.3 },
  }, { responsive: true, displaylogo: false });
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
    else { current.play(); $("play").textContent = "Pause"; }
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
