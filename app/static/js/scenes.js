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
    $("scrub").max = String(d.t.length - 1);
    current.play();
    $("play").textContent = "Pause";
    document.body.dataset.playing = s.id;
  } catch (e) {
    $("scene-status").textContent = `The scene failed: ${e.message}`;
    $("scene-status").classList.add("error");
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
