// The 3D point maps page: the paper's Figs. 3, 5, 6 and 7 (static/data/paper_figures.json,
// written by bench/paper_figures.py) and maps computed on demand by POST /api/poincare
// (?stream=true: NDJSON progress events, then the result). The form has one field per
// parameter of the chosen case (GET /api/cases/{id}), filled with the case's example and
// checked against the glossary's range as it is typed; a field left empty takes the
// example (the request says example: true, and the server merges). A map is drawn twice,
// in 3D (L/G, H/G, l) and in 2D (l, L/G), from the same points.
"use strict";

import { api, download, escapeHtml, fmt } from "./api.js";
import { applyFormQuery, csvText, formQuery, scrollToResult, setQuery } from "./permalink.js";
import { LEGEND_BELOW, MODEBAR } from "./plots.js";

let lastMap = null;    // {request, result} of the last map computed here

const CONFIG = { responsive: true, displaylogo: false };
const PALETTE = ["#1f5f99", "#c2571a", "#2a8a3e", "#8e3ea8", "#b8860b", "#0f7f8a", "#c21c2c",
  "#5b6770", "#d6336c", "#3b5bdb", "#66a80f", "#e8590c"];
const FIG_ORDER = ["ris-1", "ris-2", "ris-3", "ris-4"];
// the paper's printed numbers (GET /api/printed-numbers): "ris-*1" -> "Fig. 3"
let NUMBERS = {};
// "(eq-d*2)" -> "(2.29)", not "((2.29))" (as catalogue/numbering.py cite())
const cite = (text) => Object.keys(NUMBERS).sort((a, b) => b.length - a.length)
  .reduce((t, lab) => t.split(`Fig ${lab}`).join(NUMBERS[lab]).split(`(${lab})`).join(NUMBERS[lab])
    .split(lab).join(NUMBERS[lab]), String(text));

const INNER = { tickvals: [-0.5, 0, 0.5], ticktext: ["−0.5", "0", "0.5"] };

function layout3d(title) {
  return {
    title: { text: title, font: { size: 14 }, x: 0.02 },
    autosize: true,
    margin: { l: 0, r: 0, t: 36, b: 0 },
    showlegend: true,
    // the markers are tiny dots on the plot; in the legend they keep a visible size
    legend: { font: { size: 11 }, itemsizing: "constant", ...LEGEND_BELOW },
    modebar: MODEBAR,
    scene: {
      // ticks inside the ranges only: labels at the ends (the -1 of L/G and H/G, the 0 of
      // l) meet at the box's corners, where they ran into each other
      xaxis: { title: { text: "L/G" }, range: [-1, 1], ...INNER },
      yaxis: { title: { text: "H/G" }, range: [-1, 1], ...INNER },
      zaxis: { title: { text: "l" }, range: [0, 2 * Math.PI], tickvals: [Math.PI / 2, Math.PI, 1.5 * Math.PI],
        ticktext: ["π/2", "π", "3π/2"] },
      aspectmode: "cube",
    },
  };
}

function traces(trajectories, size = 1.6) {
  return trajectories.map((t, i) => ({
    type: "scatter3d", mode: "markers", name: `trajectory ${i + 1}`,
    x: t.points.map((p) => p[0]), y: t.points.map((p) => p[1]), z: t.points.map((p) => p[2]),
    marker: { size, color: PALETTE[i % PALETTE.length], opacity: 0.85 },
    hovertemplate: "L/G %{x:.4f}<br>H/G %{y:.4f}<br>l %{z:.4f}<extra></extra>",
  }));
}

