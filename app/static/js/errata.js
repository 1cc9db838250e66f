// /errata as a reference table: one row per misprint with its own address
// (#e-<claim>), the display that is corrected, what changes, both residuals; the row opens
// (<details>) on the printed and the corrected form typeset, the exact check and the command
// that reproduces it. An index by section; conventions and findings in tables of their own.
// Data: GET /api/errata, /api/conventions, /api/findings (solvers/verify/errata.py).
"use strict";

import { claimAnchor } from "./anchor.js";
import { api, escapeHtml } from "./api.js";
import { mathHtml, printedHtml } from "./latex.js";
import { symbolsHtml } from "./notation.js";

// the symbols of one of a row's formulas, each a link to /notation (errata_pages.with_symbols)
const syms = (e, role) => symbolsHtml((e.symbols || {})[role]);

function katexReady() {
  return new Promise((resolve) => {
    if (window.katex) return resolve();
    document.querySelector('script[src*="katex"]').addEventListener("load", () => resolve());
  });
}

const caseHref = (e) => (e.href ? e.href : `/case/${e.case}#${claimAnchor(e.claim)}`);
const sectionOf = (e) => (e.section || "").replace(/^section /, "") || "other";
// a residual as a reader compares it: two digits, round-off in exponent form
export function res(x) {
  if (x === null || x === undefined) return "n/a";
  if (x === 0) return "0";
  return Math.abs(x) >= 1e-3 ? x.toPrecision(2) : x.toExponential(1);
}
const rowLink = (anchor) => `<a class="permalink" href="#${escapeHtml(anchor)}" title="Link to this row" aria-label="Link to this row">¶</a>`;

let CASES = {};       // case id -> title

// a row names its claim as the case pages do: the case's title, the claim's kind and printed
// number (claim_name, solvers/verify/errata.py); the record id only in the link and data-claim
const caseTitle = (e) => e.case_title || CASES[e.case] || "the case";
// in a row's summary (the part a reader clicks to open the row) the case is named, not
// linked: a link inside <summary> is an interactive element nested in another (axe-core's
// nested-interactive); the link to the claim is in the row's body (claimLink)
function caseLink(e) {
  const title = caseTitle(e);
  const tip = e.claim_name ? `${e.claim_name}, ${title}` : title;
  return `<span class="casename" title="${escapeHtml(tip)}" data-claim="${escapeHtml(e.claim)}">${escapeHtml(title)}</span>`;
}
// the claim itself, linked: "integral (2.24) of the Chaplygin ball"
function claimLink(e) {
  const text = e.claim_name ? `${e.claim_name} of ${caseTitle(e)}` : caseTitle(e);
  return `<a class="claimname" href="${escapeHtml(caseHref(e))}" data-claim="${escapeHtml(e.claim)}">${escapeHtml(text)}</a>`;
}

function exactHtml(ex, what) {
  if (!ex) return "";
  // the witness (a rational point and residual) can run to thousands of digits: behind a toggle
  const w = ex.witness !== undefined && ex.witness !== null
    ? `<details><summary>rational witness point and its exact residual</summary>` +
      `<code class="witness" tabindex="0">${escapeHtml(JSON.stringify(ex.witness))}</code></details>` : "";
  const bound = ex.holds && ex.bound ? ` ${escapeHtml(ex.bound)}.` : "";
  return `<p class="exact">Exact check of the ${what}: ` +
    `${ex.holds ? "holds" : "does not hold"} at ${ex.points} rational point${ex.points === 1 ? "" : "s"}.${bound}</p>${w}`;
}

function reproHtml(cmd) {
  return `<p class="repro">Reproduce: <code>${escapeHtml(cmd)}</code></p>`;
}

// ---- misprints

function kindBadge(e) {
  return e.kind === "inherited"
    ? `<span class="ek inherited" title="fails only through a misprinted formula it uses">↳ inherited</span>`
    : `<span class="ek misprint">✗ misprint</span>`;
}

