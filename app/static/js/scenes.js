// The teaching scenes (GET /api/scenes, catalogue/scenes.yaml): a card with a thumbnail per
// scene; Play draws what the scene claims, as its checks measured it, then computes the
// animation (POST /api/scene) and plays it with the explorer's Scene class. Every plot has
// a time cursor that moves with the 3D view; a bar under the view plays, pauses, steps and
// sets the speed; sliders change the physics and run the scene and all its checks again
// (POST /api/scenes/{id}/run); a presentation mode (button, or ?present=1) sizes all text
// for a projector; "Open in the simulator" carries the run to its case page.
// /scenes#ID opens scene ID and plays it at once (the home page links there); v.NAME=value
// in the query moves slider NAME before the scene plays. A scene with a body beside (marble
// against rubber) plays both runs side by side in one time (scene_pair.js).
"use strict";

import { api, escapeHtml } from "./api.js";
import { runQuery } from "./permalink.js";
import { plotClaim, purge } from "./plots.js";
import { Scene } from "./scene.js";
import { ScenePair } from "./scene_pair.js";
import { claimFonts, TimeCursor } from "./scene_cursors.js";
import { thumbnail } from "./scene_thumbs.js";

let current = null;
let presets = [];
let cursors = [];
let present = false;
const $ = (id) => document.getElementById(id);

// a parameter's name as TeX: I1 -> I_1, delta -> \delta
const GREEK = { delta: "\\delta", rho: "\\rho", omega: "\\omega" };
const texName = (k) => GREEK[k] || k.replace(/^([A-Za-z]+)(\d+)$/, "$1_$2");

// a place for TeX in markup; typeset() renders it once the markup is in the page (KaTeX's
// render sets its styles through the DOM, which the strict CSP allows; style attributes in
// markup it would block)
function tex(src) {
  return `<span class="tex" data-tex="${escapeHtml(src)}">${escapeHtml(src)}</span>`;
}

function typeset(root) {
  if (!window.katex) return;
  for (const el of root.querySelectorAll("span.tex[data-tex]")) {
    window.katex.render(el.dataset.tex, el, { throwOnError: false });
  }
}

function card(s) {
  const el = document.createElement("article");
  el.className = "scene-card";
  el.id = `card-${s.id}`;
  el.innerHTML = `${thumbnail(s)}
    <div class="scene-card-text"><h3>${escapeHtml(s.title)}</h3>
    <p>${escapeHtml(s.sentence || s.claim)}</p>
    <a class="button play-link" href="#${s.id}" data-scene="${s.id}">Play</a></div>`;
  return el;
}

let playToken = 0;

// the values of the sliders now on the page, or those of a link (?v.NAME=value)
function sliderValues() {
  const out = {};
  for (const el of $("scene-sliders").querySelectorAll("input[type=range]")) {
    if (el.value !== el.dataset.preset) out[el.name] = Number(el.value);
  }
  return out;
}

function queryValues() {
  const out = {};
  for (const [k, v] of new URLSearchParams(location.search)) {
    if (k.startsWith("v.") && v !== "" && Number.isFinite(Number(v))) out[k.slice(2)] = Number(v);
  }
  return out;
}

function setQuery(values) {
  const q = new URLSearchParams(location.search);
  for (const k of [...q.keys()]) if (k.startsWith("v.")) q.delete(k);
  for (const [k, v] of Object.entries(values)) q.set(`v.${k}`, String(v));
  if (present) q.set("present", "1"); else q.delete("present");
  const qs = q.toString();
  history.replaceState(null, "", `${location.pathname}${qs ? `?${qs}` : ""}${location.hash}`);
}

