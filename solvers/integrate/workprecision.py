"""Work-precision results: load the committed measurements, derive Pareto fronts, the
ratios at equal error, each case's default method and what a tolerance buys.

The measurements come from `bench/work_precision.py` (also `rolling bench
work-precision`), written to solvers/integrate/data/work_precision.json (package data: an
installed explorer serves it; the table stays in bench/results/): one record per (case,
method, tolerance) with the error against a high-precision reference and the cost. This
module only reads and summarises them (the explorer's GET /api/work-precision serves
`load_results()`); it runs nothing.

Error of a run: max over the output grid of |y - y_ref|_inf / max(1, max |y_ref|_inf).
Cost at an error level E for a method: the least wall time of its runs with error <= E
(no interpolation between tolerances: a conservative reading of the front).
"""

from __future__ import annotations

import json
import math
from functools import cache
from pathlib import Path

RESULTS = Path(__file__).resolve().parent / "data" / "work_precision.json"
# the data file's layout: "format" (this number; a file without it is format 1) and
# "generator" (the command that writes it); a reader refuses a format it does not know
FORMAT = 1
GENERATOR = "python bench/work_precision.py"
LEVELS = (1e-4, 1e-6, 1e-8, 1e-10, 1e-12)

# method keys of the benchmark; OURS are the compiled kernels of this project
PLAIN = ("dop853", "vern9")
SYMMETRIC = ("gauss8",)               # constant step: its records' tol is the step h
OURS = (*PLAIN, "dop853+proj", "vern9+proj", *SYMMETRIC)
SCIPY_NUMPY = "scipy-DOP853/numpy"    # scipy's DOP853 on the independent NumPy field
SCIPY_COMPILED = "scipy-DOP853/numba"  # the same on our compiled field (scipy overhead only)
HEYOKA = "heyoka"                     # heyoka on the general expression system (taylor.py)
TAYLOR = "taylor"                     # the Taylor backend: heyoka on the lean generated field


def cost_at(records: list[dict], level: float) -> dict | None:
    """The cheapest successful run with error <= level, or None."""
    ok = [r for r in records if r["ok"] and r["error"] is not None and r["error"] <= level]
    return min(ok, key=lambda r: r["wall_s"]) if ok else None


def pareto(records: list[dict]) -> list[dict]:
    """Runs not beaten in both error and wall time by another run, by increasing error."""
    pts = sorted((r for r in records if r["ok"] and r["error"] is not None),
                 key=lambda r: (r["wall_s"], r["error"]))
    front, best = [], math.inf
    for r in pts:
        if r["error"] < best:
            front.append(r)
            best = r["error"]
    return sorted(front, key=lambda r: r["error"])


def summarise(data: dict) -> dict:
    """Per case: the Pareto table (best of ours and each reference at every error level,
    with the ratios), the default method and what each tolerance of it buys."""
    out = {}
    for case in data["cases"]:
        recs = [r for r in data["runs"] if r["case"] == case["id"]]
        by = {}
        for r in recs:
            by.setdefault(r["method"], []).append(r)
        ours = [r for r in recs if r["method"] in OURS]
        rows = []
        for level in LEVELS:
            best = cost_at(ours, level)
            row = {"level": level, "ours": _brief(best)}
            for m in sorted(by):
                if m in OURS:
                    continue
                ref = cost_at(by[m], level)
                row[m] = _brief(ref)
                row[f"ratio_{m}"] = (ref["wall_s"] / best["wall_s"]) if best and ref else None
            rows.append(row)
        default = _default_method(by)
        buys = [{"rtol": r["tol"], "error": r["error"], "wall_s": r["wall_s"],
                 "rhs_calls": r["rhs_calls"]}
                for r in sorted(by.get(default, []), key=lambda r: -r["tol"]) if r["ok"]]
        out[case["id"]] = {"table": rows, "default_method": default, "tolerance_buys": buys,
                           "front": {m: [_brief(r) for r in pareto(v)] for m, v in by.items()}}
    return out


def _brief(r: dict | None) -> dict | None:
    if r is None:
        return None
    return {"method": r["method"], "tol": r["tol"], "error": r["error"], "wall_s": r["wall_s"],
            "rhs_calls": r["rhs_calls"], "knob": r.get("knob", "tol")}


def _default_method(by: dict) -> str:
    """The plain method (projection is a separate switch) that is cheapest at the most
    error levels from 1e-6 to 1e-12, the tighter levels weighing a little more."""
    score = {}
    for i, level in enumerate(LEVELS[1:]):
        cands = [(cost_at(by.get(m, []), level), m) for m in PLAIN]
        cands = [(c["wall_s"], m) for c, m in cands if c is not None]
        if cands:
            m = min(cands)[1]
            score[m] = score.get(m, 0) + 1 + 0.1 * i
    return max(score, key=score.get) if score else "dop853"


@cache
def _load(path: str, mtime: float) -> dict:
    data = json.loads(Path(path).read_text())
    check_format(data, path)
    data["summary"] = summarise(data)
    return data


def check_format(data: dict, where: str = "work-precision data") -> None:
    """Raise ValueError unless data is a work-precision file this reader knows: a format
    number it reads (absent: 1), a generator string if any, and its runs and cases."""
    fmt = data.get("format", 1)
    if isinstance(fmt, bool) or not isinstance(fmt, int) or not 1 <= fmt <= FORMAT:
        raise ValueError(f"{where}: format {fmt!r}, this reader knows formats 1 to {FORMAT}; "
                         f"write it again with `{GENERATOR}`")
    if not isinstance(data.get("generator", ""), str):
        raise ValueError(f"{where}: 'generator' is not a command line")
    if not isinstance(data.get("runs"), list) or not isinstance(data.get("cases"), list):
        raise ValueError(f"{where}: no 'runs' and 'cases' lists")


def load_results(path: Path | None = None) -> dict:
    """The committed work-precision measurements plus their summary (see module doc).
    Raises FileNotFoundError if the benchmark has not been run."""
    p = Path(path or RESULTS)
    return _load(str(p), p.stat().st_mtime)


def default_method(case_id: str, fallback: str = "dop853") -> str:
    """The case's default compiled method, chosen from the measured Pareto front."""
    try:
        return load_results()["summary"][case_id]["default_method"]
    except (FileNotFoundError, KeyError):
        return fallback