async function figures() {
  const status = document.getElementById("fig-status");
  const grid = document.getElementById("fig-grid");
  let data;
  try {
    NUMBERS = await api("/api/printed-numbers").catch(() => ({}));
    const res = await fetch("/static/data/paper_figures.json");
    if (!res.ok) throw new Error(`${res.status} ${res.statusText}`);
    data = (await res.json()).figures;
  } catch (e) {
    status.textContent = `The figure data is missing (run python bench/paper_figures.py): ${e.message}`;
    status.classList.add("error");
    return;
  }
  status.textContent = "";
  for (const key of FIG_ORDER) {
    const f = data[key];
    if (!f) continue;
    const card = document.createElement("article");
    card.className = "fig-card";
    card.id = `fig-${key}`;
    const params = Object.entries(f.params)
      .map(([k, v]) => `${k} = ${v}`).join(", ");
    card.innerHTML = `<h3>${escapeHtml(NUMBERS[key.replace("ris-", "ris-*")] || "Fig.")}: ${escapeHtml(cite(f.title))}</h3>
      <p class="status">${escapeHtml(f.case)}; ${escapeHtml(params)}; E₀ = ${f.energy},
        section g = ${f.section.g0}</p>
      <div class="plot3d" data-testid="plot-${key}"></div>
      <ul class="notes">${f.notes.map((n) => `<li>${escapeHtml(cite(n))}</li>`).join("")}</ul>`;
    grid.appendChild(card);
    later(card.querySelector(".plot3d"), f);
  }
}

// A figure is drawn when it comes near the screen, not on load: each is a 3D scatter of
// many points, and drawing the four one after the other kept a browser without a GPU
// (WebGL in software) busy for seconds after the page had loaded, for figures below the
// fold (and the browser tests open the same page many times). Printing draws them all.
const PENDING = new Map();    // plot element -> its figure, not drawn yet
const NEAR = "IntersectionObserver" in window ? new IntersectionObserver((entries) => {
  for (const e of entries) if (e.isIntersecting) draw(e.target);
}, { rootMargin: "100px 0px" }) : null;

function later(el, f) {
  PENDING.set(el, f);
  if (NEAR) NEAR.observe(el);
  else draw(el);
}

async function draw(el) {
  const f = PENDING.get(el);
  if (!f) return;
  PENDING.delete(el);
  if (NEAR) NEAR.unobserve(el);
  await window.Plotly.newPlot(el, traces(f.trajectories), layout3d(""), CONFIG);
  window.Plotly.Plots.resize(el);
  el.dataset.drawn = "1";
}

window.addEventListener("beforeprint", () => { for (const el of [...PENDING.keys()]) draw(el); });

// the map seen from above the section: each point at (l, L/G), in its trajectory's colour
function traces2d(trajectories) {
  const many = trajectories.reduce((n, t) => n + t.points.length, 0) > 5000;
  return trajectories.map((t, i) => ({
    type: many ? "scattergl" : "scatter", mode: "markers", name: `trajectory ${i + 1}`,
    x: t.points.map((p) => p[2]), y: t.points.map((p) => p[0]),
    marker: { size: 3, color: PALETTE[i % PALETTE.length], opacity: 0.85 },
    hovertemplate: "l %{x:.4f}<br>L/G %{y:.4f}<extra></extra>",
  }));
}

function layout2d(title) {
  const PI = Math.PI;
  return {
    title: { text: title, font: { size: 14 }, x: 0.02 },
    autosize: true,
    margin: { l: 60, r: 40, t: 36, b: 52 },
    showlegend: false,        // the 3D view beside it names the colours
    modebar: MODEBAR,
    // five ticks on l, in multiples of pi/2, and five on L/G: none runs into the next
    xaxis: { title: { text: "l" }, range: [0, 2 * PI], tickvals: [0, PI / 2, PI, 1.5 * PI, 2 * PI],
      ticktext: ["0", "π/2", "π", "3π/2", "2π"], zeroline: false },
    yaxis: { title: { text: "L/G" }, range: [-1.05, 1.05], tickvals: [-1, -0.5, 0, 0.5, 1],
      zeroline: false },
  };
}

// ---- the parameter fields of the chosen case

const RUNNABLE = new Map();    // case id -> the promise of its GET /api/cases/{id} .runnable
let RANGES = {};               // parameter -> its valid range in words (the glossary's)

function runnable(id) {
  if (!RUNNABLE.has(id)) RUNNABLE.set(id, api(`/api/cases/${id}`).then((c) => c.runnable));
  return RUNNABLE.get(id);
}

async function glossary() {
  const g = await api("/api/glossary").catch(() => ({ entries: [] }));
  const entries = Array.isArray(g.entries) ? g.entries : Object.values(g.entries || {});
  RANGES = Object.fromEntries(entries.filter((e) => e.range).map((e) => [e.symbol, e.range]));
}

let building = Promise.resolve();     // the fields of the case chosen last, being built