function renderSliders(s, values) {
  const form = $("scene-sliders");
  form.innerHTML = (s.sliders || []).map((sl) => {
    const now = (sl.param ? s.scene.params[sl.param] : s.scene.state[sl.state]) / sl.factor;
    const v = values[sl.name] !== undefined ? values[sl.name] : now;
    const id = `slider-${sl.name}`;
    return `<div class="scene-slider"><label for="${id}">${escapeHtml(sl.label)},
      ${tex(sl.symbol)}</label>
      <input type="range" id="${id}" name="${escapeHtml(sl.name)}" min="${sl.min}" max="${sl.max}"
        step="any" value="${v}" data-preset="${now}" data-step="${sl.step}">
      <output for="${id}" data-testid="slider-value">${fmt(v)} ${escapeHtml(sl.units)}</output></div>`;
  }).join("") + ((s.sliders || []).length ? `<button type="button" id="slider-reset">Back to the preset</button>` : "");
  typeset(form);
  for (const el of form.querySelectorAll("input[type=range]")) {
    const sl = s.sliders.find((x) => x.name === el.name);
    // the browser's own steps would not reach the preset's value: snap while dragging
    el.addEventListener("input", () => {
      const v = Number(el.value), st = Number(el.dataset.step);
      const snapped = Math.abs(v - Number(el.dataset.preset)) < st / 2 ? Number(el.dataset.preset)
        : Math.round((v - sl.min) / st) * st + sl.min;
      el.value = String(Math.min(sl.max, Math.max(sl.min, Number(snapped.toFixed(6)))));
      el.nextElementSibling.textContent = `${fmt(Number(el.value))} ${sl.units}`;
    });
    el.addEventListener("change", () => play(s.id, sliderValues()));
  }
  const reset = $("slider-reset");
  if (reset) reset.addEventListener("click", () => { renderSliders(s, {}); play(s.id, {}); });
}

function fmt(v) {
  return Number(v).toFixed(Math.abs(v) >= 10 ? 1 : 2).replace(/\.?0+$/, "") || "0";
}

function paramLine(sc) {
  return Object.entries(sc.params).map(([k, v]) => `${tex(`${texName(k)} = ${Number(v.toPrecision(6))}`)}`).join(", ");
}

function simulatorHref(sc) {
  return `/case/${sc.case}?${runQuery({ params: sc.params, state: sc.state, t_end: sc.t_end,
    samples: sc.samples })}`;
}

// One check's figure: its title and verdict, the plot of the data the verdict was taken
// from, the plot's time cursor, what to look for.
async function drawCheck(box, d) {
  const fig = document.createElement("figure");
  fig.className = "claim";
  fig.dataset.kind = d.kind;
  fig.innerHTML = `<figcaption><strong class="claim-title">${escapeHtml(d.plot ? d.plot.title : d.kind)}</strong>
    <span class="verdict ${d.passed ? "pass" : "fail"}" data-testid="verdict">${d.passed ? "✓" : "✗"} ${escapeHtml(d.plot ? d.plot.headline : "")}</span></figcaption>
    <div class="claim-wrap"><div class="claim-plot" data-testid="claim-plot" data-kind="${escapeHtml(d.kind)}"></div></div>
    <p class="caption">${escapeHtml(d.caption)}</p>
    <details><summary>What the check measured</summary><p class="status">${escapeHtml(d.detail)}</p></details>`;
  box.appendChild(fig);
  if (!d.plot) return;
  const el = fig.querySelector(".claim-plot");
  await plotClaim(el, d.plot);
  if (present) await claimFonts(el, true);
  const c = new TimeCursor(el, d.plot.cursor);
  cursors.push(c);
  c.at(current ? current.d.t[current.frame] : 0);
  // a redraw (a resized window, the presentation's fonts) moves the plot area
  el.on("plotly_afterplot", () => c.at(c.t));
}

function clearChecks() {
  const box = $("scene-checks");
  cursors.forEach((c) => c.remove());
  cursors = [];
  box.querySelectorAll(".claim-plot").forEach((el) => purge(el));
  box.innerHTML = "";
  return box;
}

