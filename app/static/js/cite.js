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
import { MACROS, mathHtml, printedHtml } from "./latex.js";

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

/** The explorer's key for a page or a claim: stable, unique, in characters every BibTeX
 * reads (reader_pages.cite_key): "sphere/body-of-revolution/measure" ->
 * "RollingHierarchy:sphere:body-of-revolution:measure". */
export function citeKey(data, what = "") {
  const rest = what.replace(/[^A-Za-z0-9_.-]+/g, ":").replace(/^:+|:+$/g, "");
  return rest ? `${data.software.key}:${rest}` : data.software.key;
}

export function bibtex(entry, extra = {}, key = entry.key) {
  const fields = Object.entries({ ...entry.fields, ...extra }).filter(([, v]) => v);
  const width = Math.max(...fields.map(([k]) => k.length));
  const body = fields.map(([k, v]) => `  ${k.padEnd(width)} = {${v}}`).join(",\n");
  return `@${entry.type}{${key},\n${body}\n}`;
}

/** The explorer's fields for `url` (a page, or a claim on it), accessed today. */
function softwareFields(url, note) {
  const d = today();
  const extra = { year: d.slice(0, 4), url, urldate: d };
  if (note) extra.note = note;
  return extra;
}

export function softwareBibtex(data, url, note, key = data.software.key) {
  return bibtex(data.software, softwareFields(url, note), key);
}

// ---- the same entries as CSL-JSON and RIS (reference managers read either)

const unbrace = (s) => String(s || "").replace(/[{}]/g, "");
const dateParts = (d) => d.split("-").map(Number);

function cslPaper(data) {
  const f = data.paper.fields;
  return { id: data.paper.key, type: "article-journal", title: f.title,
    author: f.author.split(" and ").map((a) => { const [family, given] = a.split(", "); return { family, given }; }),
    "container-title": f.journal, volume: f.volume, issue: f.number, page: f.pages.replace("--", "-"),
    issued: { "date-parts": [[Number(f.year)]] }, DOI: f.doi };
}

export function cslJson(data, url, note, key) {
  const f = { ...data.software.fields, ...softwareFields(url, note) };
  const sw = { id: key, type: "software", title: f.title, author: [{ literal: unbrace(f.author) }],
    version: f.version, URL: url, issued: { "date-parts": [[Number(f.year)]] },
    accessed: { "date-parts": [dateParts(f.urldate)] }, note: f.note };
  return JSON.stringify([sw, cslPaper(data)], null, 2);
}

export function ris(data, url, note, key) {
  const f = { ...data.software.fields, ...softwareFields(url, note) };
  const p = data.paper.fields;
  const [sp, ep] = p.pages.split("--");
  const line = (k, v) => (v ? `${k}  - ${v}\n` : "");
  const sw = line("TY", "COMP") + line("ID", key) + line("AU", unbrace(f.author)) + line("TI", f.title) +
    line("ET", f.version) + line("PY", f.year) + line("UR", url) + line("Y2", f.urldate) + line("N1", f.note) + "ER  - \n";
  const paper = line("TY", "JOUR") + line("ID", data.paper.key) + p.author.split(" and ").map((a) => line("AU", a)).join("") +
    line("TI", p.title) + line("JO", p.journal) + line("VL", p.volume) + line("IS", p.number) +
    line("SP", sp) + line("EP", ep) + line("PY", p.year) + line("DO", p.doi) + "ER  - \n";
  return `${sw}\n${paper}`;
}

/** Where the explorer is: the configured public address (ROLLING_PUBLIC_URL), else the
 * address this page was asked for. */
export const baseUrl = (data) => (data && data.public_url) || location.origin;
const pageUrl = (data, hash = "") => `${baseUrl(data)}${location.pathname}${hash}`;

function boxHtml(data, url, note, what, key, lead = "") {
  return `<p class="citeurl">Permalink: <a href="${escapeHtml(url)}">${escapeHtml(url)}</a></p>${lead}` +
    `<p>The paper (<a href="https://doi.org/${escapeHtml(data.paper.fields.doi)}">doi:${escapeHtml(data.paper.fields.doi)}</a>):</p>` +
    `<pre class="bibtex" data-cite="paper" tabindex="0">${escapeHtml(bibtex(data.paper))}</pre>` +
    `<p>This explorer, ${escapeHtml(what)} (version ${escapeHtml(data.software.fields.version)}, accessed ${today()}):</p>` +
    `<pre class="bibtex" data-cite="software" data-key="${escapeHtml(key)}" tabindex="0">${escapeHtml(softwareBibtex(data, url, note, key))}</pre>` +
    `<details class="cite-formats"><summary>CSL-JSON and RIS</summary>` +
    `<p>CSL-JSON (Zotero, Mendeley, pandoc):</p><pre class="csl" data-cite="csl" tabindex="0">${escapeHtml(cslJson(data, url, note, key))}</pre>` +
    `<p>RIS:</p><pre class="ris" data-cite="ris" tabindex="0">${escapeHtml(ris(data, url, note, key))}</pre></details>`;
}

