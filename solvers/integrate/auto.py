"""`method="auto"`: the method to run, chosen from the measured work-precision front per
case and per tolerance, across the in-house kernels and the Taylor backend.

The measurements are bench/work_precision.py's (solvers/integrate/data/work_precision.json):
for each benchmark case, runs of dop853, vern9 and `taylor` (heyoka on the lean generated
field, solvers/integrate/taylor_backend.py) at tolerances 1e-4 ... 1e-16, each with its
error against a long-double reference and its wall time. For a requested rtol the error
level is rtol itself (the benchmark's error is relative to max(1, |y_ref|)), and the
choice is the method whose cheapest run reaching that level is cheapest (workprecision's
`cost_at`: no interpolation, a conservative reading of the front). The chosen method then
runs with that front point's tolerance (rtol = atol = its tol, and its precision for
taylor): auto reads rtol as the error wanted and picks the (method, tolerance) the
measurements say delivers it at least cost, over the benchmark's run length (a longer
run accumulates more error, a shorter one less).

A case the benchmark did not measure takes the method that wins the level on most of the
measured cases. A level no measured run reaches (rtol below what double delivers over the
benchmark's run, e.g. 1e-15 over T = 1000) goes to the Taylor backend, whose precision
rule (taylor_backend.choose_precision) then picks long double or quad. Projection has no
Taylor form, so with project = true only dop853 and vern9 compete. Without heyoka the
Taylor candidate is left out, and the reason says so.
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


def _winner(runs: list[dict], case_id: str, level: float, allowed) -> dict | None:
    best = None
    for m in allowed:
        c = wp.cost_at([r for r in runs if r["case"] == case_id and r["method"] == m], level)
        if c is not None and (best is None or c["wall_s"] < best["wall_s"]):
            best = c
    return best


def choose(case_id: str, model: int, rtol: float, t_end: float, project: bool = False,
           step=None, precision: str | None = None) -> dict:
    """{"method", "precision", "tol", "requested_rtol", "reason", "front_point"}: what
    auto runs, with which tolerance, and why."""
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
    point, basis = None, ""
    if case_id in measured:
        point = _winner(runs, case_id, rtol, allowed)
        basis = f"the measured front of {case_id}"
    else:
        wins = Counter()
        for cid in sorted(measured):
            w = _winner(runs, cid, rtol, allowed)
            if w is not None:
                wins[w["method"]] += 1
        if wins:
            m = wins.most_common(1)[0][0]
            point = {"method": m, "wins": dict(wins)}
            basis = (f"{case_id} is not measured: the method cheapest at this level on "
                     f"most measured cases ({dict(wins)})")
    if point is not None:
        method = point["method"]
        reason = f"cheapest run with error <= {rtol:.0e} on {basis}"
    elif wp.TAYLOR in allowed:
        method = wp.TAYLOR
        reason = (f"no measured run reaches error {rtol:.0e}; the Taylor backend in the "
                  "precision the request needs")
    else:
        method = "vern9"
        reason = (f"no measured run reaches error {rtol:.0e}; vern9, the most accurate "
                  "in-house pair (double precision limits it)")
    front = None
    if point is not None and "wall_s" in point:
        front = {k: point.get(k) for k in ("method", "tol", "error", "wall_s", "precision")}
    tol = rtol
    if front is not None:
        tol = front["tol"]
        if method == wp.TAYLOR and precision is None:
            precision = front.get("precision")
    return {"method": method, "precision": precision if method == wp.TAYLOR else None,
            "tol": tol, "requested_rtol": rtol, "reason": "; ".join([reason, *notes]),
            "front_point": front}