function erratumHtml(e) {
  const claimAt = e.place === e.corrected_display ? "" : `<span class="at">claim at ${escapeHtml(e.place)}</span> `;
  const inherits = e.kind === "inherited" && e.inherits
    ? `<p>Inherited: this formula uses <a href="#e-${escapeHtml(e.inherits)}">a misprinted one</a> and fails only through it.</p>` : "";
  const corrected = e.corrected_tex
    ? `<div class="printed corrected" tabindex="0">${mathHtml(e.corrected_tex, true)}</div>${syms(e, "corrected")}` : "";
  return `<details class="erow" id="${escapeHtml(e.anchor)}" data-section="${escapeHtml(sectionOf(e))}">` +
    `<summary><span class="disp">${kindBadge(e)} <strong>${escapeHtml(e.corrected_display || e.place)}</strong></span>` +
    `<span class="case">${claimAt}${caseLink(e)}</span>` +
    `<span class="change">${escapeHtml(e.change || "")}</span>` +
    `<span class="res"><span title="residual of the printed form">${res(e.residual_printed)}</span> → ` +
    `<span title="residual of the corrected form">${res(e.residual_corrected)}</span></span></summary>` +
    `<div class="ebody">${rowLink(e.anchor)} ` +
    `<p class="where">Corrected display: <strong>${escapeHtml(e.corrected_display || "")}</strong>` +
    `${e.corrected_where && e.corrected_number ? "" : e.corrected_where ? ` (${escapeHtml(e.corrected_where)})` : ""}` +
    `${e.section_title ? `, section ${escapeHtml(sectionOf(e))}, “${escapeHtml(e.section_title)}”` : ""}. ` +
    `The claim that fails as printed stands at ${escapeHtml(e.number || e.where || e.place)}: ${claimLink(e)}.</p>` +
    `<div class="pair"><div><h4>Printed ${escapeHtml(e.corrected_display || "")}</h4>` +
    `<div class="printed" tabindex="0">${printedHtml(e.corrected_printed || e.printed)}</div>${syms(e, "printed")}` +
    `<p>residual of the claim as printed ${res(e.residual_printed)} (fails)</p></div>` +
    `<div><h4>Corrected (the project)</h4>${corrected}` +
    `<p>residual ${res(e.residual_corrected)} (${e.corrected_verdict === "verified" ? "holds" : escapeHtml(e.corrected_verdict || "")})</p></div></div>` +
    (e.corrected_printed && e.corrected_printed !== e.printed
      ? `<details class="claimform"><summary>the claim as printed at ${escapeHtml(e.place)}</summary>` +
        `<div class="printed" tabindex="0">${printedHtml(e.printed)}</div>${syms(e, "claim")}</details>` : "") +
    `<p class="note"><strong>What changes:</strong> ${escapeHtml(e.change || "")}</p>` +
    `<details class="claimform"><summary>the note registered with the correction</summary><p>${escapeHtml(e.corrected)}</p></details>${inherits}` +
    exactHtml(e.exact, "printed form") + exactHtml(e.corrected_exact, "corrected form") +
    reproHtml(e.reproduce) + `</div></details>`;
}

// ---- conventions: the printed form holds when read with the convention the text supports

function conventionHtml(e) {
  return `<details class="erow convention" id="${escapeHtml(e.anchor)}" data-section="${escapeHtml(sectionOf(e))}">` +
    `<summary><span class="disp"><span class="ek convention">◇ convention</span> <strong>${escapeHtml(e.place)}</strong></span>` +
    `<span class="case">${caseLink(e)}</span>` +
    `<span class="change">${escapeHtml(e.convention || "")}</span>` +
    `<span class="res"><span title="residual under the convention">${res(e.residual_under_convention)}</span> · ` +
    `<span title="residual read with the project's convention">${res(e.residual_printed)}</span></span></summary>` +
    `<div class="ebody">${rowLink(e.anchor)} <p class="where">The claim: ${claimLink(e)}.</p>` +
    `<div class="printed" tabindex="0">${printedHtml(e.printed)}</div>${syms(e, "printed")}` +
    `<p><strong>Convention:</strong> ${escapeHtml(e.convention || "")}</p>` +
    `<p>Under this convention the printed form holds: residual ${res(e.residual_under_convention)}. ` +
    `Read with the project's convention instead, it fails: residual ${res(e.residual_printed)}.</p>` +
    exactHtml(e.exact, "printed form under the convention") + reproHtml(e.reproduce) + `</div></details>`;
}

// ---- findings: refuted statements and conjectures, and checks that could not decide