async function buildParams(id) {
  const R = await runnable(id);
  const box = document.getElementById("param-fields");
  if (document.getElementById("case").value !== id) return;   // a later choice won
  box.innerHTML = R.params.map((p) => {
    const ex = p.example ?? p.default;
    const v = ex === null || ex === undefined ? "" : String(ex);
    // an optional parameter with neither example nor default (I2 of a body of revolution)
    // equals I1 when it is left empty (the API's rule, as on the case page)
    const hint = v === "" && !p.required ? "= I1" : v;
    const range = RANGES[p.name] ? `${p.name}: ${RANGES[p.name]}` : p.name;
    return `<label><span><span class="nm">${escapeHtml(p.name)}</span>` +
      `${p.required ? "" : ' <span class="opt">optional</span>'}</span>` +
      `<input name="p.${escapeHtml(p.name)}" data-param="${escapeHtml(p.name)}" ` +
      `data-example="${escapeHtml(v)}" value="${escapeHtml(v)}" placeholder="${escapeHtml(hint)}" ` +
      `title="${escapeHtml(range)}" inputmode="decimal" autocomplete="off" spellcheck="false" ` +
      `aria-describedby="pm-${escapeHtml(p.name)}">` +
      `<span class="msg" id="pm-${escapeHtml(p.name)}"></span></label>`;
  }).join("");
  box.dataset.case = id;
  checkParams();
}

// what is wrong with the value typed for a parameter ("" when nothing is)
function paramProblem(name, raw) {
  const t = raw.trim();
  if (t === "") return "";
  const x = Number(t);
  if (!Number.isFinite(x)) return `${name}: enter a number (empty: the example)`;
  const range = RANGES[name] || "";
  if (/^>\s*0/.test(range) && !(x > 0)) return `${name} = ${t}: must be positive`;
  if (/^≥\s*0/.test(range) && !(x >= 0)) return `${name} = ${t}: must be ≥ 0`;
  return "";
}

// each field's own message; the moments of inertia also against the triangle inequality.
// The first problem, or "" when the fields can be sent.
function checkParams() {
  const inputs = [...document.querySelectorAll("#param-fields input")];
  const problems = new Map(inputs.map((el) => [el, paramProblem(el.dataset.param, el.value)]));
  const value = (n) => {
    const el = inputs.find((e) => e.dataset.param === n);
    if (!el || problems.get(el)) return null;
    const t = el.value.trim() === "" ? el.dataset.example : el.value.trim();
    return t === "" ? null : Number(t);
  };
  const I = ["I1", "I2", "I3"].map(value);
  if (I.every((x) => x !== null && x > 0)) {
    I.forEach((x, i) => {
      const others = I[(i + 1) % 3] + I[(i + 2) % 3];
      const el = inputs.find((e) => e.dataset.param === `I${i + 1}`);
      if (x > others * (1 + 1e-12) && !problems.get(el)) {
        problems.set(el, `I${i + 1} = ${x} is more than the sum of the other two (${others}): ` +
          "no rigid body has these moments");
      }
    });
  }
  let first = "";
  for (const el of inputs) {
    const msg = problems.get(el);
    document.getElementById(`pm-${el.dataset.param}`).textContent = msg;
    if (msg) el.setAttribute("aria-invalid", "true");
    else el.removeAttribute("aria-invalid");
    if (msg && !first) first = msg;
  }
  return first;
}

function paramValues() {
  const out = {};
  for (const el of document.querySelectorAll("#param-fields input")) {
    if (el.value.trim() !== "") out[el.dataset.param] = Number(el.value.trim());
  }
  return out;
}

// an address written before the fields (?params=I1=1 I2=2): its values into the fields
function legacyParams(text) {
  for (const item of String(text || "").split(/[\s,;]+/).filter(Boolean)) {
    const [k, v] = item.split("=");
    const el = k && document.querySelector(`#param-fields input[data-param="${CSS.escape(k.trim())}"]`);
    if (el && v !== undefined) el.value = v.trim();
  }
}

async function cases() {
  const sel = document.getElementById("case");
  const list = await api("/api/cases");
  for (const c of list.filter((c) => c.body !== "flat" && c.constraint !== "rubber")) {
    const o = document.createElement("option");
    o.value = c.id;
    o.textContent = `${c.id} — ${c.model_title}`;
    sel.appendChild(o);
  }
}

