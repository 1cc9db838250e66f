// Marks: one per meaning, from the vocabulary the server defines once
// (solvers/verify/marks.yaml, GET /api/marks), drawn the same way in the tables, on the
// case pages and on /how-we-check. Each mark is a shape and a word, so it reads without
// colour; what goes with it (the convention, the misprint and its erratum, what an
// inconclusive check found) is visible text behind a disclosure that opens on a tap,
// never in a hover title alone. A cell's mark is given for each body (case) it spans, in
// column order, so a merged cell never hides one body's mark behind another's.
"use strict";

import { claimAnchor as anchor } from "./anchor.js";
import { api, escapeHtml } from "./api.js";

let vocabulary = { marks: [], cells: {}, cells_total: 0, summary: "" };
try {
  vocabulary = await api("/api/marks");
} catch {
  // without the vocabulary a mark still shows its id as its word
}
const BY_ID = Object.fromEntries(vocabulary.marks.map((m) => [m.id, m]));

export function markInfo(id) {
  return BY_ID[id] || { id, shape: "?", word: id, name: id, definition: "" };
}

// the counts and their sentence as the server last computed them (home page summary)
export async function overview() {
  try {
    vocabulary = await api("/api/marks");
  } catch {
    // keep the last one
  }
  return vocabulary;
}


// the erratum of a misprinted formula: its row on /errata
export function erratumLinks(errata) {
  if (!errata || !errata.length) return "";
  return errata.map((id) => `<a href="/errata#e-${escapeHtml(id)}">erratum</a>`).join(", ");
}

function whyHtml(marks) {
  const seen = new Set();
  const parts = [];
  for (const m of marks) {
    if (!m.mark_note && !(m.errata && m.errata.length)) continue;
    const key = `${m.mark}|${m.mark_note || ""}`;
    if (seen.has(key)) continue;
    seen.add(key);
    const info = markInfo(m.mark);
    const who = marks.length > 1 && m.column ? `column ${m.column}, ` : "";
    const links = m.mark === "after-correction" ? erratumLinks(m.errata) : "";
    parts.push(`<p>${who}${escapeHtml(info.name)}: ${escapeHtml(m.mark_note || "")}` +
      `${links ? ` (${links})` : ""}</p>`);
  }
  return parts.length
    ? `<details class="mark-why"><summary>why?</summary>${parts.join("")}</details>` : "";
}

// A table cell's marks: the shape of each body's mark (with its column number when the
// cell is merged), the word once per run of equal marks, the meaning for screen readers.
export function markHtml(summary, href, { why = true } = {}) {
  const marks = summary.marks && summary.marks.length ? summary.marks
    : [{ case: "", column: null, mark: summary.mark, mark_note: null, errata: [] }];
  const many = marks.length > 1;
  let html = "";
  marks.forEach((m, i) => {
    const info = markInfo(m.mark);
    const col = many && m.column ? `<sub class="col">${m.column}</sub>` : "";
    html += `<span class="mk ${escapeHtml(m.mark)}" data-case="${escapeHtml(m.case)}" aria-hidden="true">${info.shape}${col}</span>`;
    const next = marks[i + 1];
    if (!next || next.mark !== m.mark) html += `<span class="mkword" aria-hidden="true">${escapeHtml(info.word)}</span>`;
  });
  const said = marks.map((m) => (many && m.column ? `column ${m.column}: ` : "") + markInfo(m.mark).name).join(", ");
  return `<a class="cellmark ${escapeHtml(summary.mark)}" href="${href}">` +
    `${html}<span class="sr-only">${escapeHtml(said)}</span></a>${why ? whyHtml(marks) : ""}`;
}

// A claim's mark: shape and full name.
export function badgeHtml(mark) {
  const info = markInfo(mark);
  return `<span class="badge ${escapeHtml(mark)}">${info.shape} ${escapeHtml(info.name)}</span>`;
}

// One line under a claim's mark: the sentence that goes with it, and the erratum it links to.
export function markNoteHtml(v) {
  if (!v || (!v.mark_note && !(v.errata && v.errata.length))) return "";
  const links = v.mark === "after-correction" ? erratumLinks(v.errata) : "";
  const inherits = v.qualifier === "inherited" && v.inherits
    ? ` It fails through <a href="#${anchor(v.inherits)}">the formula it uses</a>.` : "";
  const note = (v.mark_note || "").replace(/\.$/, "");
  return `<p class="marknote ${escapeHtml(v.mark)}">${escapeHtml(note)}` +
    `${links ? ` (${links})` : ""}.${inherits}</p>`;
}

// "N claims hold as printed, ..." as shape + count + word, one badge per mark
export function tallyHtml(counts) {
  return vocabulary.marks.filter((m) => counts[m.id])
    .map((m) => `<span class="badge ${m.id}">${m.shape} ${counts[m.id]} ${escapeHtml(m.word)}</span>`).join(" ");
}
