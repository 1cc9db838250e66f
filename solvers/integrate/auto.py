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
several times over (a Taylor method's error is not a smooth power of tol, its order steps with
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

import numpy as np

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
            "front_point": front, "taylor_allowed": wp.TAYLOR in allowed}


# --- the estimate of this run's error, and tightening until it meets the request ----------
# The front is measured on one start per case; on other starts the chosen tolerance can miss
# the requested error several times over (bench/auto_coverage.py). So auto checks its own
# run: it runs the
# same method once more at a tolerance CHECK_FACTOR tighter and reports the difference of
# the two (the benchmark's error measure, error_between) as the estimated global error of
# the run it returns. With error roughly proportional to tol, the check run's own error is
# ~1/30 of the returned run's, so the difference estimates the returned run's error to a
# few per cent. If the estimate exceeds the request, the tolerance is tightened (error ~ tol
# again, aiming at half the request) and checked again, at most MAX_ROUNDS rounds, all runs
# together within the request's max_steps. Measured: bench/auto_coverage.py.
# The Runge-Kutta pairs run in double: below RK_MIN_TOL their round-off, not the tolerance,
# sets the error (bench/auto_coverage.py: vern9 at tol 1e-16 missed 1e-12 by more than an
# order of magnitude on the disk, and its check run at the same floor could not tell). A tighter
# run than that goes to the Taylor backend in extended precision where it can run (a
# generated field, no projection, heyoka installed), as choose() does for levels beyond the
# front; there the check run may go to TAYLOR_MIN_TOL in long double.
CHECK_FACTOR = 10.0 ** 1.5      # six quarter decades: keeps the tolerances on the front's grid
MAX_ROUNDS = 4
AIM = 0.5                       # a tightened tolerance aims at this fraction of the request
RK_MIN_TOL = 1e-16              # simulate's smallest rtol
RK_MIN_RUN = RK_MIN_TOL * CHECK_FACTOR   # the tightest RK run that still has a tighter check
TAYLOR_MIN_TOL = 10.0 ** -18.5


def error_between(Y, Yref) -> float:
    """max over the output times of |Y - Yref|_inf / max(1, max |Yref|_inf): the error
    measure of bench/work_precision.py, the one auto reads the requested rtol as."""
    Y, Yref = np.asarray(Y, dtype=float), np.asarray(Yref, dtype=float)
    return float(np.max(np.abs(Y - Yref)) / max(1.0, float(np.max(np.abs(Yref)))))


def _snap(tol: float, floor: float) -> float:
    from solvers.integrate.taylor_backend import snap_tol

    return max(snap_tol(tol * (1.0 + 1e-9)), floor)   # 1e-9: 10^(j/4) itself stays


def _rung(method: str, tol: float, precision: str | None, compensated: bool,
          t_end: float) -> dict:
    """One run auto may make. A Taylor run below its precision's floor widens precision
    (taylor_backend.choose_precision) up to long double (quad only if chosen before: it
    costs far more: software arithmetic), never narrows it."""
    if method == wp.TAYLOR:
        from solvers.integrate.taylor_backend import PRECISIONS, choose_precision

        need = choose_precision(tol, t_end)
        if need == "quad" and precision != "quad":
            need = "long double"
        if precision is None or PRECISIONS.index(need) > PRECISIONS.index(precision):
            precision = need
        return {"method": method, "tol": _snap(tol, TAYLOR_MIN_TOL), "precision": precision,
                "compensated": False}
    return {"method": method, "tol": _snap(tol, RK_MIN_TOL), "precision": None,
            "compensated": compensated}


def _tightened(rung: dict, tol: float, t_end: float, taylor_ok: bool) -> dict:
    """The run at `tol`: the same method, or the Taylor backend where a Runge-Kutta pair
    could not be checked at that tol (RK_MIN_RUN)."""
    if rung["method"] != wp.TAYLOR and tol < RK_MIN_RUN * (1 - 1e-9):
        if taylor_ok:
            return _rung(wp.TAYLOR, tol, None, False, t_end)
    return _rung(rung["method"], tol, rung["precision"], rung["compensated"], t_end)


