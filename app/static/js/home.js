// Home: Tables 1 and 2 as printed (same rows, columns and merged cells, the paper's gray
// and partial fill), a verdict mark in every checkable cell, case headers linking to
// /case/<id>; the rubber tables' statements typeset like their cells.
"use strict";

import { api, escapeHtml } from "./api.js";
import { kernelSentence } from "./kernels.js";
import { textHtml } from "./latex.js";
import { markHtml, overview } from "./marks.js";
import { pinHeader } from "./pinned_head.js";

function katexReady() {
  return new Promise((resolve) => {
    if (window.katex) return resolve();
    document.querySelector('script[src*="katex"]').addEventListener("load", () => resolve());
  });
}

// why a cell is shaded as it is: a disclosure that opens on click, tap or Enter (never a
// hover title, which a touch screen cannot show); the same markup as the server's (ssr.py)
function shadeWhy(cell) {
  if (!cell.shade_note) return "";
  const word = cell.shade === "partial" ? "partial" : cell.shade === "full" ? "gray" : "unshaded";
  return `<details class="shade-why"><summary>why ${word}?</summary><p>${escapeHtml(cell.shade_note)}</p></details>`;
}

function cellHtml(cell, table) {
  const cls = [`shade-${cell.shade}`];
  const first = cell.merged[0];
  const mark = cell.verdict
    ? markHtml(cell.verdict, `/case/${first}#row-${cell.row}`)
    : "";
  const why = shadeWhy(cell);
  const shadeText = cell.shade === "full" ? "invariant exists" : cell.shade === "partial" ? "incomplete set of integrals" : "";
  const sr = shadeText ? `<span class="sr-only"> (${shadeText})</span>` : "";
  const cols = cell.colspan > 1 ? ` colspan="${cell.colspan}"` : "";
  const cases = cell.merged.map((c) => table.columns.find((x) => x.id === c)?.column).join(" ");
  return `<td${cols} class="${cls.join(" ")}" data-cases="${escapeHtml(cell.merged.join(" "))}" data-columns="${cases}">` +
    `<div class="cell-body">${textHtml(cell.printed)}${sr}</div>${why}${mark}</td>`;
}

function tableHtml(t) {
  const head = t.columns.map((c) =>
    `<th scope="col" class="case-head"><a href="${c.href}" data-case="${escapeHtml(c.id)}">` +
    `<span class="colno">${c.column}</span> <span class="coltitle">${escapeHtml(c.title)}</span></a></th>`).join("");
  const lastHeader = [...t.rows].reverse().find((r) => r.header)?.key;
  const rows = [];
  for (const grow of t.grid) {
    const row = t.rows.find((r) => r.key === grow.key);
    const subs = grow.cells.some((c) => c.subrow);
    const rowspan = subs ? ' rowspan="2"' : "";
    const cls = [row.header ? "hdr" : "inv", `row-${row.key}`];
    if (row.key === lastHeader && !subs) cls.push("double-rule");
    rows.push(`<tr class="${cls.join(" ")}"><th scope="row"${rowspan}>${textHtml(row.printed)}</th>` +
      grow.cells.map((c) => cellHtml(c, t)).join("") + "</tr>");
    if (subs) {
      // Table 2: the restrictions row has a second line (a = 2R) under one column
      const cells = [];
      for (const c of grow.cells) {
        for (const id of c.merged) {
          const sub = c.subrow && (c.subrow_case || c.merged[0]) === id ? textHtml(c.subrow.printed) : "";
          cells.push(`<td class="shade-none subrow">${sub}</td>`);
        }
      }
      const sc = ["hdr", "subrow-row"];
      if (row.key === lastHeader) sc.push("double-rule");
      rows.push(`<tr class="${sc.join(" ")}">${cells.join("")}</tr>`);
    }
  }
  return `<table class="paper" id="tbl-${t.id}" aria-describedby="cap-${t.id}">` +
    `<thead><tr><th scope="col" class="corner"><span class="sr-only">row</span></th>${head}</tr></thead>` +
    `<tbody>${rows.join("")}</tbody></table>`;
}

async function showTable(id) {
  const section = document.getElementById(`table-${id}`);
  const wrap = section.querySelector(".table-wrap");
  try {
    const t = await api(`/api/tables/${id}`);
    section.querySelector("h2").textContent = t.caption_plain;
    wrap.innerHTML = tableHtml(t);
    section.querySelector(".remark").innerHTML = textHtml(t.remark_printed);
    return t;
  } catch (err) {
    wrap.innerHTML = `<p class="error" role="alert">Could not load the table: ${escapeHtml(err.message)}</p>`;
    return null;
  }
}

// the rubber tables' statements and their claims' (beyond the paper): the server draws them
// in plain text with their LaTeX in data-tex (ssr.py rubber_statement_html); typeset here as
// Tables 1 and 2's cells are, KaTeX's MathML carrying them to screen readers
function typesetRubber() {
  for (const el of document.querySelectorAll("#rubber [data-tex]")) el.innerHTML = textHtml(el.dataset.tex);
}

let lastDone = null;

// the cells of both tables counted by mark, in words (GET /api/marks; the same sentence the
// server wrote into the page)
async function showSummary() {
  const o = await overview();
  if (o.summary) document.getElementById("mark-summary").textContent = o.summary;
}

async function showStatus() {
  const el = document.getElementById("verify-status");
  try {
    const h = await api("/api/health");
    const v = h.verification;
    const done = `checks have run for ${v.cases_done} of ${v.cases_total} cases`;
    if (lastDone !== null && v.cases_done !== lastDone) {
      await Promise.all([showTable("plane"), showTable("sphere"), showSummary()]);   // new marks
    }
    lastDone = v.cases_done;
    document.getElementById("kernel-status").textContent = kernelSentence(h.kernels);
    const warming = ["starting", "running"].includes(h.kernels.state);
    if (v.state === "running" || warming) setTimeout(showStatus, 4000);
    el.textContent = v.state === "running"
      ? `Computing verdicts: ${v.cases_done} of ${v.cases_total} cases so far; the marks fill in as they come.`
      : v.state === "done" ? ""
        : v.state === "unavailable" ? "Checking is unavailable on this server: every cell shows as not checkable."
          : `Checking ${v.state}: ${done}.`;
  } catch {
    el.textContent = "";
  }
}

await katexReady();
typesetRubber();
await Promise.all([showTable("plane"), showTable("sphere"), showStatus(), showSummary()]);
for (const id of ["plane", "sphere"]) pinHeader(document.querySelector(`#table-${id} .table-wrap`));
document.body.dataset.ready = "1";