/** The case page's Cite box, with the link to the case's JSON record. */
export function caseCiteHtml(data, c) {
  const json = `/api/cases/${c.id}`;
  const what = c.in_tables === false ? `${c.title}: a case beyond the tables of Borisov and Mamaev (2002), run by computation`
    : `${c.title}: Table ${c.table}, column ${c.column} of Borisov and Mamaev (2002), checked by computation`;
  return boxHtml(data, pageUrl(data), what, "this case page", citeKey(data, `case/${c.id}`)) +
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

/** The paper's own macros (latex.js MACROS) expanded, so that a citing document needs
 * only amsmath: those with brace arguments first, then the others (errata_pages.expand). */
export function expandMacros(tex) {
  let t = tex;
  for (const [name, body] of Object.entries(MACROS)) {
    const n = Math.max(0, ...[...body.matchAll(/#(\d)/g)].map((m) => Number(m[1])));
    if (!n) continue;
    const re = new RegExp(`\\\\${name.slice(1)}(?![A-Za-z])${"\\s*\\{([^{}]*)\\}".repeat(n)}`, "g");
    t = t.replace(re, (...m) => body.replace(/#(\d)/g, (_, k) => m[Number(k)]));
  }
  return t.replace(/\\([A-Za-z]+)(?![A-Za-z])/g, (all, name) => {
    const body = MACROS[`\\${name}`];
    return body && !body.includes("#") ? body : all;
  });
}

// a formula in a BibTeX note: inline math on one line, the paper's macros expanded, an
// alignment outside any environment put in "aligned" as mathHtml does (errata_pages._inline)
function texInline(tex) {
  let t = expandMacros(tex).trim().replace(/(\\\\\s*)+$/, "");
  if (!t.includes("$")) {
    if (/(^|[^\\])&/.test(t) && !/\\begin\{/.test(t)) t = `\\begin{aligned}${t}\\end{aligned}`;
    t = `$${t}$`;
  }
  return t.replace(/\s+/g, " ").trim();
}

/** What a claim's citation says was shown: its mark in words and the formula that holds --
 * the project's corrected form where the printed one is misprinted, the printed form then
 * labelled "as printed", with the erratum's address. */
export function claimCitation(data, c, cl) {
  const v = cl.verdict || {};
  const mark = v.mark || "pending";
  const m = (data.marks || {})[mark] || { shape: "", name: mark };
  const markWords = mark === "pending" ? "checking (not yet decided)" : m.name;
  const corr = (cl.corrections || []).find((r) => r.printed_tex) || null;
  const base = baseUrl(data);
  const errata = (v.errata || []).map((e) => `${base}/errata#e-${e}`);
  const head = `${c.title}: the claim ${claimLabel(cl)} of Borisov and Mamaev (2002). Mark: ${markWords}`;
  let note;
  let holds = null;
  let printedLabel = "as printed";
  if (mark === "after-correction" && corr) {
    holds = corr.printed_tex;
    note = `${head}. The formula that holds, the project's correction: ${texInline(corr.printed_tex)}. ` +
      `As printed (fails): ${texInline(cl.printed)}`;
    printedLabel = "as printed (fails; misprint)";
  } else if (mark === "as-printed" || mark === "under-convention") {
    holds = cl.printed;
    note = `${head}${mark === "under-convention" && v.mark_note ? ` (${v.mark_note.replace(/\.$/, "")})` : ""}. ` +
      `As printed: ${texInline(cl.printed)}`;
    printedLabel = mark === "under-convention" ? "as printed (holds under the convention)" : "as printed (holds)";
  } else if (mark === "project-formula") {
    holds = cl.printed;
    note = `${head}. The project's formula (the paper prints none): ${texInline(cl.printed)}`;
    printedLabel = "of the project (holds; the paper prints none)";
  } else if (mark === "after-correction") {
    // a correction without its formula here: the erratum has it
    note = `${head}. As printed (fails): ${texInline(cl.printed)}`;
    printedLabel = "as printed (fails; misprint)";
  } else {
    // fails, evidence, not checkable, checking: nothing is cited as holding
    note = `${head}${v.mark_note ? ` (${v.mark_note.replace(/\.$/, "")})` : ""}. As printed: ${texInline(cl.printed)}`;
    printedLabel = mark === "pending" ? "as printed (checking)" : `as printed (${m.name})`;
  }
  if (errata.length) note += `. Erratum: ${errata.join(", ")}`;
  const lead = `<div class="cite-shown"><p class="cite-mark">Mark: <strong class="badge ${escapeHtml(mark)}">${escapeHtml(`${m.shape || ""} ${markWords}`.trim())}</strong>` +
    `${v.mark_note ? ` (${escapeHtml(v.mark_note.replace(/\.$/, ""))})` : ""}.</p>` +
    (holds && corr && mark === "after-correction"
      ? `<p>The formula that holds (the project's correction):</p><div class="printed cite-holds" tabindex="0">${mathHtml(holds, true)}</div>` : "") +
    `<p>The formula ${escapeHtml(printedLabel)}:</p><div class="printed cite-printed" tabindex="0">${printedHtml(cl.printed)}</div>` +
    (errata.length ? `<p class="cite-erratum">Erratum: ${(v.errata || []).map((e, i) =>
      `<a href="/errata#e-${escapeHtml(e)}">${escapeHtml(errata[i])}</a>`).join(", ")}</p>` : "") + `</div>`;
  return { note, lead, key: citeKey(data, cl.id) };
}

/** Every claim article of a case page gets its permalink and a Cite box (collapsed). */
export function decorateClaims(data, c, anchor) {
  for (const cl of c.claims) {
    const id = anchor(cl.id);
    const el = document.getElementById(id);
    if (!el || el.querySelector(".permalink")) continue;
    const head = el.querySelector("header") || el;
    head.insertAdjacentHTML("afterbegin", permalinkHtml(id, `the claim ${claimLabel(cl)}`));
    const { note, lead, key } = claimCitation(data, c, cl);
    el.insertAdjacentHTML("beforeend", `<details class="cite-claim"><summary>Cite this claim</summary>` +
      `${boxHtml(data, pageUrl(data, `#${id}`), note, "this claim", key, lead)}</details>`);
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
  for (const pre of pres) pre.textContent = softwareBibtex(data, pageUrl(data), null, pre.dataset.key || data.software.key);
}

upgradeStaticBoxes().catch(() => { /* the server's text stays */ });
