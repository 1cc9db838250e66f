// Permalinks: a run, a map or a scene written into the page's query string, so that the
// address bar holds everything needed to reproduce it (copy it, open it: the page fills its
// form from the query and runs again), and downloads of what a page computed.
"use strict";

// ---- a run on a case page: /case/<id>?run=1&p.I1=1&...&state=a,b,c&t_end=...

export function runQuery(req) {
  const q = new URLSearchParams({ run: "1" });
  for (const [k, v] of Object.entries(req.params || {})) q.set(`p.${k}`, String(v));
  q.set("state", req.state.map(String).join(","));
  for (const k of ["t_end", "samples", "method", "rtol", "atol", "step"]) {
    if (req[k] !== undefined && req[k] !== null) q.set(k, String(req[k]));
  }
  if (req.project) q.set("project", "1");
  return q.toString();
}

/** Once the page has drawn what a permalink asked for (document.body.dataset[flag] set,
 * as case.js sets `run` and poincare.js sets `map`), scroll to it: a link to a run opens at
 * its result, not at the top of the page far above it (on a phone, screens above). */
export function scrollToResultWhenDone(flag, id) {
  const go = () => scrollToResult(id);
  if (document.body.dataset[flag]) { go(); return; }
  const seen = new MutationObserver(() => {
    if (!document.body.dataset[flag]) return;
    seen.disconnect();
    go();
  });
  seen.observe(document.body, { attributes: true, attributeFilter: [`data-${flag}`] });
}

/** Scroll the element `id` to the top of the screen, below the site's sticky header. */
export function scrollToResult(id) {
  const el = document.getElementById(id);
  if (!el) return;
  const head = document.querySelector("header.site");
  const pos = head ? getComputedStyle(head).position : "";
  const cover = pos === "sticky" || pos === "fixed" ? head.getBoundingClientRect().height : 0;
  window.scrollTo({ top: el.getBoundingClientRect().top + window.scrollY - cover - 8 });
}

/** Fill the case page's simulate form from a run query; true when the query asks for a
 * run (the page then scrolls to the results once the run is drawn). */
export function applyRunQuery(search, $) {
  const q = new URLSearchParams(search);
  if (q.get("run") !== "1") return false;
  scrollToResultWhenDone("run", "results");
  for (const el of document.querySelectorAll('input[data-group="p"]')) {
    const v = q.get(`p.${el.dataset.name}`);
    el.value = v === null ? "" : v;       // a parameter left out of the link takes its default
  }
  const state = (q.get("state") || "").split(",");
  document.querySelectorAll('input[data-group="s"]').forEach((el, i) => {
    if (state[i] !== undefined && state[i] !== "") el.value = state[i];
  });
  if (q.get("method")) $("f-method").value = q.get("method");
  for (const k of ["t_end", "samples", "rtol", "atol", "step"]) {
    if (q.get(k) !== null) $(`f-${k}`).value = q.get(k);
  }
  $("f-project").checked = q.get("project") === "1";
  return true;
}

// ---- any form: its named fields as the query (the Poincaré map, the scenes page)

export function formQuery(form, extra = {}) {
  const q = new URLSearchParams();
  for (const [k, v] of new FormData(form).entries()) q.set(k, String(v));
  for (const [k, v] of Object.entries(extra)) q.set(k, String(v));
  return q.toString();
}

export function applyFormQuery(form, search, { flag, result } = {}) {
  const q = new URLSearchParams(search);
  for (const [k, v] of q.entries()) {
    const el = form.elements.namedItem(k);
    if (el && "value" in el) el.value = v;
  }
  const run = q.get("run") === "1";
  if (run && flag && result) scrollToResultWhenDone(flag, result);
  return run;
}

export function setQuery(query) {
  history.replaceState(null, "", `${location.pathname}?${query}${location.hash}`);
}

// ---- downloads (saved with api.js's download)

export function csvText(header, rows) {
  const cell = (x) => (x === null || x === undefined ? "" : /[",\n]/.test(String(x))
    ? `"${String(x).replace(/"/g, '""')}"` : String(x));
  return [header, ...rows].map((r) => r.map(cell).join(",")).join("\n") + "\n";
}