const FINDING_KIND = {
  "refuted-conjecture": ["✗", "refuted conjecture"],
  refuted: ["✗", "refuted"],
  inconclusive: ["◌", "inconclusive"],
};

function evidenceHtml(ev) {
  const rows = Object.entries(ev || {}).map(([k, v]) => {
    const val = typeof v === "number" ? res(v) : Array.isArray(v) ? `${v.length} values` : String(v);
    return `<tr><th scope="row">${escapeHtml(k)}</th><td>${escapeHtml(val)}</td></tr>`;
  }).join("");
  return rows ? `<details><summary>the numbers</summary><table class="evidence"><tbody>${rows}</tbody></table></details>` : "";
}

function findingHtml(e) {
  const [icon, word] = FINDING_KIND[e.kind] || ["•", e.kind];
  const leans = e.leans ? `, leans ${escapeHtml(e.leans)}` : "";
  const stmt = e.claim.startsWith("figure/")
    ? `<blockquote class="caption">${escapeHtml(e.printed)}</blockquote>`
    : `<div class="printed" tabindex="0">${printedHtml(e.printed)}</div>${syms(e, "printed")}`;
  const inconclusive = e.kind === "inconclusive"
    ? "<p>A check ran and could not decide: this is numerical evidence, not a proof; it weighs against the printed statement without refuting it.</p>" : "";
  return `<details class="erow fnd" id="${escapeHtml(e.anchor)}" data-section="${escapeHtml(sectionOf(e))}">` +
    `<summary><span class="disp"><span class="ek ${escapeHtml(e.kind)}">${icon} ${escapeHtml(word)}</span> <strong>${escapeHtml(e.place || "")}</strong></span>` +
    `<span class="case">${caseLink(e)}</span>` +
    `<span class="change">${escapeHtml(e.title)}</span>` +
    `<span class="res">${escapeHtml(word)}${leans}</span></summary>` +
    `<div class="ebody">${rowLink(e.anchor)} <p class="where">The paper (${escapeHtml(e.where || e.place || "")}), ${claimLink(e)}:</p>${stmt}` +
    `<p><strong>Found:</strong> ${escapeHtml(e.finding)}</p>${inconclusive}${evidenceHtml(e.evidence)}` +
    exactHtml(e.exact, "claim") + reproHtml(e.reproduce) + `</div></details>`;
}

// ---- the index by section: each display once, with a link to each of its rows
// (app/services/errata_pages.py renders the same index on the server)

const tipOf = (e) => `${caseTitle(e)}${e.claim_name ? `, ${e.claim_name}` : ""}`;

function groupedLinks(rows) {
  const groups = new Map();
  for (const [label, e] of rows) {
    if (!groups.has(label)) groups.set(label, []);
    groups.get(label).push(e);
  }
  const out = [...groups.entries()].map(([label, es]) => {
    let first = `<a href="#${escapeHtml(es[0].anchor)}" title="${escapeHtml(tipOf(es[0]))}">${escapeHtml(label)}</a>`;
    if (es.length > 1) {
      first += ` <span class="rows">(${es.length} rows: ${es.map((e, i) =>
        `<a href="#${escapeHtml(e.anchor)}" title="${escapeHtml(tipOf(e))}">${i + 1}</a>`).join(" ")})</span>`;
    }
    return `<span class="idx">${first}</span>`;
  });
  return out.join(" ") || "—";
}

/** What makes two rows one misprint: the display corrected (errata_pages.misprint_key). */
const misprintKey = (e) => e.corrected_label || e.corrected_where || e.corrected_formula || e.claim;

export function counts(errata) {
  const own = errata.filter((e) => e.kind !== "inherited");
  return { rows: errata.length, misprints: new Set(own.map(misprintKey)).size,
    misprintRows: own.length, inherited: errata.length - own.length };
}

/** "23 misprints, and 5 inherited rows that repeat one" (errata_pages.counts_sentence). */
export function countsSentence(errata) {
  const n = counts(errata);
  let words = `${n.misprints} misprint${n.misprints === 1 ? "" : "s"}`;
  const extra = n.misprintRows - n.misprints;
  if (extra > 0) words += ` (${extra} more row${extra === 1 ? "" : "s"} where several cases use the same display)`;
  return `${words}, and ${n.inherited} inherited row${n.inherited === 1 ? "" : "s"} that repeat${n.inherited === 1 ? "s" : ""} one`;
}

