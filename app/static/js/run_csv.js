// A run as CSV, as POST /api/simulate?format=csv writes it: the run's provenance as "# "
// lines (the server's own text, result.provenance.header: case, parameters, method,
// tolerances, version, date and the address that reproduces the run), then t, the state and
// the invariants under the names the JSON uses (M2 the component, M_squared the integral).
"use strict";

export function csvHeader(stateLabels, invariants) {
  const header = ["t", ...stateLabels, ...invariants];
  if (new Set(header).size !== header.length) throw new Error(`column names repeat: ${header.join(",")}`);
  return header;
}

export function csvOf(res) {
  const inv = Object.keys(res.invariants);
  const lines = [...((res.provenance && res.provenance.header) || []),
    csvHeader(res.state_labels, inv).join(",")];
  res.t.forEach((t, i) => {
    lines.push([t, ...res.state[i], ...inv.map((n) => res.invariants[n][i])]
      .map((x) => (x === null ? "" : String(x))).join(","));
  });
  return lines.join("\n") + "\n";
}

// the download's file name without extension: case, t_end and the hash of the run's inputs
export function fileStem(res, caseId, tEnd) {
  if (res.provenance && res.provenance.file_stem) return res.provenance.file_stem;
  return `${caseId.replace(/\//g, "_")}_t${tEnd}`;
}
