// Verdict marks of table cells. A cell states a property; its mark is the verdict of that
// property for each body (case) the cell spans, one mark per body in column order, so a
// merged cell never hides one body's verdict behind another's. Everything a mark means is
// in visible text or in screen-reader text, never in the tooltip alone: the note "holds;
// printed formula corrected" is printed under the mark.
"use strict";

import { escapeHtml, VERDICT_ICON, VERDICT_TEXT } from "./api.js";

const ICON = VERDICT_ICON;
const WORD = {
  verified: "property holds", fails: "property fails", evidence: "numerical evidence",
  unchecked: "not checkable", pending: "checking",
};

export function markHtml(summary, href) {
  const marks = summary.marks && summary.marks.length ? summary.marks
    : [{ case: "", column: null, mark: summary.mark, notes: summary.notes || [] }];
  const many = marks.length > 1;
  const spans = marks.map((m) => {
    const col = many && m.column ? `<sub class="col">${m.column}</sub>` : "";
    return `<span class="mk ${m.mark}" data-case="${escapeHtml(m.case)}" aria-hidden="true">${ICON[m.mark] || "?"}${col}</span>`;
  }).join("");
  const said = marks.map((m) => (many && m.column ? `column ${m.column}: ` : "") + (WORD[m.mark] || m.mark) +
    (m.notes && m.notes.length ? ` (${m.notes.join("; ")})` : "")).join(", ");
  const notes = (summary.notes || []).map((n) => `<span class="cellnote">${escapeHtml(n)}</span>`).join("");
  return `<a class="cellmark ${summary.mark}" href="${href}" title="${escapeHtml(said)}">` +
    `${spans}<span class="sr-only">${escapeHtml(said)}</span></a>${notes}`;
}

export function badgeHtml(verdict) {
  return `<span class="badge ${verdict}">${VERDICT_ICON[verdict]} ${VERDICT_TEXT[verdict] || verdict}</span>`;
}

const QUALIFIER_TEXT = {
  convention: "holds under a convention",
  misprint: "misprint: the project's correction holds",
  inherited: "inherited failure",
  "refuted-conjecture": "refuted conjecture",
  refuted: "refuted statement",
  "formula-free": "formula-free test",
};

// One line under a claim's verdict saying what kind of verdict it is.
export function qualifierHtml(v) {
  if (!v || !v.qualifier) return "";
  let extra = "";
  if (v.qualifier === "convention" && v.convention) extra = `: ${escapeHtml(v.convention)}`;
  if (v.qualifier === "inherited" && v.inherits) {
    extra = `: fails only through <a href="#claim-${v.inherits.replace(/[^A-Za-z0-9_-]+/g, "_")}">${escapeHtml(v.inherits)}</a>`;
  }
  if (v.qualifier === "refuted-conjecture" && v.finding) extra = `: found ${escapeHtml(v.finding)}`;
  const link = ["misprint", "inherited", "convention", "refuted-conjecture", "refuted"].includes(v.qualifier)
    ? ` <a href="/errata">errata</a>` : "";
  return `<p class="qualifier ${v.qualifier}"><strong>${QUALIFIER_TEXT[v.qualifier] || v.qualifier}</strong>${extra}.${link}</p>`;
}