// The claim first, from the data its check measured (GET /api/scenes/{id}/checks/{k} for the
// preset, all checks of the moved run at once from POST /api/scenes/{id}/run), one plot per
// check; the 3D animation's data fetched beside them and drawn after the first plot, so the
// first plot never waits for the 3D.
async function play(id, values = {}) {
  const s = presets.find((p) => p.id === id);
  if (!s) return;
  const token = ++playToken;
  const live = () => token === playToken;
  const moved = Object.keys(values).length > 0;
  performance.clearMarks();
  performance.mark("scene:play");
  $("player").hidden = false;
  $("h-player").textContent = s.title;
  $("scene-claim").textContent = s.claim;
  $("scene-sentence").textContent = s.sentence || s.claim;
  if (!$("scene-sliders").dataset.scene || $("scene-sliders").dataset.scene !== id) {
    renderSliders(s, values);
    $("scene-sliders").dataset.scene = id;
  }
  setQuery(values);
  setStatus("");
  if (current) current.destroy();
  current = null;
  for (const k of ["playing", "drawn", "claimed", "rerun"]) delete document.body.dataset[k];
  const box = clearChecks();
  if (!moved) $("player").scrollIntoView({ block: "start" });
  let sc = s.scene, checks = null;
  if (moved) {
    $("claim-progress").textContent = "Running the scene again with the sliders' values and checking the claim…";
    try {
      const r = await api(`/api/scenes/${encodeURIComponent(s.id)}/run`, { method: "POST", body: { values } });
      if (!live()) return;
      sc = r.scene;
      checks = r.checks;
    } catch (e) {
      if (!live()) return;
      $("claim-progress").textContent = `The run with these values failed: ${e.message}`;
      $("claim-progress").classList.add("error");
      return;
    }
  }
  $("claim-progress").classList.remove("error");
  $("open-sim").href = simulatorHref(sc);
  const besideLine = s.beside ? ` · beside it: <a href="${escapeHtml(simulatorHref({ ...sc, case: s.beside.case }))}">${escapeHtml(s.beside.case)}</a>, the ${escapeHtml(s.beside.label)}` : "";
  $("scene-text").innerHTML = `<p>${escapeHtml(s.explanation)}</p>
    <p class="status">Parameters: ${paramLine(sc)} · ${escapeHtml(sc.case)}${besideLine} · t = 0 … ${sc.t_end}
    · ${escapeHtml((s.paper_numbers || []).join(", "))}</p>`;
  typeset($("scene-text"));
  performance.mark("scene:3d-request");
  const sceneOf = (caseId) => api("/api/scene", { method: "POST", body: {
    case: caseId, params: sc.params, state: sc.state, t_end: sc.t_end, frames: sc.samples,
  } });
  // a body beside: both runs of the same start, drawn side by side
  const data = (s.beside ? Promise.all([sceneOf(sc.case), sceneOf(s.beside.case)])
    : sceneOf(sc.case)).then((d) => { performance.mark("scene:3d-data"); return d; });
  data.catch(() => {});      // a failure is shown by animate(), not as an unhandled rejection
  const n = s.checks.length;
  let anim = null;
  for (let k = 0; k < n; k++) {
    let d;
    if (checks) d = checks[k];
    else {
      $("claim-progress").textContent = `Checking the claim on the scene's run: check ${k + 1} of ${n}…`;
      try {
        d = await api(`/api/scenes/${encodeURIComponent(s.id)}/checks/${k}`);
      } catch (e) {
        if (!live()) return;
        $("claim-progress").textContent = `Check ${k + 1} of ${n} failed: ${e.message}`;
        $("claim-progress").classList.add("error");
        break;
      }
    }
    if (!live()) return;
    await drawCheck(box, d);
    if (!live()) return;
    if (k === 0) {
      performance.mark("scene:first-plot");
      document.body.dataset.claimed = s.id;
      anim = animate(data, live, s);      // the 3D is drawn once the first plot is
    }
  }
  if (!live()) return;
  $("claim-progress").textContent = "";
  if (moved) document.body.dataset.rerun = JSON.stringify(values);
  if (anim) await anim;
}

