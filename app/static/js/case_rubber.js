// A rubber case's page (/case/rubber-...: a body rolling without slipping and without
// spinning, beyond the 2002 paper): the head says so and links to the guide's equations and
// to the case's cells in the rubber tables of the home page; after each run two more plots,
// the constraint (ω, γ) and |γ| − 1, and the energy with the case's integrals, all against
// time, their values from POST /api/observables (solvers/models/observables.py) and the run.
"use strict";

import { api, escapeHtml } from "./api.js";
import { textHtml } from "./latex.js";
import { base, CONFIG } from "./plots.js";
import { $, C } from "./case_state.js";

const COLORS = ["#1f5f99", "#c2571a", "#2a8a3e", "#8e3ea8", "#b8860b"];
// rows a request carries at most (app/schemas/observables.py MAX_ROWS)
const MAX_ROWS = 4000;

export const isRubber = () => Boolean(C && C.rubber);

// the head's box and the cells of the rubber tables, in place of Tables 1 and 2's cells,
// each statement typeset from its LaTeX as Tables 1 and 2's cells are (latex.js textHtml)
export function showRubber() {
  const R = C.rubber;
  const box = document.createElement("div");
  box.className = "beyond-paper";
  box.id = "beyond-paper";
  box.dataset.testid = "beyond-paper";
  box.innerHTML = `<p>${escapeHtml(R.sentence)}</p>
    <p><a href="${escapeHtml(R.equations_href)}" id="rubber-equations">The rubber equations (guide: Rubber rolling)</a>
    · <a href="${escapeHtml(R.table_href)}" id="rubber-table">the rubber table on the home page</a></p>`;
  $("facts").after(box);
  $("h-in-table").textContent = "The case in the rubber tables";
  const rows = R.cells.map((c) => `<tr><th scope="row">${escapeHtml(c.row_words || c.row.replaceAll("_", " "))}</th>
    <td><span class="chip">${escapeHtml(c.mark)}</span> <span class="cell-statement">${textHtml(c.statement_tex)}</span>
    <a href="${escapeHtml(c.href)}" data-testid="rubber-cell">where it comes from</a></td></tr>`);
  $("cells").innerHTML = rows.length
    ? `<table class="cells" data-testid="rubber-cells"><tbody>${rows.join("")}</tbody></table>`
    : `<p class="status" data-testid="rubber-cells">No column of its own in the rubber tables: see <a href="${escapeHtml(R.table_href)}">the rubber table</a>.</p>`;
}

// every k-th row of the run (and its last), at most MAX_ROWS
function thin(run) {
  const n = run.state.length, k = Math.ceil(n / MAX_ROWS);
  const idx = [];
  for (let i = 0; i < n; i += k) idx.push(i);
  if (idx[idx.length - 1] !== n - 1) idx.push(n - 1);
  return { k, t: idx.map((i) => run.t[i]), state: idx.map((i) => run.state[i]) };
}

function lines(el, title, ytitle, series, note) {
  const traces = series.map(([name, x, y], j) => ({ type: "scatter", mode: "lines", x, y, name,
    line: { width: 1.8, color: COLORS[j % COLORS.length] } }));
  // automargin: the tick labels (1.5×10⁻¹⁰) and the axis titles keep their own room
  const layout = base(title, { xaxis: { title: { text: "t", standoff: 8 }, automargin: true },
    yaxis: { title: { text: ytitle, standoff: 6 }, exponentformat: "power", automargin: true },
    height: 400,
    annotations: note ? [{ text: note, xref: "paper", yref: "paper", x: 1, y: 1.02,
      xanchor: "right", yanchor: "bottom", showarrow: false, font: { size: 11, color: "#57606a" } }] : [] });
  return window.Plotly.react(el, traces, layout, CONFIG);
}

// the two plots of a rubber run; `request`: the run's request (its parameters)
export async function plotRubber(res, request) {
  const R = C.rubber;
  const plots = $("plots");
  for (const id of ["plot-constraint", "plot-integrals"]) {
    if (!$(id)) {
      const el = document.createElement("div");
      el.className = "plot";
      el.id = id;
      el.dataset.testid = id;
      plots.appendChild(el);
    }
  }
  const th = thin(res);
  const names = R.quantities.map((q) => q.name).filter((n) => n !== "energy");
  const obs = await api("/api/observables", { method: "POST",
    body: { case: C.id, params: request.params, state: th.state, names } });
  const label = (n) => (R.quantities.find((q) => q.name === n) || { label: n }).label;
  const note = th.k > 1 ? `every ${th.k}th sample` : "";
  await lines($("plot-constraint"), "The rubber constraint and |γ| − 1", "value",
    [["spin", th.t], ["gamma_norm_defect", th.t]].map(([n, t]) => [label(n), t, obs.series[n]]), note);
  const integrals = [["energy", res.t, res.invariants.energy]]
    .concat(names.filter((n) => n !== "spin" && n !== "gamma_norm_defect")
      .map((n) => [n, th.t, obs.series[n]]));
  await lines($("plot-integrals"), "Energy and the case's integrals", "value",
    integrals.map(([n, t, y]) => [label(n), t, y]), note);
  document.body.dataset.rubberPlots = String(Number(document.body.dataset.rubberPlots || 0) + 1);
}