function indexHtml(errata, conventions, findings) {
  const secs = new Map();
  const add = (e, what, label) => {
    const s = sectionOf(e);
    if (!secs.has(s)) secs.set(s, { title: e.section_title || "", errata: [], conventions: [], findings: [] });
    const rec = secs.get(s);
    if (e.section_title) rec.title = e.section_title;
    rec[what].push([label, e]);
  };
  errata.forEach((e) => add(e, "errata", e.corrected_display || e.place));
  conventions.forEach((e) => add(e, "conventions", e.place));
  findings.forEach((e) => add(e, "findings", e.place || e.title));
  const TITLES = { 1: "Equations of motion", 2: "Body on a plane", 3: "Body on a sphere" };
  const n = counts(errata);
  const rows = [...secs.entries()].sort(([a], [b]) => a.localeCompare(b)).map(([s, r]) =>
    `<tr id="index-${escapeHtml(s)}"><th scope="row">Section ${escapeHtml(s)}. ${escapeHtml(r.title || TITLES[s] || "")}</th>` +
    `<td>${groupedLinks(r.errata)}</td><td>${groupedLinks(r.conventions)}</td><td>${groupedLinks(r.findings)}</td></tr>`);
  return `<div class="table-wrap"><table class="eindex"><thead><tr><th scope="col">section</th>` +
    `<th scope="col">misprints (${n.misprints}, in ${n.rows} rows): the corrected displays</th><th scope="col">conventions (${conventions.length})</th>` +
    `<th scope="col">findings (${findings.length})</th></tr></thead><tbody>${rows.join("")}</tbody></table></div>`;
}

function grouped(list, render) {
  const out = [];
  let last = null;
  for (const e of list) {
    const s = sectionOf(e);
    if (s !== last) {
      out.push(`<h3 class="esec">Section ${escapeHtml(s)}${e.section_title ? `. ${escapeHtml(e.section_title)}` : ""}</h3>`);
      last = s;
    }
    out.push(render(e));
  }
  return out.join("");
}

async function load(path) {
  try {
    return await api(path);
  } catch (err) {
    return err;
  }
}

function show(id, list, html, empty) {
  const el = document.getElementById(id);
  if (list instanceof Error) {
    el.innerHTML = `<p class="error" role="alert">Could not load: ${escapeHtml(list.message)}</p>`;
    return [];
  }
  el.innerHTML = list.length ? html(list) : `<p>${empty}</p>`;
  document.getElementById(`n-${id.replace("-list", "")}`).textContent = `(${list.length})`;
  return list;
}

// a row's address opens it: on load and when the reader follows an index link
function openTarget() {
  const id = decodeURIComponent(location.hash.slice(1));
  const el = id ? document.getElementById(id) : null;
  if (el && el.tagName === "DETAILS") {
    el.open = true;
    el.scrollIntoView();
  }
}

await katexReady();
const [cases, ers, cvs, fds] = await Promise.all(
  [load("/api/cases"), load("/api/errata"), load("/api/conventions"), load("/api/findings")]);
if (Array.isArray(cases)) CASES = Object.fromEntries(cases.map((c) => [c.id, c.title]));
const e = show("errata-list", ers, (l) => grouped(l, erratumHtml), "No misprint found yet.");
if (e.length) {
  const n = counts(e);
  document.getElementById("n-errata").textContent = `(${n.misprints} misprints in ${n.rows} rows)`;
}
const c = show("conventions-list", cvs, (l) => l.map(conventionHtml).join(""), "None yet.");
const f = show("findings-list", fds, (l) => l.map(findingHtml).join(""), "None found yet.");
document.getElementById("index-table").innerHTML = indexHtml(e, c, f);
try {
  const h = await api("/api/health");
  const v = h.verification;
  document.getElementById("errata-status").textContent =
    `${countsSentence(e)}; ${c.length} conventions, ${f.length} findings` +
    (v.state === "done" ? "." : ` — verification ${v.state}: ${v.cases_done} of ${v.cases_total} cases so far.`);
} catch { /* the tables stand on their own */ }
window.addEventListener("hashchange", openTarget);
openTarget();
document.body.dataset.ready = "1";