function setStatus(text, error = false) {
  $("scene-status").textContent = text;
  $("scene-status").classList.toggle("error", error);
}

function onFrame(f, t) {
  $("scrub").value = String(f);
  $("scene-time").textContent = `t = ${t.toFixed(1)}`;
  for (const c of cursors) c.at(t);
}

async function animate(data, live, s) {
  const id = s.id;
  setStatus("Computing the 3D animation…");
  try {
    const got = await data;
    if (!live()) return;
    const runs = s.beside ? got : [got];
    const d = runs[0];
    const span = `Rolling from t = 0 to t = ${d.t[d.t.length - 1].toFixed(0)} (the case's time unit).`;
    const stopped = runs.filter((r) => r.status !== "ok")
      .map((r) => `The run of ${r.case} stopped early (${r.status}): ${r.message}.`).join(" ");
    const note = stopped ? `${stopped} ${span}` : span;
    setStatus("Drawing the 3D view…");
    current = s.beside
      ? new ScenePair($("scene-plot"), runs[0], runs[1], [s.beside.main_label, s.beside.label], { onFrame, present })
      : new Scene($("scene-plot"), d, { onFrame, present });
    current.speed = Number($("speed").value);
    await current.render();
    if (!live()) return;
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

function pause() {
  if (!current) return;
  current.pause();
  $("play").textContent = "Play";
  delete document.body.dataset.playing;
}

async function setPresent(on) {
  present = on;
  document.body.classList.toggle("present", on);
  $("present").setAttribute("aria-pressed", String(on));
  $("present").textContent = on ? "Leave presentation" : "Presentation";
  const q = new URLSearchParams(location.search);
  if (on) q.set("present", "1"); else q.delete("present");
  const qs = q.toString();
  history.replaceState(null, "", `${location.pathname}${qs ? `?${qs}` : ""}${location.hash}`);
  const jobs = [...document.querySelectorAll("#scene-checks .claim-plot")]
    .filter((el) => el.data).map((el) => claimFonts(el, on));
  if (current) jobs.push(current.setPresent(on));
  await Promise.all(jobs);
  // the layout changed size: the plots follow it, then the cursors; the scene at the top
  window.dispatchEvent(new Event("resize"));
  if (!$("player").hidden) $("player").scrollIntoView({ block: "start" });
  document.body.dataset.present = on ? "1" : "0";
}

function controls() {
  $("play").addEventListener("click", () => {
    if (!current) return;
    if (current.playing) pause();
    else {
      current.play();
      $("play").textContent = "Pause";
      document.body.dataset.playing = document.body.dataset.drawn;
    }
  });
  $("step").addEventListener("click", () => { if (current) { pause(); current.stepBy(1); } });
  $("step-back").addEventListener("click", () => { if (current) { pause(); current.stepBy(-1); } });
  $("restart").addEventListener("click", () => { if (current) { pause(); current.show(0); } });
  $("speed").addEventListener("change", () => { if (current) current.speed = Number($("speed").value); });
  $("scrub").addEventListener("input", () => {
    if (!current) return;
    pause();
    current.show(Number($("scrub").value));
  });
  $("present").addEventListener("click", () => setPresent(!present));
  $("fullscreen").addEventListener("click", () => {
    if (document.fullscreenElement) document.exitFullscreen();
    else $("player").requestFullscreen().catch((e) => setStatus(`Full screen refused: ${e.message}`, true));
  });
  document.addEventListener("fullscreenchange", () => {
    $("fullscreen").textContent = document.fullscreenElement ? "Leave full screen" : "Full screen";
    window.dispatchEvent(new Event("resize"));
  });
}

function route() {
  const id = decodeURIComponent(location.hash.slice(1));
  if (id) play(id, queryValues());
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
  controls();
  if (new URLSearchParams(location.search).get("present") === "1") await setPresent(true);
  window.addEventListener("hashchange", () => {
    // another scene: its own sliders, at its preset
    delete $("scene-sliders").dataset.scene;
    setQuery({});
    route();
  });
  route();
}

main();
