// A run as CSV: t, the state, then the invariants under their CSV names
// (/static/data/columns.json, the same file the server's ?format=csv reads), so that every
// column name is unique and says what it holds (M2 the component, M_squared the integral).
"use strict";

let names = null;

async function columnNames() {
  if (!names) {
    const r = await fetch("/static/data/columns.json");
    names = r.ok ? await r.json() : {};
  }
  return names;
}

export async function csvHeader(stateLabels, invariants) {
  const map = await columnNames();
  const header = ["t", ...stateLabels];
  for (const n of invariants) {
    let col = map[n] || n;
    while (header.includes(col)) col += "_integral";
    header.push(col);
  }
  return header;
}

export async function csvOf(res) {
  const inv = Object.keys(res.invariants);
  const lines = [(await csvHeader(res.state_labels, inv)).join(",")];
  res.t.forEach((t, i) => {
    lines.push([t, ...res.state[i], ...inv.map((n) => res.invariants[n][i])]
      .map((x) => (x === null ? "" : String(x))).join(","));
  });
  return lines.join("\n") + "\n";
}
