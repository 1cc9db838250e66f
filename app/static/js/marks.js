// Verdict marks: an icon, a word for screen readers and a tooltip with the counts.
"use strict";

import { escapeHtml, VERDICT_ICON } from "./api.js";

export function markHtml(summary, href) {
  const n = summary.claims.length;
  const parts = Object.entries(summary.counts).map(([v, k]) => `${k} ${v}`);
  const title = `${n} claim${n > 1 ? "s" : ""}: ${parts.join(", ")}`;
  const counts = Object.entries(summary.counts)
    .map(([v, k]) => `<span class="mk ${v}" aria-hidden="true">${VERDICT_ICON[v]}${k > 1 ? k : ""}</span>`)
    .join("");
  return `<a class="cellmark ${summary.mark}" href="${href}" title="${escapeHtml(title)}">` +
    `${counts}<span class="sr-only">${escapeHtml(title)}</span></a>`;
}

export function badgeHtml(verdict) {
  return `<span class="badge ${verdict}">${VERDICT_ICON[verdict]} ${verdict}</span>`;
}
