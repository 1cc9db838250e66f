// /errata: misprints with their corrections, conventions, and the project's findings, from
// GET /api/errata, /api/conventions and /api/findings.
"use strict";

import { api, escapeHtml, fmt } from "./api.js";
import { printedHtml } from "./latex.js";

function katexReady() {
  return new Promise((resolve) => {
    if (window.katex) return resolve();
    document.querySelector('script[src*="katex"]').addEventListener("load", () => resolve());
  });
}

const anchor = (id) => "claim-" + id.replace(/[^A-Za-z0-9_-]+/g, "_");
const caseLink = (e) => `<a href="/case/${e.case}#${anchor(e.claim)}">${escapeHtml(e.case)}</a>`;
const where = (e) => escapeHtml([e.number, e.where, e.section].filter(Boolean).join(" · "));
const res = (x) => (x === null || x === undefined ? "n/a" : fmt(x, 2));

function exactHtml(ex, what) {
  if (!ex) return "";
  // the witness (a rational point and residual) can run to thousands of digits: behind a toggle
  const w = ex.witness !== undefined && ex.witness !== null
    ? `<details><summary>rational witness point and its exact residual</summary>` +
      `<code tabindex="0">${escapeHtml(JSON.stringify(ex.witness))}</code></details>` : "";
  const bound = ex.holds && ex.bound ? ` ${escapeHtml(ex.bound)}.` : "";
  return `<div class="exact"><p>Exact check of the ${what}: ` +
    `${ex.holds ? "holds" : "does not hold"} at ${ex.points} rational point${ex.points === 1 ? "" : "s"}.${bound}</p>` +
    `<details><summary>method</summary><p>${escapeHtml(ex.method || "")}</p></details>${w}</div>`;
}

function erratumHtml(e) {
  const kind = e.kind === "inherited"
    ? `inherited failure: it uses <a href="#e-${escapeHtml(e.inherits)}">${escapeHtml(e.inherits)}</a>, which is misprinted`
    : "misprint";
  return `<article class="erratum" id="e-${escapeHtml(e.claim)}">` +
    `<header><span class="badge fails">✗ ${kind.startsWith("misprint") ? "misprint" : "inherited"}</span> ` +
    `<strong>${where(e)}</strong> — ${caseLink(e)} <span class="cid">${escapeHtml(e.claim)}</span></header>` +
    `<p class="kindline">${kind}</p>` +
    `<div class="pair"><div><h3>Printed</h3><div class="printed" tabindex="0">${printedHtml(e.printed)}</div>` +
    `<p>residual ${res(e.residual_printed)}</p></div>` +
    `<div><h3>Corrected (the project)</h3><p class="corrected">${escapeHtml(e.corrected)}</p>` +
    `<p>residual ${res(e.residual_corrected)} <span class="badge ${e.corrected_verdict === "verified" ? "verified" : "fails"}">` +
    `${e.corrected_verdict === "verified" ? "✓ holds" : "✗ fails"}</span></p></div></div>` +
    exactHtml(e.exact, "printed form") + exactHtml(e.corrected_exact, "corrected form") +
    `<p class="repro">Reproduce: <code>${escapeHtml(e.reproduce)}</code></p></article>`;
}

function conventionHtml(e) {
  return `<article class="erratum convention" id="c-${escapeHtml(e.claim)}">` +
    `<header><span class="badge verified">✓ holds under a convention</span> <strong>${where(e)}</strong> — ` +
    `${caseLink(e)} <span class="cid">${escapeHtml(e.claim)}</span></header>` +
    `<div class="printed" tabindex="0">${printedHtml(e.printed)}</div>` +
    `<p><strong>Convention:</strong> ${escapeHtml(e.convention || "")}</p>` +
    `<p>residual under it ${res(e.residual_under_convention)}; read with the project's convention ${res(e.residual_printed)}</p>` +
    `<p class="repro">Reproduce: <code>${escapeHtml(e.reproduce)}</code></p></article>`;
}

function findingHtml(e) {
  const ev = Object.entries(e.evidence || {}).map(([k, v]) =>
    `<li>${escapeHtml(k)}: ${escapeHtml(typeof v === "number" ? fmt(v, 2) : String(v))}</li>`).join("");
  const kind = e.kind === "refuted-conjecture" ? "refuted conjecture" : "refuted statement";
  return `<article class="finding" id="f-${escapeHtml(e.claim)}">` +
    `<header><span class="badge evidence">${kind}</span> <strong>${escapeHtml(e.title)}</strong></header>` +
    `<p>Where: ${where(e)} — ${caseLink(e)} <span class="cid">${escapeHtml(e.claim)}</span></p>` +
    `<div class="printed" tabindex="0">${printedHtml(e.printed)}</div>` +
    `<p><strong>Found:</strong> ${escapeHtml(e.finding)}</p>` +
    `<details><summary>Evidence</summary><ul>${ev}</ul></details>` +
    exactHtml(e.exact, "claim") +
    `<p class="repro">Reproduce: <code>${escapeHtml(e.reproduce)}</code></p></article>`;
}

async function show(id, path, render, empty) {
  const el = document.getElementById(id);
  try {
    const list = await api(path);
    el.innerHTML = list.length ? list.map(render).join("") : `<p>${empty}</p>`;
    return list.length;
  } catch (err) {
    el.innerHTML = `<p class="error" role="alert">Could not load: ${escapeHtml(err.message)}</p>`;
    return 0;
  }
}

await katexReady();
const [nf, ne, nc] = await Promise.all([
  show("findings-list", "/api/findings", findingHtml, "None found yet."),
  show("errata-list", "/api/errata", erratumHtml, "No misprint found yet."),
  show("conventions-list", "/api/conventions", conventionHtml, "None yet."),
]);
try {
  const h = await api("/api/health");
  const v = h.verification;
  document.getElementById("errata-status").textContent =
    `${ne} misprinted formulas, ${nc} conventions, ${nf} findings` +
    (v.state === "done" ? "." : ` — verification ${v.state}: ${v.cases_done} of ${v.cases_total} cases so far.`);
} catch { /* the lists stand on their own */ }
document.body.dataset.ready = "1";