function table(result) {
  const rows = result.trajectories.map((t, i) => {
    const spread = Object.entries(t.spread).map(([k, v]) => `${k} ${fmt(v, 2)}`).join(", ");
    return `<tr><td>${i + 1}</td><td>${t.initial.map((v) => v.toFixed(4)).join(", ")}</td>
      <td>${t.points.length}</td><td>${escapeHtml(t.status)}</td>
      <td>${t.check.missed ?? "—"} / ${t.check.extra ?? "—"}</td><td>${escapeHtml(spread)}</td></tr>`;
  }).join("");
  document.getElementById("map-table").innerHTML = `<table class="maptab"><thead><tr>
    <th>#</th><th>start L/G, H/G, l</th><th>points</th><th>status</th><th>missed / extra</th>
    <th>spread of the integrals on the trajectory</th></tr></thead><tbody>${rows}</tbody></table>`;
}

async function compute(ev) {
  ev.preventDefault();
  const status = document.getElementById("map-status");
  const bar = document.getElementById("progress");
  const button = document.getElementById("run");
  status.classList.remove("error");
  await building;                       // the fields of the case chosen last
  const form = new FormData(ev.target);
  let body;
  try {
    const problem = checkParams();
    if (problem) {
      document.querySelector('#param-fields input[aria-invalid="true"]')?.focus();
      throw new Error(problem);
    }
    const params = paramValues();
    body = {
      case: form.get("case"), energy: Number(form.get("energy")),
      section: `g=${Number(form.get("g0"))}`, direction: Number(form.get("direction")),
      trajectories: Number(form.get("trajectories")), points: Number(form.get("points")),
      rtol: Number(form.get("rtol") || 1e-10),
      // example: true, the server fills every parameter left out with the case's example
      seed: Number(form.get("seed")), params, example: true,
    };
  } catch (e) {
    status.textContent = e.message;
    status.classList.add("error");
    return;
  }
  button.disabled = true;
  bar.hidden = false;
  bar.value = 0;
  status.textContent = "Timing a pilot of the first trajectory…";
  let estimate = null;
  const started = performance.now();
  try {
    const res = await fetch("/api/poincare?stream=true", {
      method: "POST", headers: { "Content-Type": "application/json" }, body: JSON.stringify(body),
    });
    if (!res.ok) {
      const err = await res.json().catch(() => ({}));
      throw new Error(err.detail || `${res.status} ${res.statusText}`);
    }
    const reader = res.body.getReader();
    const decoder = new TextDecoder();
    let buf = "";
    let result = null;
    for (;;) {
      const { value, done } = await reader.read();
      if (value) buf += decoder.decode(value, { stream: true });
      let nl;
      while ((nl = buf.indexOf("\n")) >= 0) {
        const line = buf.slice(0, nl);
        buf = buf.slice(nl + 1);
        if (!line.trim()) continue;
        const ev = JSON.parse(line);
        if (ev.event === "compiling") {
          // the map's kernels compile first (routes/poincare.py: outside its time limit)
          status.textContent = `Compiling the map's kernels (first use on this machine, about ` +
            `${secs(ev.estimate_s)}; not counted in the time limit)…`;
        } else if (ev.event === "estimate") {
          // from a real pilot of this case on this server (routes/poincare.py _pilot)
          estimate = ev.seconds;
          status.textContent = `0 of ${ev.total} trajectories; about ${secs(ev.seconds)} in all` +
            (ev.seconds > ev.deadline ? ` — more than the ${ev.deadline} s a request may take: ` +
              "lower Trajectories or Points, or loosen rtol" : "");
        } else if (ev.event === "progress") {
          bar.max = ev.total;
          bar.value = ev.done;
          if (ev.done > 0) {
            status.textContent = `${ev.done} of ${ev.total} trajectories` +
              (ev.done < ev.total ? `; about ${secs(ev.remaining)} left` : "");
          }
        } else if (ev.event === "error") {
          throw new Error(ev.detail);
        } else if (ev.event === "result") {
          result = ev.result;
        }
      }
      if (done) break;
    }
    if (!result) throw new Error("the answer ended before the result");
    const took = (performance.now() - started) / 1000;
    status.textContent = `${result.trajectories.length} trajectories, ${result.points} points each` +
      ` in ${secs(took)}` + (estimate !== null ? ` (estimated ${secs(estimate)})` : "");
    document.getElementById("map-views").hidden = false;     // empty until the first map
    await window.Plotly.react(document.getElementById("map-plot"), traces(result.trajectories, 2),
      layout3d(`${result.case}, E₀ = ${result.energy}, g = ${result.section.g0}`), CONFIG);
    await window.Plotly.react(document.getElementById("map-plot-2d"), traces2d(result.trajectories),
      layout2d("The same points: l against L/G"), CONFIG);
    table(result);
    scrollToResult("map-plot");
    lastMap = { request: body, result };
    setQuery(formQuery(ev.target, { run: 1 }));     // the address now reproduces this map
    document.getElementById("map-downloads").hidden = false;
    document.body.dataset.map = String(Number(document.body.dataset.map || 0) + 1);
  } catch (e) {
    status.textContent = e.message;
    status.classList.add("error");
  } finally {
    button.disabled = false;
  }
}

