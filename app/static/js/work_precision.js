// The work-precision page: GET /api/work-precision (bench/work_precision.py) drawn as one
// log-log diagram per case (error against wall time, a trace per method), the Pareto table
// (ours against each reference at equal error) and what each tolerance of the default
// method buys.
"use strict";

import { api, download, escapeHtml } from "./api.js";
import { csvText } from "./permalink.js";
import { LEGEND_BELOW, MODEBAR } from "./plots.js";

const $ = (id) => document.getElementById(id);
const OURS = ["dop853", "vern9", "dop853+proj", "vern9+proj", "gauss8"];
const fmt = (x, d = 1) => (x == null ? "–" : Number(x).toExponential(d));
const ms = (s) => (s == null ? "–" : (s * 1e3).toFixed(s < 0.01 ? 2 : 1) + " ms");

function traces(runs) {
  const by = new Map();
  for (const r of runs) {
    if (!r.ok || r.error == null) continue;
    if (!by.has(r.method)) by.set(r.method, []);
    by.get(r.method).push(r);
  }
  return [...by.entries()].map(([method, rs]) => {
    rs.sort((a, b) => b.tol - a.tol);
    const ours = OURS.includes(method);
    return {
      name: method, x: rs.map((r) => r.error), y: rs.map((r) => r.wall_s * 1e3),
      text: rs.map((r) => `${r.knob === "h" ? "step h" : "tol"} ${fmt(r.tol, 0)}` + (r.rhs_calls ? `, ${r.rhs_calls} rhs calls` : "")
        + (r.order ? `, order ${r.order}` : "") + (r.precision ? `, ${r.precision}` : "")),
      mode: "lines+markers", type: "scatter",
      line: { width: ours ? 2.5 : 1.5, dash: ours ? "solid" : "dot" },
      hovertemplate: "%{text}<br>error %{x:.1e}<br>%{y:.3g} ms<extra>" + method + "</extra>",
    };
  });
}

function paretoTable(summary) {
  const rows = summary.table;
  const refs = Object.keys(rows[0]).filter((k) => !["level", "ours"].includes(k) && !k.startsWith("ratio_"));
  let html = `<div class="scroll-x" tabindex="0"><table class="wp-table"><caption>Least time reaching each error level: ours, and how
    many times longer each reference takes (— : no run of it reached the level)</caption>
    <thead><tr><th>error ≤</th><th>ours (method, tol)</th><th>time</th>`
    + refs.map((r) => `<th>${escapeHtml(r)}</th>`).join("") + "</tr></thead><tbody>";
  for (const row of rows) {
    const o = row.ours;
    html += `<tr><td>${fmt(row.level, 0)}</td><td>${o ? `${escapeHtml(o.method)}, ${o.knob === "h" ? "h = " : ""}${fmt(o.tol, 0)}` : "not reached"}</td>`
      + `<td>${o ? ms(o.wall_s) : "–"}</td>`
      + refs.map((r) => {
        const q = row[`ratio_${r}`];
        return `<td>${q ? q.toFixed(q < 10 ? 1 : 0) + "×" : "—"}</td>`;
      }).join("") + "</tr>";
  }
  return html + "</tbody></table></div>";
}

function buys(c, summary) {
  const items = summary.tolerance_buys.map((b) =>
    `<li>rtol = atol = ${fmt(b.rtol, 0)}: error ${fmt(b.error)} over t = 0 … ${c.t_end}, `
    + `${ms(b.wall_s)}, ${b.rhs_calls} right-hand-side calls</li>`).join("");
  return `<p>Default method for this case (fastest at the most error levels on the measured
    front): <strong>${escapeHtml(summary.default_method)}</strong>. What a tolerance buys:</p><ul>${items}</ul>`;
}

async function main() {
  let data;
  try {
    data = await api("/api/work-precision");
  } catch (e) {
    $("wp-status").textContent = `The measurements are not available: ${e.message}`;
    $("wp-status").classList.add("error");
    return;
  }
  $("wp-status").textContent = `Error: ${data.error}. ${data.samples} output times per run.`;
  const root = $("wp-cases");
  for (const c of data.cases) {
    const s = data.summary[c.id];
    const sec = document.createElement("section");
    const slug = c.id.replace("/", "-");
    sec.id = slug;
    sec.innerHTML = `<h2>${escapeHtml(c.id)} <span class="status">T = ${c.t_end}</span></h2>
      <p class="status">${c.note ? escapeHtml(c.note) + ". " : ""}Reference: ${escapeHtml(c.reference)}.
      ${escapeHtml(c.reference_check || "")}</p>
      <div class="wp-plot" id="plot-${slug}"></div>
      ${paretoTable(s)}${buys(c, s)}`;
    root.appendChild(sec);
    const runs = data.runs.filter((r) => r.case === c.id);
    // on a phone the legend under the plot is a column of one entry a row: the plot grows
    // by its height, so that the axes keep their own room and no entry lands on a tick label
    const plotTraces = traces(runs);
    $(`plot-${slug}`).style.height = window.innerWidth < 600
      ? `${320 + 22 * plotTraces.length}px` : "420px";
    // ticks as powers of ten (10⁻¹²), never SI prefixes (1p), and the unit in each title
    const logAxis = (title) => ({ type: "log", title: { text: title }, exponentformat: "power",
      showexponent: "all", dtick: 1 });
    window.Plotly.newPlot(`plot-${slug}`, plotTraces, {
      // a phone gets the short form of the x-axis title: the long one is wider than the plot
      // and a tick every third power of ten, upright: fifteen of them were turned on end
      // and drawn over the x-axis title
      xaxis: window.innerWidth < 600 ? { ...logAxis("error (max relative deviation)"), dtick: 3,
        tickangle: 0 } : logAxis("error: max relative deviation from the reference (dimensionless)"),
      yaxis: { ...logAxis("wall time (ms)"), dtick: undefined },
      // the legend under the x-axis title, the toolbar upright at the right edge: the
      // legend does not cover the x-axis title (tests/e2e/test_plot_layout_browser.py)
      // (a phone: above the plot, where it pushes the top margin: under it, the x-axis
      // title was placed before the legend's room and landed on the tick labels)
      margin: { t: 10, r: 34 }, modebar: MODEBAR,
      legend: window.innerWidth < 600 ? { ...LEGEND_BELOW, y: 1, yanchor: "top" } : LEGEND_BELOW,
    }, { responsive: true, displaylogo: false });
  }
  showDownloads(data);
}

function showDownloads(data) {
  // every run as one row: the columns are the runs' scalar fields, named as in the API
  const keys = [];
  for (const r of data.runs) {
    for (const [k, v] of Object.entries(r)) {
      if ((v === null || typeof v !== "object") && !keys.includes(k)) keys.push(k);
    }
  }
  const rows = data.runs.map((r) => keys.map((k) => r[k]));
  $("wp-csv").addEventListener("click", () => download("work_precision.csv", csvText(keys, rows), "text/csv"));
  $("wp-json").addEventListener("click", () => download("work_precision.json",
    JSON.stringify(data, null, 1), "application/json"));
  $("wp-downloads").hidden = false;
}

if (document.readyState === "loading") document.addEventListener("DOMContentLoaded", main);
else main();
