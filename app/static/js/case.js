// A case's page (/case/<id>, a permalink): the case in the table, every claim with its
// printed formula, source and verdict, and a simulate panel with plots and a 3D scene.
"use strict";

import { api, ApiError, download, escapeHtml, fmt } from "./api.js";
import { mathHtml, printedHtml, textHtml } from "./latex.js";
import { badgeHtml, erratumLinks, markHtml, markInfo, markNoteHtml, tallyHtml } from "./marks.js";
import { plotDrift, plotGamma, plotState } from "./plots.js";
import { applyRunQuery, runQuery, setQuery } from "./permalink.js";
import { csvOf, fileStem as runFileStem } from "./run_csv.js";
import { estimate } from "./estimate.js";
import { kernelSentence, runLabel } from "./kernels.js";
import { Scene } from "./scene.js";
import { glossary, tipHtml } from "./glossary.js";
import { caseCiteHtml, checkedHtml, citeData, decorateClaims } from "./cite.js";
import { symbolsHtml } from "./notation.js";

const caseId = decodeURIComponent(location.pathname.replace(/^\/case\//, "").replace(/\/$/, ""));
const $ = (id) => document.getElementById(id);
const anchor = (claimId) => "claim-" + claimId.replace(/[^A-Za-z0-9_-]+/g, "_");
const PRETTY = { g1: "γ₁", g2: "γ₂", g3: "γ₃", M1: "M₁", M2: "M₂", M3: "M₃", r1: "r₁", r2: "r₂",
  mu: "μ", lambda: "λ", eps: "ε" };
const RUN_DEFAULTS = { t_end: "100", samples: "801", rtol: "1e-10", atol: "1e-12", step: "0.1" };

let C = null;          // the case (GET /api/cases/{id})
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

// ---------------------------------------------------------------- the case and its claims

function attributionText(list) {
  return list.map((a) => {
    const who = a.authors || a.reference_authors.join(", ") || "the reference";
    const year = a.year ? ` (${a.year})` : "";
    const title = a.reference_title ? `, <cite>${escapeHtml(a.reference_title)}</cite>` : "";
    const note = a.note ? ` — ${escapeHtml(a.note)}` : "";
    // the reference's key ([bm-new]) is data: the reader gets a link to its entry instead
    const ref = a.ref ? ` <a href="/bibliography#ref-${encodeURIComponent(a.ref)}">reference</a>` : "";
    return `${escapeHtml(who)}${year}${title}${ref}${note}`;
  }).join("; ");
}

// "(M, gamma)" -> "(M, γ)": the data spells Greek letters out, the page does not
function greekWords(text) {
  return String(text).replace(/\b(gamma|omega|lambda|mu|rho|tau)\b/g,
    (w) => ({ gamma: "γ", omega: "ω", lambda: "λ", mu: "μ", rho: "ρ", tau: "τ" })[w]);
}

function showHead() {
  document.title = `${C.title} — Rolling hierarchy`;
  $("case-title").textContent = C.title;
  // a runnable case beyond the tables (the rattleback) has no table and column
  const place = C.in_tables === false ? "beyond Tables 1 and 2" : `Table ${C.table}, column ${C.column}`;
  $("crumb-table").innerHTML = C.in_tables === false ? "beyond the tables"
    : `<a href="/#table-${C.surface}">Table ${C.table}</a>`;
  $("crumb-case").textContent = C.in_tables === false ? C.id : `column ${C.column}`;
  if (C.in_tables === false) {                     // no cells, no claims to check
    $("reverify").hidden = true;
    $("h-in-table").textContent = "Not in the paper's tables";
  }
  const m = C.model;
  // the conditions in words (conditions_text), not the data's key: value pairs
  const cond = (m.conditions_text || []).map(escapeHtml).join("; ");
  $("facts").innerHTML = [
    place,
    `support: ${C.surface}`,
    `body: ${escapeHtml(String(m.body).replaceAll("-", " "))}`,
    `state ${escapeHtml(greekWords(m.state))}`,
    (m.equation_numbers || []).length ? `equations ${m.equation_numbers.join(", ")}` : "",
    cond ? `conditions: ${cond}` : "",
  ].filter(Boolean).map((f) => `<span class="chip">${f}</span>`).join("");
  showTally();
}

// the case's counts by mark, in words (views.case_sentence) and as shape + count + word
function showTally() {
  const state = C.verification === "running"
    ? " · being checked now on this server; the page updates when the check finishes" : "";
  $("tally").innerHTML = `<p class="mark-summary" id="mark-summary">${escapeHtml(C.summary || "")}</p>` +
    (C.in_tables === false ? "" : `<span>cells: ${tallyHtml(C.cell_marks || {})}</span> <span>claims: ${tallyHtml(C.marks || {})}</span>` +
    `<span class="hint">${state}</span>`);
  $("nclaims").textContent = `(${C.claims.length})`;
}

// a merged cell lists claims of the other cases it spans: those link to their own page
// shown as the reader knows a claim: its kind and printed number (the id is in its Details)
function claimLink(id) {
  const parts = id.split("/");
  const owner = parts.slice(0, 2).join("/");
  if (owner === C.id) {
    const cl = C.claims.find((x) => x.id === id);
    const text = cl ? `${cl.kind}${cl.number ? ` ${cl.number}` : ""}` : parts.slice(2).join(" ");
    return `<a href="#${anchor(id)}">${escapeHtml(text)}</a>`;
  }
  // another case's claim: named by its kind and the case in words, not by its record id
  const where = `${parts[1].replaceAll("-", " ")} on a ${parts[0]}`;
  return `<a href="/case/${owner}#${anchor(id)}">${escapeHtml(`${parts[2] || "claim"} of the ${where}`)}</a>`;
}

// the claims of a cell: several claims with the same kind and number ("gyrostat (2.38)")
// are one entry with numbered links, not the same words repeated
function claimLinks(ids) {
  const own = ids.filter((id) => C.claims.some((x) => x.id === id));
  const groups = new Map();
  for (const id of own) {
    const cl = C.claims.find((x) => x.id === id);
    const text = `${cl.kind}${cl.number ? ` ${cl.number}` : ""}`;
    if (!groups.has(text)) groups.set(text, []);
    groups.get(text).push(id);
  }
  const parts = [...groups].map(([text, list]) => list.length === 1
    ? `<a href="#${anchor(list[0])}">${escapeHtml(text)}</a>`
    : `${escapeHtml(text)} (${list.length} claims: ${list.map((id, i) =>
      `<a href="#${anchor(id)}" aria-label="${escapeHtml(text)}, claim ${i + 1}">${i + 1}</a>`).join(", ")})`);
  return [...parts, ...ids.filter((id) => !own.includes(id)).map(claimLink)].join(", ");
}

function showCells() {
  const rows = C.cells.map((c) => {
    const own = c.verdict ? c.verdict.claims.find((id) => id.startsWith(C.id + "/")) : null;
    // the note that goes with the mark is written out in the row: no "why?" under it here
    const mark = c.verdict ? markHtml(c.verdict, own ? `#${anchor(own)}` : `#row-${c.row}`, { why: false }) : "";
    const att = c.attribution.length ? `<div class="claimrefs">credited: ${attributionText(c.attribution)}</div>` : "";
    const refs = c.claims.length
      ? `<div class="claimrefs">claims: ${claimLinks(c.claims)}</div>` : "";
    const merged = c.merged.length > 1 ? `<div class="claimrefs">merged cell: spans ${c.merged.length} columns</div>` : "";
    const sub = c.subrow ? `<div>${textHtml(c.subrow.printed)}</div>` : "";
    const cm = c.verdict && c.verdict.marks && c.verdict.marks.length ? c.verdict.marks[0] : null;
    // the verdict in words; the checking code's message (developer text) behind a toggle
    const info = cm ? markInfo(cm.mark) : null;
    const links = cm && cm.mark === "after-correction" ? erratumLinks(cm.errata) : "";
    const prop = cm && cm.mark !== "pending"
      ? `<div class="claimrefs cellverdict">the cell's property: <strong>${info.shape} ${escapeHtml(info.name)}</strong>` +
        `${cm.mark_note ? `: ${escapeHtml(cm.mark_note)}` : ""}${links ? ` (${links})` : ""}` +
        `${cm.rests_on.length ? `; rests on ${cm.rests_on.map(claimLink).join(", ")}` : ""}` +
        `${cm.message ? `<details class="dev"><summary>Details</summary>${escapeHtml(cm.message)}</details>` : ""}</div>`
      : (cm ? `<div class="claimrefs cellverdict">the cell's property: checking…</div>` : "");
    const shade = c.shade === "full" ? "gray: the invariant exists" : c.shade === "partial"
      ? "partial fill: incomplete set of integrals" : "";
    const why = shade ? `<div class="claimrefs shade-note">shading: ${shade}${c.shade_note ? ` — ${escapeHtml(c.shade_note)}` : ""}</div>` : "";
    return `<tr id="row-${c.row}"><th scope="row">${escapeHtml(c.row_label)}</th>` +
      `<td class="shade-${c.shade}">${textHtml(c.printed)}${sub}${symbolsHtml(c.symbols)}${att}${refs}${merged}${why}${prop}${mark}</td></tr>`;
  });
  $("cells").innerHTML = rows.length ? `<table class="cells"><tbody>${rows.join("")}</tbody></table>`
    : `<p class="status" data-testid="beyond-tables">No column of Tables 1 and 2 holds this body: it has no cells to show.</p>`;
}

function stamp(v) {
  return v.computed_at ? ` · computed ${escapeHtml(v.computed_at.slice(0, 10))} by version ${escapeHtml(v.version || "?")}` : "";
}

function verdictLine(v) {
  const res = v.residual !== null && v.residual !== undefined ? ` · residual <code>${fmt(v.residual, 2)}</code>` : "";
  return `<div class="verdict-line">${badgeHtml(v.mark)}${res}${stamp(v)}</div>`;
}

// one plain sentence: what was checked (the kind of check, see /how-we-check) and what came out
const CHECKED = {
  integral: "We checked that this quantity stays constant along the motion, at random states",
  measure: "We checked that this density is preserved by the flow (Liouville equation), at random states",
  identity: "We checked that the printed expression equals the one it is claimed to equal, at random states",
  reduced_agrees: "We checked that the printed reduced equations agree with the full equations of motion, at random states",
  solves_ode: "We checked that the printed solution satisfies its equation",
  linear_integrals: "We checked the printed integrals against solutions of the linear system",
  symmetry: "We checked that the motion commutes with the printed symmetry",
  jacobi: "We checked that the printed bracket satisfies the Jacobi identity, at random states",
  casimir: "We checked that the listed functions are Casimir functions of the bracket",
  bracket_rank: "We checked the rank of the bracket",
  hamiltonian_field: "We checked that after the change of time the motion is generated by the bracket and the Hamiltonian",
  hamiltonian_field_on_level: "We checked that after the change of time the motion is generated by the bracket and the Hamiltonian, at random states of one level of an integral",
  hamiltonian_attempt: "We tried a bracket for the Hamiltonian form the paper asserts: its Jacobi identity and whether it generates the motion, at random states",
  functionally_dependent: "We checked that these functions are functionally dependent",
  permanent_rotations: "We checked the family of permanent rotations",
  measure_fails: "We checked that this density is NOT preserved here",
  integral_fails: "We checked that this quantity is NOT conserved here",
  jacobi_fails: "We checked that this bracket does NOT satisfy the Jacobi identity",
  negative_measure: "We looked for evidence that no invariant measure exists",
  negative_integral: "We looked for evidence that no further integral exists (3D point maps)",
  open_problem: "The paper states this as open; there is nothing to compute",
  formula_not_printed: "The paper asserts this without printing a formula, so it cannot be computed",
  not_checkable: "This statement cannot be decided by a pointwise computation",
};
// what came out, by mark (solvers/verify/marks.yaml defines each on /how-we-check)
const OUTCOME = {
  "as-printed": "it holds as printed, to round-off.",
  "after-correction": "as printed it does not hold; the project's corrected form does.",
  "under-convention": "it holds under the convention stated below, not read with the project's conventions.",
  "project-formula": "the paper prints no formula; the project's derived formula holds, to round-off.",
  fails: "it does not hold: the residual is far above the tolerance.",
  "evidence-for": "numerical evidence supports it (not a proof); the numbers are in the details.",
  "evidence-against": "numerical evidence goes against it (not a proof); the numbers are in the details.",
  inconclusive: "the check ran and could not decide; what it found is stated below.",
  "not-checkable": "nothing was run (see the details).",
  pending: "being checked now; this page updates when the check finishes.",
};

function sentence(c) {
  const v = c.verdict.mark;
  const what = CHECKED[c.check] || "Checked";
  const out = c.check === "open_problem" || c.check === "formula_not_printed" || c.check === "not_checkable"
    ? "." : `: ${OUTCOME[v] || v}`;
  return `<p class="checked">${escapeHtml(what)}${escapeHtml(out)} <a href="/how-we-check#${escapeHtml(c.check)}">How we check</a></p>`;
}

function claimHtml(c) {
  const v = c.verdict;
  const source = [c.number ? `<strong>${escapeHtml(c.number)}</strong>` : "", c.where ? escapeHtml(c.where) : ""]
    .filter(Boolean).join(" — ");
  const cond = (c.conditions_text || []).map(escapeHtml).join("; ");
  const args = Object.entries(c.check_args).map(([k, x]) => `${escapeHtml(k)} ${escapeHtml(Array.isArray(x) ? x.join(", ") : String(x))}`).join("; ");
  const dl = [
    source ? ["in the paper", source] : null,
    c.attribution.length ? ["credited to", attributionText(c.attribution)] : null,
    cond ? ["conditions", cond] : null,
  ].filter(Boolean).map(([k, x]) => `<dt>${k}</dt><dd>${x}</dd>`).join("");
  // developer-facing text: behind the details toggle
  const dev = [
    ["claim id", `<code>${escapeHtml(c.id)}</code>`],
    ["variables", escapeHtml(c.variables)],
    ["check", `<code>${escapeHtml(c.check)}</code>${args ? ` (${args})` : ""}`],
    v.message ? ["message", escapeHtml(v.message)] : null,
    v.seconds ? ["time", `${fmt(v.seconds, 2)} s`] : null,
  ].filter(Boolean).map(([k, x]) => `<dt>${k}</dt><dd>${x}</dd>`).join("");
  const notes = [
    c.convention_note ? `<p><strong>Convention:</strong> ${escapeHtml(c.convention_note)}</p>` : "",
    c.remarks ? `<p><strong>Remark:</strong> ${escapeHtml(c.remarks)}</p>` : "",
  ].join("");
  // a misprint: the formula that holds leads, typeset large; the printed form follows
  const lead = v.mark === "after-correction"
    ? c.corrections.find((r) => r.printed_tex && r.mark === "after-correction") : null;
  const corr = c.corrections.map((r) => `<div class="correction"><strong>${r === lead ? "What the correction changes" : "The project's corrected form"}</strong>` +
    `${r.printed_tex && r !== lead ? `<div class="printed">${mathHtml(r.printed_tex, true)}</div>${symbolsHtml(r.symbols)}` : ""}` +
    `${r === lead && r.change ? `<p class="plain">${escapeHtml(r.change)}</p>` : ""}` +
    `${r.printed && !(r === lead && r.change) ? `<p class="plain">${r.printed_tex ? escapeHtml(r.printed) : printedHtml(r.printed)}</p>` : ""}${verdictLine(r)}</div>`).join("");
  const formulas = lead
    ? `<div class="printed corrected-lead" data-testid="corrected-lead"><span class="formlabel">corrected form, which holds</span>${mathHtml(lead.printed_tex, true)}</div>` +
      `${symbolsHtml(lead.symbols)}<div class="printed as-printed" data-testid="as-printed"><span class="formlabel">as printed</span>${printedHtml(c.printed)}</div>`
    : `<div class="printed">${printedHtml(c.printed)}</div>`;
  return `<article class="claim ${v.verdict} ${escapeHtml(v.mark)}" id="${anchor(c.id)}">` +
    `<header><span class="kind">${escapeHtml(c.kind)}</span>${c.number ? `<span class="label">${escapeHtml(c.number)}</span>` : ""}` +
    `${badgeHtml(v.mark)}</header>` +
    formulas + symbolsHtml(c.symbols) +
    `<p class="plain">${escapeHtml(c.plain)}</p>${sentence(c)}<dl>${dl}</dl>${verdictLine(v)}${markNoteHtml(v)}` +
    `<details class="dev"><summary>Details</summary><dl>${dev}</dl>${notes}</details>${corr}</article>`;
}

// The "since 2002" notes come rendered by the server beside their claims and cells
// (app/services/ssr.py since_html); a redraw of the claims puts the same nodes back.
let SINCE = null;
function showClaims() {
  const list = $("claimlist");
  SINCE = SINCE || { notes: [...list.querySelectorAll("article.claim > aside.since-2002")],
                     cells: list.querySelector("section.since-cells") };
  list.innerHTML = C.claims.length ? C.claims.map(claimHtml).join("")
    : `<p class="status">No claims: ${escapeHtml(C.in_tables === false ? "this case is not in the paper's tables." : "none catalogued.")}</p>`;
  for (const note of SINCE.notes) {
    const claim = document.getElementById(anchor(note.dataset.record));
    if (claim) claim.appendChild(note);
  }
  if (SINCE.cells) list.appendChild(SINCE.cells);
  showCite();
}

// the Cite box, the claims' permalinks and Cite boxes, what was checked (cite.js)
let CITE = null;
let HOW = null;
async function showCite() {
  try {
    [CITE, HOW] = await Promise.all([CITE || citeData(), HOW || api("/api/how-we-check")]);
  } catch {
    return;   // the claims stand without their Cite boxes
  }
  decorateClaims(CITE, C, anchor);
  $("citebox").innerHTML = caseCiteHtml(CITE, C);
  $("checkedbox").innerHTML = C.claims.length ? checkedHtml(C, HOW, anchor)
    : "<p>No claims on this page: nothing is checked.</p>";
  document.body.dataset.cite = "1";
}

// A fresh server recomputes the verdicts of changed cases in the background: while this
// case is among them its claims show "checking", and the page redraws them when it is done.
async function followChecking() {
  while (C.verification === "running") {
    await new Promise((r) => setTimeout(r, 3000));
    try {
      const c = await api(`/api/cases/${C.id}`);
      if (c.verification === "running") continue;
      C = c;
      showTally(); showCells(); showClaims();
      document.body.dataset.checked = "1";
    } catch {
      return;
    }
  }
}

async function reverify() {
  const btn = $("reverify"), msg = $("reverify-msg");
  btn.disabled = true;
  msg.textContent = "Checking every claim of this case…";
  try {
    const r = await api(`/api/verify/${C.id}`, { method: "POST", body: {} });
    C = await api(`/api/cases/${C.id}`);
    showTally(); showCells(); showClaims();
    msg.textContent = `Done in ${fmt(r.seconds, 2)} s.`;
  } catch (err) {
    msg.textContent = `Verification failed: ${err.message}`;
  } finally {
    btn.disabled = false;
  }
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
    C = c;
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
