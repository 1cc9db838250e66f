// Cite and link, as DLMF and LMFDB do: BibTeX for the paper (with its
// DOI) and for this explorer (author, year, version, the page's URL and the reader's access
// date), a visible permalink (¶) on every claim, a Cite box on every claim and case page,
// and a box saying what was checked on the case and how, and what was not.
// The fields come from GET /api/cite (app/services/reader_pages.cite_data: the paper's entry
// is catalogue/references.yaml's "this-paper"); the layout of an entry is the same as
// reader_pages.bibtex, which renders the boxes of the server-built pages that this module
// upgrades with the page's full address and today's date.
"use strict";

import { api, escapeHtml } from "./api.js";

let DATA = null;

export async function citeData() {
  if (!DATA) DATA = await api("/api/cite");
  return DATA;
}

/** The reader's date, YYYY-MM-DD (local time: the day the reader accessed the page). */
export function today(now = new Date()) {
  const p = (n) => String(n).padStart(2, "0");
  return `${now.getFullYear()}-${p(now.getMonth() + 1)}-${p(now.getDate())}`;
}

export function bibtex(entry, extra = {}) {
  const fields = Object.entries({ ...entry.fields, ...extra }).filter(([, v]) => v);
  const width = Math.max(...fields.map(([k]) => k.length));
  const body = fields.map(([k, v]) => `  ${k.padEnd(width)} = {${v}}`).join(",\n");
  return `@${entry.type}{${entry.key},\n${body}\n}`;
}

/** The explorer's entry for `url` (a page, or a claim on it), accessed today. */
export function softwareBibtex(data, url, note) {
  const d = today();
  const extra = { year: d.slice(0, 4), url, urldate: d };
  if (note) extra.note = note;
  return bibtex(data.software, extra);
}

const pageUrl = (hash = "") => `${location.origin}${location.pathname}${hash}`;

function boxHtml(data, url, note, what) {
  return `<p class="citeurl">Permalink: <a href="${escapeHtml(url)}">${escapeHtml(url)}</a></p>` +
    `<p>The paper (<a href="https://doi.org/${escapeHtml(data.paper.fields.doi)}">doi:${escapeHtml(data.paper.fields.doi)}</a>):</p>` +
    `<pre class="bibtex" data-cite="paper" tabindex="0">${escapeHtml(bibtex(data.paper))}</pre>` +
    `<p>This explorer, ${escapeHtml(what)} (accessed ${today()}):</p>` +
    `<pre class="bibtex" data-cite="software" tabindex="0">${escapeHtml(softwareBibtex(data, url, note))}</pre>`;
}

/** The case page's Cite box, with the link to the case's JSON record. */
export function caseCiteHtml(data, c) {
  const json = `/api/cases/${c.id}`;
  const what = c.in_tables === false ? `${c.title}: a case beyond the tables of Borisov and Mamaev (2002), run by computation`
    : `${c.title}: Table ${c.table}, column ${c.column} of Borisov and Mamaev (2002), checked by computation`;
  return boxHtml(data, pageUrl(), what, "this case page") +
    `<p class="jsonlink">The case's record as data: <a href="${escapeHtml(json)}" type="application/json">${escapeHtml(json)}</a> (JSON: every claim with its printed formula, verdict and residual).</p>`;
}

/** A claim's visible permalink, put first in its header. */
export function permalinkHtml(anchorId, label) {
  return `<a class="permalink" href="#${escapeHtml(anchorId)}" title="Permalink to this claim" ` +
    `aria-label="Permalink to ${escapeHtml(label)}">¶</a>`;
}

function claimLabel(cl) {
  return `${cl.kind.replace(/-/g, " ")}${cl.number ? ` ${cl.number}` : ""}`;
}

