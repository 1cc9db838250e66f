// A case's page (/case/<id>, a permalink): the case in the table, every claim with its
// printed formula, source and verdict, and a simulate panel with plots and a 3D scene; a
// rubber case (beyond the 2002 paper) also its rubber cells and plots (case_rubber.js).
"use strict";

import { api, ApiError, download, escapeHtml, fmt } from "./api.js";
import { plotDrift, plotGamma, plotState } from "./plots.js";
import { applyRunQuery, runQuery, setQuery } from "./permalink.js";
import { csvOf, fileStem as runFileStem } from "./run_csv.js";
import { estimate } from "./estimate.js";
import { kernelSentence, runLabel } from "./kernels.js";
import { Scene } from "./scene.js";
import { glossary, tipHtml } from "./glossary.js";
import { $, C, setCase } from "./case_state.js";
import { followChecking, reverify, showCells, showClaims, showHead } from "./case_claims.js";
import { isRubber, plotRubber, showRubber } from "./case_rubber.js";

const caseId = decodeURIComponent(location.pathname.replace(/^\/case\//, "").replace(/\/$/, ""));
const PRETTY = { g1: "γ₁", g2: "γ₂", g3: "γ₃", M1: "M₁", M2: "M₂", M3: "M₃", r1: "r₁", r2: "r₂",
  mu: "μ", lambda: "λ", eps: "ε" };
const RUN_DEFAULTS = { t_end: "100", samples: "801", rtol: "1e-10", atol: "1e-12", step: "0.1" };

let SYMMETRIC = new Set();  // methods of kind "symmetric" (GET /api/methods): they take a step
let limits = { deadline_s: 20, max_samples: 20000, max_frames: 600 };
let lastRun = null;    // {request, result}
let scene = null;
let running = null;    // AbortController of the run in flight

function katexReady() {
  return new Promise((resolve) => {
    if (window.katex) return resolve();
    document.querySelector('script[src*="katex"]').addEventListener("load", () => resolve());
  });
}

// ---------------------------------------------------------------- the simulate form

function inputHtml(name, value, { placeholder = "", title = "", group } = {}) {
  const label = PRETTY[name] || name;
  return `<span class="field"><label title="${escapeHtml(title)}"><span class="nm">${escapeHtml(label)}</span>` +
    `<input id="f-${group}-${name}" data-group="${group}" data-name="${escapeHtml(name)}" value="${escapeHtml(value)}" ` +
    `placeholder="${escapeHtml(placeholder)}" inputmode="decimal" autocomplete="off" spellcheck="false"></label>${tipHtml(name)}</span>`;
}

let GLOSSARY = {};
// what to enter in an empty required field: the glossary's valid range
const whatToEnter = (name) => (GLOSSARY[name] ? `enter ${name}: ${GLOSSARY[name].range}` : `enter a number for ${name}`);

function buildForm() {
  const R = C.runnable;
  $("params").innerHTML = R.params.map((p) => {
    const v = p.example ?? "";
    const placeholder = p.required ? whatToEnter(p.name) : p.default === null ? "= I1" : String(p.default);
    const title = p.required ? `${p.name} (required)` : `${p.name} (optional, default ${p.default ?? "I1"})`;
    return inputHtml(p.name, v === "" ? "" : String(v), { placeholder, title, group: "p" });
  }).join("");
  const fixed = R.fixed_k ? ` k is fixed by the case (k = ${R.fixed_k}).` : "";
  $("params-hint").textContent = `Defaults are the case's example.${fixed} ` +
    "Optional parameters left empty take their default.";
  $("state").innerHTML = R.state_labels.map((l, i) => inputHtml(l, String(R.state[i]), { group: "s" })).join("");
  $("state-hint").innerHTML = R.state_labels.length === 6
    ? `γ: unit normal at the contact point, from the body into the support; <span id="gnorm"></span> <button type="button" class="small" id="normalise">normalise γ</button>`
    : "(M, r₁, r₂): γ = e₃ is fixed; r = (r₁, r₂, z) is the contact point on the flat base.";
  for (const [k, v] of Object.entries(RUN_DEFAULTS)) $(`f-${k}`).value = v;
  const nb = $("normalise");
  if (nb) nb.addEventListener("click", normaliseGamma);
}

function readNumber(el, errors) {
  const raw = el.value.trim();
  if (raw === "") return undefined;
  const x = Number(raw);
  if (!Number.isFinite(x)) {
    errors.push({ el, msg: `${el.dataset.name || el.name} = ${raw}: must be a finite number` });
    return undefined;
  }
  return x;
}

function gatherRequest() {
  const errors = [];
  const params = {};
  for (const el of document.querySelectorAll('input[data-group="p"]')) {
    const x = readNumber(el, errors);
    if (x !== undefined) params[el.dataset.name] = x;
    else if (el.value.trim() === "" && C.runnable.params.find((p) => p.name === el.dataset.name).required) {
      errors.push({ el, msg: `${el.dataset.name} is required: ${whatToEnter(el.dataset.name)}` });
    }
  }
  const state = [];
  for (const el of document.querySelectorAll('input[data-group="s"]')) {
    const x = readNumber(el, errors);
    if (x === undefined && el.value.trim() === "") errors.push({ el, msg: `${el.dataset.name} is required: ${whatToEnter(el.dataset.name)}` });
    state.push(x);
  }
  const num = (id, name) => {
    const el = $(id);
    el.dataset.name = name;
    const x = readNumber(el, errors);
    if (x === undefined && el.value.trim() === "") errors.push({ el, msg: `${name} is required` });
    return x;
  };
  const req = {
    case: C.id, params, state,
    t_end: num("f-t_end", "t_end"), samples: num("f-samples", "samples"),
    rtol: num("f-rtol", "rtol"), atol: num("f-atol", "atol"),
    method: $("f-method").value, project: $("f-project").checked,
  };
  // a symmetric method (Gauss collocation) runs with a constant step instead of tolerances
  const symmetric = SYMMETRIC.has(req.method);
  $("l-rtol").hidden = $("l-atol").hidden = symmetric;
  $("l-step").hidden = !symmetric;
  $("f-project").disabled = symmetric;
  if (symmetric) {
    delete req.rtol;
    delete req.atol;
    req.project = false;
    req.step = num("f-step", "step");
    if (req.step !== undefined && !(req.step > 0)) errors.push({ el: $("f-step"), msg: `step = ${req.step}: must be positive` });
  }
  // the simple checks, mirrored here so that most mistakes show before any request
  if (req.t_end !== undefined && !(req.t_end > 0)) errors.push({ el: $("f-t_end"), msg: `t_end = ${req.t_end}: must be positive` });
  if (req.samples !== undefined && !(Number.isInteger(req.samples) && req.samples >= 2 && req.samples <= limits.max_samples)) {
    errors.push({ el: $("f-samples"), msg: `samples = ${req.samples}: must be an integer in [2, ${limits.max_samples}]` });
  }
  if (req.rtol !== undefined && !(req.rtol >= 1e-16 && req.rtol <= 0.1)) errors.push({ el: $("f-rtol"), msg: `rtol = ${req.rtol}: must lie in [1e-16, 0.1]` });
  if (req.atol !== undefined && !(req.atol > 0 && req.atol <= 1)) errors.push({ el: $("f-atol"), msg: `atol = ${req.atol}: must lie in (0, 1]` });
  if (params.m !== undefined && !(params.m > 0)) errors.push({ el: $("f-p-m"), msg: `m = ${params.m}: must be positive` });
  if (state.length === 6 && state.every((x) => x !== undefined)) {
    const n = Math.hypot(state[3], state[4], state[5]);
    const g = $("gnorm");
    if (g) g.textContent = `now |γ| = ${n.toPrecision(12)}.`;
    if (Math.abs(n - 1) > 1e-9) {
      errors.push({ el: $("f-s-g1"), msg: `|γ| = ${n.toPrecision(6)}: γ is a unit vector, |γ| must be 1 (press “normalise γ”)` });
    }
  }
  return { req, errors };
}

function normaliseGamma() {
  const els = ["g1", "g2", "g3"].map((n) => $(`f-s-${n}`));
  const g = els.map((e) => Number(e.value));
  const n = Math.hypot(...g);
  if (!(n > 0) || !Number.isFinite(n)) return;
  els.forEach((e, i) => { e.value = String(g[i] / n); });
  onEdit();
}

function fieldFor(loc) {
  const [, a, b] = loc;
  if (a === "params" && b !== undefined) return $(`f-p-${b}`);
  if (a === "state") return typeof b === "number" ? document.querySelectorAll('input[data-group="s"]')[b] : $("f-s-g1") || $("f-s-M1");
  if (a) return $(`f-${a}`);
  return null;
}

function showFormMessage(text, kind, el) {
  const msg = $("formmsg");
  msg.textContent = text;
  msg.className = `formmsg ${kind}`;
  for (const i of document.querySelectorAll("#simform input")) i.removeAttribute("aria-invalid");
  if (el) {
    el.setAttribute("aria-invalid", "true");
    el.setAttribute("aria-describedby", "formmsg");
  }
}

let validateTimer = null;
let validateCtl = null;

let pilotGeneration = 0;

function onEdit() {
  // every edit supersedes any pending or in-flight server check: a late answer about an
  // older form must not clear the message about this one
  clearTimeout(validateTimer);
  if (validateCtl) validateCtl.abort();
  const { req, errors } = gatherRequest();
  $("plots").classList.toggle("stale", errors.length > 0 || lastRun !== null);
  $("estimate").textContent = "";
  pilotGeneration++;
  if (errors.length) {
    showFormMessage(errors[0].msg, "bad", errors[0].el);
    return;
  }
  showFormMessage("", "", null);
  clearTimeout(validateTimer);
  validateTimer = setTimeout(async () => {
    if (validateCtl) validateCtl.abort();
    validateCtl = new AbortController();
    try {
      const v = await api("/api/validate", { method: "POST", body: req, signal: validateCtl.signal });
      showFormMessage(`✓ valid — reports ${(v.invariants_text || v.invariants).join(", ")}`, "good", null);
      // the pilot is not aborted by a later edit (a short run; aborting counts as a
      // cancellation on the server): a late answer about an older form is dropped instead
      const mine = ++pilotGeneration;
      const e = await estimate(req, limits).catch(() => ({ level: "info", text: "" }));
      if (mine !== pilotGeneration) return;
      $("estimate").textContent = e.text;
      $("estimate").className = `estimate ${e.level}`;
    } catch (err) {
      if (err.name === "AbortError") return;
      if (err instanceof ApiError && err.status === 422) {
        showFormMessage(err.message, "bad", fieldFor((err.errors[0] || {}).loc || []));
      }
    }
  }, 250);
}

function resetForm() {
  buildForm();
  $("f-method").value = "dop853";
  $("f-project").checked = false;
  onEdit();
}

// ---------------------------------------------------------------- running

function setRunning(on) {
  $("plots").classList.toggle("stale", on);     // the plots shown are of the previous run
  $("run").disabled = on;
  $("scene-btn").disabled = on;
  $("progress").hidden = !on;
}

async function withProgress(label, fn) {
  const ctl = new AbortController();
  running = ctl;
  const t0 = performance.now();
  setRunning(true);
  $("progress").hidden = true;
  const tick = setInterval(() => {
    const s = (performance.now() - t0) / 1000;
    if (s > 0.8) $("progress").hidden = false;   // runs over a second show progress
    $("progress-text").textContent = `${label}: ${s.toFixed(1)} s (limit ${limits.deadline_s} s per run)`;
  }, 100);
  try {
    for (let attempt = 0; ; attempt++) {
      try {
        return await fn(ctl.signal);
      } catch (err) {
        if (err instanceof ApiError && err.status === 503 && attempt < 5) {
          const wait = Number(err.retryAfter || 2);
          $("progress").hidden = false;
          $("progress-text").textContent = `server busy, retrying in ${wait} s…`;
          await new Promise((r) => setTimeout(r, wait * 1000));
          if (ctl.signal.aborted) throw new DOMException("aborted", "AbortError");
          continue;
        }
        throw err;
      }
    }
  } finally {
    clearInterval(tick);
    running = null;
    setRunning(false);
  }
}

function runInfo(res, seconds) {
  const s = res.stats;
  const drift = Object.entries(s.drift || {}).map(([k, v]) => `${k} ${fmt(v, 2)}`).join(", ");
  const st = `<span class="st-${res.status}">${res.status}</span>`;
  const msg = res.status !== "ok" ? ` — ${escapeHtml(res.message)}` : "";
  const knob = s.step !== undefined ? `step ${fmt(s.step, 1)}` : `rtol ${fmt(s.rtol, 1)} · atol ${fmt(s.atol, 1)}`;
  return `${st}${msg}<br>${escapeHtml(s.method)} · ${knob} · ` +
    `${s.steps} steps · ${s.rhs_calls} field evaluations · integration ${fmt(s.wall_s * 1000, 3)} ms · ` +
    `round trip ${fmt(seconds, 3)} s${s.projected ? " · projected" : ""}<br>max relative drift: ${escapeHtml(drift)}`;
}

async function runSimulation(ev) {
  ev.preventDefault();
  const { req, errors } = gatherRequest();
  if (errors.length) {
    showFormMessage(errors[0].msg, "bad", errors[0].el);
    errors[0].el.focus();
    return;
  }
  const t0 = performance.now();
  // performance marks (the browser's timeline): the click, the answer, each plot drawn
  performance.clearMarks();
  performance.mark("run:click");
  try {
    const label = await runLabel("/api/simulate", req, "running");
    const res = await withProgress(label, (signal) => api("/api/simulate", { method: "POST", body: req, signal }));
    const secs = (performance.now() - t0) / 1000;
    performance.mark("run:data");
    lastRun = { request: req, result: res };
    setQuery(runQuery(req));              // the address is now this run's permalink
    $("permalink").href = location.href;
    $("runinfo").innerHTML = runInfo(res, secs);
    $("downloads").hidden = false;
    await showPlots(res);
    document.body.dataset.run = String(Number(document.body.dataset.run || 0) + 1);
  } catch (err) {
    if (err.name === "AbortError") {
      $("runinfo").textContent = "Cancelled: the server stopped the computation.";
    } else if (err instanceof ApiError && err.status === 422) {
      showFormMessage(err.message, "bad", fieldFor((err.errors[0] || {}).loc || []));
      $("runinfo").textContent = "";
    } else {
      $("runinfo").innerHTML = `<span class="error">Run failed: ${escapeHtml(err.message)}</span>`;
    }
  }
}

async function showPlots(res) {
  const plots = $("plots");
  if (!$("plot-state")) {
    plots.innerHTML = '<div class="plot" id="plot-state"></div><div class="plot" id="plot-drift"></div>' +
      '<div class="plot full" id="plot-gamma"></div>';
  }
  await plotState($("plot-state"), res);
  performance.mark("run:first-plot");
  await plotDrift($("plot-drift"), res);
  await plotGamma($("plot-gamma"), res);
  if (isRubber()) {
    try {
      await plotRubber(res, lastRun.request);
    } catch (err) {
      $("runinfo").insertAdjacentHTML("beforeend", `<br><span class="error">The rubber plots failed: ${escapeHtml(err.message)}</span>`);
    }
  }
  performance.mark("run:plots");
}

function fileStem() {
  return runFileStem(lastRun.result, C.id, lastRun.request.t_end);
}

async function runScene() {
  const { req, errors } = gatherRequest();
  if (errors.length) {
    showFormMessage(errors[0].msg, "bad", errors[0].el);
    return;
  }
  const frames = Math.max(2, Math.min(limits.max_frames, Math.round(Number($("f-frames").value) || 200)));
  $("scene-msg").textContent = "";
  try {
    const label = await runLabel("/api/scene", { ...req, frames }, "computing the scene");
    const d = await withProgress(label, (signal) =>
      api("/api/scene", { method: "POST", body: { ...req, frames }, signal }));
    if (scene) scene.destroy();
    const el = $("plot-scene");
    el.hidden = false;
    const ck = d.checks;
    $("scene-msg").textContent = (d.status !== "ok" ? `${d.status}: ${d.message}. ` : "") +
      `${d.t.length} frames; checks: |QᵀQ − E| ≤ ${fmt(ck.orthogonality, 1)}, contact point off the support ≤ ${fmt(ck.contact_on_support, 1)}.`;
    scene = new Scene(el, d, {
      onFrame: (f, t) => {
        $("scrub").value = String(f);
        $("scene-time").textContent = `t = ${t.toFixed(3)}`;
      },
    });
    await scene.render();
    $("scrub").max = String(d.t.length - 1);
    $("scrub").hidden = false;
    $("play").hidden = false;
    $("play").textContent = "Play";
    document.body.dataset.scene = "1";
  } catch (err) {
    if (err.name === "AbortError") $("scene-msg").textContent = "Cancelled.";
    else $("scene-msg").textContent = `Scene failed: ${err.message}`;
  }
}

// ---------------------------------------------------------------- kernels

let kernels = null;   // GET /api/health's kernels at load

// "kernels: k of n compiled; a run of this case compiles its kernel before it starts", while
// the server's background warm-up runs (refreshed until it is done)
function showKernels(k) {
  $("kernel-status").textContent = kernelSentence(k, caseId);
  if (k && ["starting", "running"].includes(k.state)) {
    setTimeout(async () => {
      try {
        showKernels((await api("/api/health")).kernels);
      } catch {
        // keep the last sentence
      }
    }, 5000);
  }
}

// ---------------------------------------------------------------- start

async function main() {
  await katexReady();
  try {
    const [c, h, methods, g] = await Promise.all([
      api(`/api/cases/${caseId}`), api("/api/health"), api("/api/methods"), glossary()]);
    GLOSSARY = g;
    setCase(c);
    limits = h.limits;
    kernels = h.kernels;
    SYMMETRIC = new Set(methods.filter((m) => m.kind === "symmetric").map((m) => m.name));
    const group = (kind, label) => `<optgroup label="${label}">` + methods.filter((m) => m.kind === kind)
      .map((m) => `<option value="${m.name}">${m.name}</option>`).join("") + "</optgroup>";
    $("f-method").innerHTML = group("auto", "chosen from the measured front") +
      group("compiled", "compiled Runge–Kutta") + group("taylor", "Taylor (heyoka)") +
      group("symmetric", "symmetric, constant step (Gauss)") + group("scipy reference", "scipy reference");
  } catch (err) {
    $("case-title").textContent = "Could not load the case";
    $("facts").innerHTML = `<p class="error" role="alert">${escapeHtml(err.message)}</p>`;
    return;
  }
  showHead();
  showCells();
  if (isRubber()) showRubber();
  showClaims();
  resetForm();
  showKernels(kernels);
  $("simform").addEventListener("input", onEdit);
  $("simform").addEventListener("change", onEdit);
  $("simform").addEventListener("submit", runSimulation);
  $("reset").addEventListener("click", resetForm);
  $("cancel").addEventListener("click", () => running && running.abort());
  $("reverify").addEventListener("click", reverify);
  $("dl-csv").addEventListener("click", async () => download(`${fileStem()}.csv`, csvOf(lastRun.result), "text/csv"));
  $("dl-json").addEventListener("click", () => download(`${fileStem()}.json`,
    JSON.stringify({ request: lastRun.request, ...lastRun.result }, null, 1), "application/json"));
  $("scene-btn").addEventListener("click", runScene);
  $("play").addEventListener("click", () => {
    if (!scene) return;
    if (scene.playing) { scene.pause(); $("play").textContent = "Play"; } else { scene.play(); $("play").textContent = "Pause"; }
  });
  $("scrub").addEventListener("input", () => {
    if (!scene) return;
    scene.pause();
    $("play").textContent = "Play";
    scene.show(Number($("scrub").value));
  });
  if (location.hash) document.getElementById(location.hash.slice(1))?.scrollIntoView();
  document.body.dataset.ready = "1";
  followChecking();
  if (applyRunQuery(location.search, $)) {   // a permalink of a run: reproduce it
    onEdit();
    $("simform").requestSubmit();
  }
}

main();
