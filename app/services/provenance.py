"""Where a run's data came from: the case, its parameters, the method and tolerances, the
package version, the date and the address that reproduces it (the case page's permalink
of the run), and a short hash of the run's inputs for file names.

POST /api/simulate puts this object in every answer: under "provenance" in the JSON, in
the Arrow schema's metadata, and as the commented header ("# " lines) of the CSV. The case
page's CSV button writes the same header from the JSON's object (static/js/run_csv.js), so
the two downloads of one run begin alike and carry the same file name.
"""

from __future__ import annotations

import hashlib
import json
import re
from datetime import UTC, datetime
from urllib.parse import urlencode

from app import __version__
from catalogue.glossary import load_glossary
from catalogue.numbering import cite

# the inputs that decide a run's numbers, in the order the header lists them
RUN_FIELDS = ("case", "params", "state", "t_end", "samples", "method", "rtol", "atol",
              "step", "project", "precision", "field", "allow_any_inertia")
HASH_HEX = 8


def _num(x):
    """A number as the hash and the header spell it: a float (1 and 1.0 are one input),
    written by repr."""
    if isinstance(x, bool) or x is None:
        return x
    return float(x)


def run_inputs(job: dict) -> dict:
    """The run-defining fields of a resolved request (routes/simulate.py resolve), plain."""
    return {"case": job["case"],
            "params": {k: _num(v) for k, v in sorted(job["params"].items())},
            "state": [_num(v) for v in job["state"]],
            "t_end": _num(job["t_end"]), "samples": int(job["samples"]),
            "method": job["method"], "rtol": _num(job["rtol"]), "atol": _num(job["atol"]),
            "step": _num(job.get("step")), "project": bool(job.get("project", False)),
            "precision": job.get("precision"), "field": job.get("field", "auto"),
            "allow_any_inertia": bool(job.get("allow_any_inertia", False))}


def run_hash(job: dict) -> str:
    """The first hex digits of the SHA-256 of the run's inputs as canonical JSON (sorted
    keys, no spaces): the same inputs give the same hash, any change another."""
    text = json.dumps(run_inputs(job), sort_keys=True, separators=(",", ":"))
    return hashlib.sha256(text.encode()).hexdigest()[:HASH_HEX]


def permalink_query(job: dict) -> str:
    """The case page's query of the run (static/js/permalink.js runQuery reads it back):
    run=1, every parameter as p.<name>, the state, t_end, samples, method, tolerances,
    step and project; a field or precision other than the default is kept as well."""
    inp = run_inputs(job)
    q = [("run", "1")] + [(f"p.{k}", repr(v)) for k, v in inp["params"].items()]
    q.append(("state", ",".join(repr(v) for v in inp["state"])))
    for k in ("t_end", "samples", "method", "rtol", "atol", "step"):
        if inp[k] is not None:
            q.append((k, str(inp[k]) if isinstance(inp[k], str) else repr(inp[k])))
    if inp["project"]:
        q.append(("project", "1"))
    return urlencode(q, safe=",")


def file_stem(job: dict) -> str:
    """plane_chaplygin-ball_t100_3f2a9c1b: the case, the end time and the run's hash."""
    case = re.sub(r"[^A-Za-z0-9-]+", "_", job["case"])
    t = f"{float(job['t_end']):g}".replace("+", "")
    return f"{case}_t{t}_{run_hash(job)}"


def of_run(job: dict, base_url: str) -> dict:
    """The provenance of a run before it runs; `computed_at` is set when it has run."""
    return {"case": job["case"], "inputs": run_inputs(job), "version": __version__,
            "hash": run_hash(job), "file_stem": file_stem(job),
            "permalink": f"{base_url.rstrip('/')}/case/{job['case']}?"
                         f"{permalink_query(job)}",
            "computed_at": None}


def stamped(prov: dict, res=None, stats: dict | None = None) -> dict:
    """The provenance once the run `res` (a SimulationResult) has run: the time it
    finished (UTC, seconds) and the CSV's header lines (`header`), which the case page's
    CSV button writes as they are, with every parameter of the run (defaults filled in)
    and what each column holds."""
    now = datetime.now(UTC).replace(microsecond=0).isoformat().replace("+00:00", "Z")
    out = {**prov, "computed_at": now}
    if res is None:
        out["header"] = header_lines(out, stats)
    else:
        out["header"] = header_lines(out, stats or res.stats, res.status, res.params,
                                     [*res.state_labels, *res.invariants])
    return out


def column_lines(columns: list[str]) -> list[str]:
    """One "column <name>: what it holds" line per column but t, from the glossary (its
    state variables and the integrals a run reports, catalogue/glossary.yaml)."""
    g = load_glossary()
    out = []
    for c in columns:
        e = g.get(c)
        out.append(f"column {c}: {cite(e.meaning) if e else 'see the glossary'}")
    return out


def header_lines(prov: dict, stats: dict | None = None, status: str | None = None,
                 params: dict | None = None, columns: list[str] | None = None) -> list[str]:
    """The CSV's commented header, one "# key: value" line each (static/js/run_csv.js
    writes the same lines from the JSON's provenance). The parameters are every one of
    the run (`params`, defaults filled in) or else those given."""
    inp = prov["inputs"]
    given = inp["params"] if params is None else {k: float(v) for k, v in params.items()}
    params = ", ".join(f"{k} = {v!r}" for k, v in given.items())
    method = (stats or {}).get("method", inp["method"])
    lines = [f"case: {prov['case']}",
             f"parameters: {params}",
             f"initial state: {', '.join(repr(v) for v in inp['state'])}",
             f"t_end: {inp['t_end']!r}; samples: {inp['samples']}",
             f"method: {inp['method']}" + (f" (ran {method})" if method != inp["method"]
                                           else ""),
             f"tolerances: rtol = {inp['rtol']!r}, atol = {inp['atol']!r}"
             + (f"; step = {inp['step']!r}" if inp["step"] is not None else "")
             + ("; projected" if inp["project"] else ""),
             f"version: rolling-hierarchy {prov['version']}",
             f"date: {prov['computed_at']}",
             f"reproduce: {prov['permalink']}",
             f"hash: {prov['hash']}"]
    if status and status != "ok":
        lines.append(f"status: {status}")
    lines.append("column t: time")
    lines += column_lines([c for c in columns or [] if c != "t"])
    return [f"# {x}" for x in lines]