/** Every claim article of a case page gets its permalink and a Cite box (collapsed). */
export function decorateClaims(data, c, anchor) {
  for (const cl of c.claims) {
    const id = anchor(cl.id);
    const el = document.getElementById(id);
    if (!el || el.querySelector(".permalink")) continue;
    const head = el.querySelector("header") || el;
    head.insertAdjacentHTML("afterbegin", permalinkHtml(id, `the claim ${claimLabel(cl)}`));
    const note = `${c.title}: the claim ${claimLabel(cl)} of Borisov and Mamaev (2002) (${cl.plain}), checked by computation`;
    el.insertAdjacentHTML("beforeend", `<details class="cite-claim"><summary>Cite this claim</summary>` +
      `${boxHtml(data, pageUrl(`#${id}`), note, "this claim")}</details>`);
  }
}

// ---- what was checked on a case, and how (from the case's records and /api/how-we-check)

const NOT_RUN = { open_problem: "the paper states it as open", formula_not_printed: "the paper prints no formula for it",
  not_checkable: "no pointwise computation decides it" };

export function checkedHtml(c, how, anchor) {
  const kindOf = {};
  for (const k of how.kinds) for (const n of k.checks) kindOf[n] = k;
  const rows = new Map();
  const notRun = [];
  for (const cl of c.claims) {
    // a check that ran and could not decide says so ("inconclusive: ..."): it ran
    const inconclusive = cl.verdict.verdict === "unchecked" && /^inconclusive/.test(cl.verdict.message || "");
    const v = inconclusive ? "inconclusive" : cl.verdict.verdict;
    if (NOT_RUN[cl.check] || v === "unchecked") {
      notRun.push(cl);
      continue;
    }
    const k = kindOf[cl.check] || { id: "", title: cl.check, points: "" };
    const r = rows.get(k.title) || { k, n: 0, verified: 0, convention: 0, fails: 0, evidence: 0, inconclusive: 0, pending: 0 };
    r.n += 1;
    // a printed form that holds only under a convention the text supports is not "holds"
    const col = v === "verified" && cl.verdict.qualifier === "convention" ? "convention" : v;
    r[col] = (r[col] || 0) + 1;
    rows.set(k.title, r);
  }
  const ran = c.claims.length - notRun.length;
  const cell = (x) => `<td>${x || "—"}</td>`;
  const body = [...rows.values()].map((r) =>
    `<tr><th scope="row"><a href="/how-we-check#${escapeHtml(r.k.id)}">${escapeHtml(r.k.title)}</a></th>` +
    `<td>${r.n}</td>${cell(r.verified)}${cell(r.convention)}${cell(r.fails)}${cell(r.evidence)}${cell(r.inconclusive)}${cell(r.pending)}` +
    `<td>${escapeHtml(r.k.points || "")}</td></tr>`).join("");
  const why = (cl) => NOT_RUN[cl.check] || "the check could not run on this server";
  const link = (cl) => `<a href="#${escapeHtml(anchor(cl.id))}">${escapeHtml(claimLabel(cl))}</a>`;
  const not = notRun.length
    ? `<p><strong>Not checked (${notRun.length}):</strong> ${notRun.map((cl) => `${link(cl)} (${escapeHtml(why(cl))})`).join("; ")}.</p>`
    : "<p><strong>Not checked:</strong> none; every claim of this case was computed.</p>";
  const corrected = c.claims.filter((cl) => (cl.corrections || []).length).length;
  const fix = corrected ? ` ${corrected} printed form${corrected === 1 ? "" : "s"} fail${corrected === 1 ? "s" : ""} where the project's correction, checked the same way, holds (each under its claim and on <a href="/errata">the errata page</a>).` : "";
  return `<p>${c.claims.length} claims on this page; ${ran} decided or tested by computation, ${notRun.length} not.${fix} ` +
    `Each check evaluates the printed formula at random states with exact derivatives (<a href="/how-we-check">how we check</a>).</p>` +
    `<div class="table-wrap"><table class="checked"><thead><tr><th scope="col">kind of check</th><th scope="col">claims</th>` +
    `<th scope="col">holds</th><th scope="col">holds under a convention</th><th scope="col">fails as printed</th>` +
    `<th scope="col">evidence</th><th scope="col">inconclusive</th><th scope="col">checking</th>` +
    `<th scope="col">at how many points</th></tr></thead><tbody>${body}</tbody></table></div>${not}`;
}

// ---- the server-built boxes (/bibliography, the home page): the page's full address and
// the reader's date instead of the server's

export async function upgradeStaticBoxes(root = document) {
  const pres = root.querySelectorAll('section.cite pre[data-cite="software"]');
  if (!pres.length) return;
  const data = await citeData();
  for (const pre of pres) pre.textContent = softwareBibtex(data, pageUrl());
}

upgradeStaticBoxes().catch(() => { /* the server's text stays */ });