def _describe(r: dict) -> str:
    return (f"{r['method']} at tol {r['tol']:.3g}"
            + (f" in {r['precision']}" if r["precision"] else ""))


def run_checked(choice: dict, runner, t_end: float, max_steps: int, taylor_ok: bool = False):
    """Run auto's choice, estimate the run's global error by a check run CHECK_FACTOR
    tighter, tighten while the estimate exceeds the request (module comment above).
    The estimate returned is always the returned run's: a tightened run that could not be
    checked (budget, a failed check run) is not returned; the last checked one is.

    runner(rung, max_steps) -> an integrator result (t, y, success, steps, ...).
    taylor_ok: the Taylor backend may run this case (beyond the Runge-Kutta floor).
    Returns (the result to return, {"error_estimate", "error_estimate_method", "met",
    "rounds", "runs", "compiled_runs", "steps_total", "rhs_calls_total", "wall_s_total",
    "returned"})."""
    requested = choice["requested_rtol"]
    rung = _rung(choice["method"], choice["tol"], choice["precision"],
                 choice["compensated"], t_end)
    runs = []

    def go(r):
        res = runner(r, max(max_steps - sum(x.steps for x in runs), 1))
        runs.append(res)
        return res

    res = go(rung)
    rounds, checked, why = [], None, ""      # checked: (res, rung, estimate, how)
    for k in range(MAX_ROUNDS):
        if not res.success:
            why = f"the run of {_describe(rung)} stopped early ({res.message})"
            break
        check = _tightened(rung, rung["tol"] / CHECK_FACTOR, t_end, taylor_ok)
        if (check["tol"], check["precision"]) == (rung["tol"], rung["precision"]):
            why = f"{_describe(rung)} is as tight as auto runs, no tighter check"
            break
        if sum(x.steps for x in runs) >= max_steps:
            why = "the step budget was spent before a check run"
            break
        ref = go(check)
        if not ref.success or len(ref.t) != len(res.t):
            why = f"the check run of {_describe(check)} stopped early ({ref.message})"
            break
        estimate = error_between(res.y[:len(res.t)], ref.y[:len(ref.t)])
        how = (f"the difference from a second run of {_describe(check)} "
               f"(tol {rung['tol'] / check['tol']:.3g} times tighter): max over the output "
               "times of |y - y_check| / max(1, max |y_check|)")
        checked = (res, rung, estimate, how)
        rounds.append({**rung, "check": _describe(check), "error_estimate": estimate})
        if estimate <= requested or k == MAX_ROUNDS - 1:
            break
        want = _tightened(rung, rung["tol"] * AIM * requested / estimate, t_end, taylor_ok)
        if (want["method"], want["precision"]) == (check["method"], check["precision"]) \
                and want["tol"] >= check["tol"]:
            rung, res = check, ref     # the check run is tight enough: it becomes the run
        elif (want["tol"], want["method"]) == (rung["tol"], rung["method"]):
            why = f"{_describe(rung)} is as tight as auto runs"
            break
        else:
            rung = want
            res = go(rung)
    if checked is not None:
        res, rung, estimate, how = checked
        if checked[2] > requested and why:
            how += f"; no further round: {why}"
    else:
        estimate, how = None, f"none: {why}"
    info = {"error_estimate": estimate, "error_estimate_method": how,
            "met": estimate is not None and estimate <= requested,
            "rounds": rounds, "runs": len(runs),
            # Taylor runs that compiled their integrator here (not from a cache): what a
            # request's deadline paid for (app/services/kernel_prepare.py prepares them)
            "compiled_runs": sum(1 for x in runs if getattr(x, "extra", {}).get("compiled")),
            "steps_total": int(sum(x.steps for x in runs)),
            "rhs_calls_total": int(sum(x.rhs_calls for x in runs)),
            "wall_s_total": float(sum(x.wall_s for x in runs)),
            "returned": rung}
    return res, info
