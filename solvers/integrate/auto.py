"""`method="auto"`: the method to run, chosen from the measured work-precision front per
case and per tolerance, across the in-house kernels and the Taylor backend.

The measurements are bench/work_precision.py's (solvers/integrate/data/work_precision.json):
for each benchmark case, runs of dop853 and vern9 (compensated summation, rtol = atol)
and `taylor` (heyoka on the lean generated field, solvers/integrate/taylor_backend.py, in
double and long double) at tolerances 1e-4 ... 1e-16, each with its error against a
long-double reference and its wall time. auto reads the requested rtol as the error
wanted (the benchmark's error is relative to max(1, |y_ref|)).

For each candidate, its cheapest measured run whose error is <= that level
(workprecision.cost_at; the tolerances are half a decade apart from 10^-8.5 to 10^-10.5,
then a quarter decade apart, the Taylor backend's own grid, to 10^-13.75);
the cheapest candidate wins and runs as the benchmark ran it: that run's tolerance
(rtol = atol; compensated summation for dop853 / vern9; the run's precision for taylor).
No interpolation: a log-log interpolation of the tolerance was tried and missed the error
by up to 6x (a Taylor method's error is not a smooth power of tol, its order steps with
it), so auto keeps to tolerances that were measured to deliver. The
benchmark's run is 1000 time units (100 for the unbalanced ball): a longer run of the
same case accumulates more error, a shorter one less.

A case the benchmark did not measure takes the method that wins the level on most of the
measured cases, at the requested rtol. A level no measured run reaches (e.g. 1e-16 over
T = 1000) goes to the Taylor backend, whose rule (taylor_backend.choose_precision) picks
long double or quad. Projection has no Taylor form, so with project = true only dop853
and vern9 compete. Without heyoka the Taylor candidate is left out, and the reason says so.
"""

from __future__ import annotations

from collections import Counter

from solvers.integrate import workprecision as wp

CANDIDATES = (*wp.PLAIN, wp.TAYLOR)


def _taylor_available() -> bool:
    try:
        import heyoka  # noqa: F401
    except ImportError:
        return False
    return True


def at_level(records: list[dict], level: float) -> dict | None:
    """The cheapest measured run of one method with error <= level (workprecision's
    conservative reading of the front), or None if no run of it reaches the level."""
    best = wp.cost_at(records, level)
    return None if best is None else _point(best)


def _point(r: dict) -> dict:
    return {k: r.get(k) for k in ("method", "tol", "error", "wall_s", "precision")}


def _winner(runs: list[dict], case_id: str, level: float, allowed) -> dict | None:
    best = None
    for m in allowed:
        c = at_level([r for r in runs if r["case"] == case_id and r["method"] == m], level)
        if c is not None and (best is None or c["wall_s"] < best["wall_s"]):
            best = c
    return best


def choose(case_id: str, model: int, rtol: float, t_end: float, project: bool = False,
           step=None, precision: str | None = None) -> dict:
    """{"method", "precision", "tol", "compensated", "requested_rtol", "reason",
    "front_point"}: what auto runs, with which tolerance, and why."""
    from solvers.integrate.taylor_backend import snap_tol
    from solvers.kernels.generate import GENERATED_MODELS

    allowed = list(CANDIDATES)
    notes = []
    if project or step is not None or model not in GENERATED_MODELS:
        allowed.remove(wp.TAYLOR)
        notes.append("taylor left out (projection, a step, or no generated field)")
    elif not _taylor_available():
        allowed.remove(wp.TAYLOR)
        notes.append("taylor left out: heyoka is not installed")
    try:
        data = wp.load_results()
    except FileNotFoundError:
        data = {"runs": [], "cases": []}
    runs = data["runs"]
    measured = {c["id"] for c in data["cases"]}
    front = None
    if case_id in measured:
        front = _winner(runs, case_id, rtol, allowed)
        basis = f"the measured front of {case_id}"
        method = front["method"] if front else None
    else:
        wins = Counter()
        for cid in sorted(measured):
            w = _winner(runs, cid, rtol, allowed)
            if w is not None:
                wins[w["method"]] += 1
        method = wins.most_common(1)[0][0] if wins else None
        basis = (f"{case_id} is not measured: the method cheapest at this level on most "
                 f"measured cases ({dict(wins)})")
    if method is not None:
        reason = f"cheapest at error {rtol:.0e} on {basis}"
    elif wp.TAYLOR in allowed:
        method = wp.TAYLOR
        reason = (f"no measured run reaches error {rtol:.0e}; the Taylor backend in the "
                  "precision the request needs")
    else:
        method = "vern9"
        reason = (f"no measured run reaches error {rtol:.0e}; vern9, the most accurate "
                  "in-house pair (double precision limits it)")
    tol = rtol
    if front is not None:
        tol = min(snap_tol(front["tol"]), 0.1)
        reason += (f": {front['method']} at tol {tol:.3g}"
                   + (f" in {front['precision']}" if front.get("precision") else "")
                   + f", error {front['error']:.1e} in {front['wall_s'] * 1e3:.3g} ms on "
                   "the benchmark")
        if method == wp.TAYLOR and precision is None:
            precision = front.get("precision")
    tol = max(tol, 1e-16)
    return {"method": method, "precision": precision if method == wp.TAYLOR else None,
            "tol": tol, "compensated": front is not None and method in wp.PLAIN,
            "requested_rtol": rtol, "reason": "; ".join([reason, *notes]),
            "front_point": front}
