// The case page's claims: the case's head, its table cells, its claims with their marks,
// checks and 'since 2002' notes, the Cite box, and following a verification as it runs.
// The run form and the start of the page are in case.js; the case itself in case_state.js.
"use strict";

import { claimAnchor as anchor } from "./anchor.js";
import { api, escapeHtml, fmt } from "./api.js";
import { mathHtml, printedHtml, textHtml } from "./latex.js";
import { badgeHtml, erratumLinks, markHtml, markInfo, markNoteHtml, tallyHtml } from "./marks.js";
import { caseCiteHtml, checkedHtml, citeData, decorateClaims } from "./cite.js";
import { symbolsHtml } from "./notation.js";
import { $, C, setCase } from "./case_state.js";

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

export function showHead() {
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

export function showCells() {
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
export function showClaims() {
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
export async function followChecking() {
  while (C.verification === "running") {
    await new Promise((r) => setTimeout(r, 3000));
    try {
      const c = await api(`/api/cases/${C.id}`);
      if (c.verification === "running") continue;
      setCase(c);
      showTally(); showCells(); showClaims();
      document.body.dataset.checked = "1";
    } catch {
      return;
    }
  }
}

export async function reverify() {
  const btn = $("reverify"), msg = $("reverify-msg");
  btn.disabled = true;
  msg.textContent = "Checking every claim of this case…";
  try {
    const r = await api(`/api/verify/${C.id}`, { method: "POST", body: {} });
    setCase(await api(`/api/cases/${C.id}`));
    showTally(); showCells(); showClaims();
    msg.textContent = `Done in ${fmt(r.seconds, 2)} s.`;
  } catch (err) {
    msg.textContent = `Verification failed: ${err.message}`;
  } finally {
    btn.disabled = false;
  }
}
