"""auto's first choice from the fronts measured over many starts: which method, at which
tolerance, for a case and a requested error.

The data is bench/auto_starts.py's (solvers/integrate/data/auto_choice.json, written by
`python bench/auto_starts.py --write-data`): for each of the six work-precision cases, over
the 20 random starts of the many-start benchmark (bench/limit.py random_starts, seed 19),
and for each error level 10^-4 ... 10^-14 (half decades), each start's CPU time at that
error on the front of dop853, vern9 and the Taylor backend in double (interpolated between
tolerances; CPU rather than wall time: on a shared machine it is the steadier of the two),
and the loosest tolerance of each method whose run reached that error.
Nothing here is typed by hand: the crossover where the Taylor backend starts to win is
where its time is the least on most starts.

The choice for a request of error E: the level L, the largest of the grid <= E * AIM_FIRST
(auto's estimate is conservative, so the run aims below E to pass it the first time);
among the methods allowed that reach L on COVER of the starts (else those that reach it on
most), the one cheapest at L on most starts (ties: the lower median time); its
tolerance: the one that reached L on COVER of the starts (the lower
(1 - COVER)-quantile of the starts' loosest tolerances; a start that no tolerance of the grid
brought to L counts below every tolerance). The other starts are left to auto's check,
which tightens (auto.run_checked). A case the benchmark did not measure is chosen for
from every measured case's starts pooled.
"""

from __future__ import annotations

import json
import math
from functools import cache, lru_cache
from pathlib import Path

DATA = Path(__file__).resolve().parent / "data" / "auto_choice.json"
FORMAT = 1
GENERATOR = "python bench/auto_starts.py --write-data"
COVER = 0.8          # the first tolerance reaches the level on this fraction of the starts
AIM_FIRST = 0.5      # the first run aims at this fraction of the request


@cache
def load() -> dict | None:
    """The committed data, or None where it is missing (auto then reads the one-start
    front of work_precision.json, auto.choose)."""
    try:
        data = json.loads(DATA.read_text())
    except FileNotFoundError:
        return None
    if data.get("format") != FORMAT:
        raise ValueError(f"{DATA}: format {data.get('format')!r}, this reader knows "
                         f"{FORMAT} (regenerate: {GENERATOR})")
    return data


def _level_entries(data: dict, case_id: str, level: float) -> tuple[list[dict], str]:
    cases = data["cases"]
    ids = [case_id] if case_id in cases else sorted(cases)
    out = []
    for cid in ids:
        for e in cases[cid]["levels"]:
            if math.isclose(e["level"], level, rel_tol=1e-3):
                out.append(e)
    basis = (f"{case_id}'s {data['starts']} starts" if case_id in cases else
             f"{case_id} is not measured: the {len(ids)} measured cases' starts pooled")
    return out, basis


def _quantile_tol(tols: list, cover: float) -> float | None:
    """The tolerance that reached the level on `cover` of the starts (None: fewer did)."""
    vals = sorted((t if t is not None else 0.0) for t in tols)
    if not vals:
        return None
    v = vals[math.floor((1.0 - cover) * len(vals) + 1e-9)]
    return v if v > 0 else None


def first_choice(case_id: str, rtol: float, allowed) -> dict | None:
    """{"method", "tol", "level", "wins", "judged", "expected_s" (the method's median CPU
    time at the level), "reason"}, or None where the data has no level at or below
    rtol * AIM_FIRST (or no data) for the allowed methods. Cached per request: a short
    run costs no more than reading the data would."""
    pick = _first_choice(case_id, float(rtol), tuple(allowed))
    return None if pick is None else dict(pick)


def reload() -> None:
    """Read the data file again (the bench calls this after writing it)."""
    load.cache_clear()
    _first_choice.cache_clear()


@lru_cache(maxsize=256)
def _first_choice(case_id: str, rtol: float, allowed: tuple) -> dict | None:
    data = load()
    if data is None:
        return None
    grid = sorted({e["level"] for c in data["cases"].values() for e in c["levels"]})
    below = [L for L in grid if L <= rtol * AIM_FIRST * (1 + 1e-9)]
    if not below:
        return None
    level = below[-1]
    entries, basis = _level_entries(data, case_id, level)
    methods = [m for m in data["methods"] if m in allowed]
    wins = dict.fromkeys(methods, 0)
    walls = {m: [] for m in methods}
    judged = 0
    for e in entries:
        for i in range(e["judged"]):
            w = {m: e["cpu_s"][m][i] for m in methods if e["cpu_s"][m][i] is not None}
            if not w:
                continue
            judged += 1
            wins[min(w, key=w.get)] += 1
            for m, v in w.items():
                walls[m].append(v)
    if not judged:
        return None

    def median(xs):
        xs = sorted(xs)
        return xs[len(xs) // 2] if xs else math.inf
    # a method that reaches the level on COVER of the starts first (else the ones that
    # reach it on most), then the most wins among those
    reach = {m: sum(t is not None for e in entries for t in e["loosest_tol"][m][:e["judged"]])
             for m in methods}
    n_all = sum(e["judged"] for e in entries)
    eligible = [m for m in methods if reach[m] >= COVER * n_all] or \
        [m for m in methods if reach[m] == max(reach.values())]
    method = max(eligible, key=lambda m: (wins[m], -median(walls[m])))
    tols = [t for e in entries for t in e["loosest_tol"][method][:e["judged"]]]
    tol = _quantile_tol(tols, COVER)
    if tol is None:
        reached = [t for t in tols if t is not None]
        if not reached:
            return None
        tol = min(reached)
    return {"method": method, "tol": tol, "level": level, "wins": wins, "judged": judged,
            "expected_s": median(walls[method]) if walls[method] else None,
            "reason": (f"cheapest at error {level:.1e} (the request {rtol:.0e} x {AIM_FIRST}) "
                       f"on {wins[method]} of {judged} starts ({basis}; wins {wins}): "
                       f"{method} at tol {tol:.3g}, the tolerance that reached that error on "
                       f"{COVER:.0%} of them")}