function secs(s) {
  return s < 1 ? `${Math.max(0.1, s).toFixed(1)} s` : `${Math.round(s)} s`;
}

function mapRows(result) {
  const rows = [];
  result.trajectories.forEach((t, i) => t.points.forEach((p, j) => rows.push([i + 1, j + 1, ...p])));
  return rows;
}

function stem() {
  const r = lastMap.request;
  return `map_${r.case.replace(/\//g, "_")}_E${r.energy}_g${lastMap.result.section.g0}`;
}

document.getElementById("map-csv").addEventListener("click", () => download(`${stem()}.csv`,
  csvText(["trajectory", "point", "L_over_G", "H_over_G", "l"], mapRows(lastMap.result)), "text/csv"));
document.getElementById("map-json").addEventListener("click", () => download(`${stem()}.json`,
  JSON.stringify({ request: lastMap.request, ...lastMap.result }, null, 1), "application/json"));

// The form's defaults, per case (static/data/poincare_defaults.json): chosen so that every
// trajectory of a case's default map returns to the section within a few seconds
let DEFAULTS = { form: {}, cases: {} };

function applyDefaults(form, caseId) {
  const own = DEFAULTS.cases[caseId] || {};
  const values = { ...DEFAULTS.form, ...own };
  for (const [k, v] of Object.entries(values)) {
    const el = form.elements.namedItem(k);
    if (el && "value" in el) el.value = String(v);
  }
  document.getElementById("case-note").textContent = own.why
    ? `This case's defaults: ${Object.keys(own).filter((k) => k !== "why")
      .map((k) => `${k} = ${own[k]}`).join(", ")}. ${own.why}` : "";
}

async function loadDefaults() {
  const res = await fetch("/static/data/poincare_defaults.json");
  if (!res.ok) throw new Error(`the form's defaults: ${res.status} ${res.statusText}`);
  DEFAULTS = await res.json();
}

const form = document.getElementById("map-form");
form.addEventListener("submit", compute);
form.elements.namedItem("case").addEventListener("change", (e) => {
  applyDefaults(form, e.target.value);
  building = buildParams(e.target.value);
});
document.getElementById("param-fields").addEventListener("input", checkParams);
Promise.all([cases(), loadDefaults(), glossary()]).then(async () => {
  const q = new URLSearchParams(location.search);
  const sel = form.elements.namedItem("case");
  if ([...sel.options].some((o) => o.value === q.get("case"))) sel.value = q.get("case");
  applyDefaults(form, sel.value);
  building = buildParams(sel.value);
  await building;
  document.body.dataset.defaults = "1";
  // a permalink (?case=...&p.I1=...&energy=...&run=1): fill the form and compute that map
  const run = applyFormQuery(form, location.search, { flag: "map", result: "map-plot" });
  if (q.has("params")) legacyParams(q.get("params"));
  checkParams();
  if (run) form.requestSubmit();
}).catch((e) => {
  const s = document.getElementById("map-status");
  s.textContent = `Could not load the cases: ${e.message}`;
  s.classList.add("error");
});
figures();
