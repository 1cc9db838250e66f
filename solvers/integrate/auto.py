"""`method="auto"`: a method and tolerance chosen from fronts measured over many starts,
run once, with an estimate of that run's own global error bought by a second, looser run.

The choice (choose): solvers/integrate/auto_choice.py reads bench/auto_starts.py's data
(the fronts of dop853, vern9 and the Taylor backend over the 20 starts of the many-start
benchmark, per case): the method cheapest at the request's error on most starts, at the
tolerance that reached it on most starts. Where the data has no level for the request
(below 10^-14) or is missing, the one-start front of bench/work_precision.py
(solvers/integrate/data/work_precision.json) decides as before: its cheapest measured run
of error <= the request (workprecision.cost_at), else the Taylor backend in the precision
the request needs. Projection has no Taylor form, so with project = true only dop853 and
vern9 compete; without heyoka the Taylor candidate is left out, and the reason says so.

The error estimate (run_checked): the run returned is the TIGHTER of two runs of the same
method; the other runs CHECK_LOOSER looser: where the choice expects PARALLEL_MIN_S or
more, on a second thread beside it once the run has gone on CHECK_DEFER_S, else after it
(_pair: the numba kernels are nogil and heyoka's
propagation releases the GIL too: a Python loop on another thread keeps its pace beside
it). For a method whose global error
goes as tol^alpha, the two errors are e and e * F^alpha (F = CHECK_LOOSER), so their
difference d (the benchmark's measure, error_between) gives e = d * rho / (1 - rho) with
rho = F^-alpha. alpha is taken LOWER than the error's measured growth with tol
(ALPHA: below the q/(q+1) of a method of order q, bench/auto_starts.py's fronts), which
makes the estimate larger than the error: an upper estimate by extrapolation, not a bound.
A run whose estimate exceeds the request is followed by a tighter one (error ~ tol^alpha,
aiming at AIM of the request) checked against the run before it, which is looser by the
same argument, at most MAX_ROUNDS runs of the returned kind; the run returned is the
last one that has an estimate where that meets the request, else the one of the least
estimate (a run past double's floor may do worse than the one before it).

A Runge-Kutta pair is not run tighter than RK_MIN_RUN (round-off, not the tolerance, sets
its error there): a tighter run goes to the Taylor backend. A request above
EXTENDED_BELOW never runs in extended precision: the Taylor backend stays in double, down
to its double floor (taylor_backend.floor); past it one run of PAST_FLOOR_METHOD with
compensated sums at PAST_FLOOR_TOL (_past_floor), and met is false when that is not
enough either.
"""

from __future__ import annotations

import os
import threading
from collections import Counter
from concurrent.futures import ThreadPoolExecutor

import numpy as np

from solvers.integrate import auto_choice
from solvers.integrate import workprecision as wp
from solvers.integrate.taylor_backend import PRECISIONS, choose_precision, floor, snap_tol
from solvers.kernels.generate import GENERATED_MODELS

CANDIDATES = (*wp.PLAIN, wp.TAYLOR)
CHECK_LOOSER = 10.0 ** 2.5      # a Runge-Kutta check run's tol over the returned run's
TAYLOR_CHECK_ORDERS = 2         # a Taylor check run is this many orders lower
MIN_TIGHTEN = 10.0 ** 0.5       # a tighter round is at least this much tighter
CHECK_MAX_TOL = 1e-5            # no looser check than this: errors there are not a power of tol
# the exponent of the error's growth with tol, taken low (module doc): below q/(q+1) for
# the pairs' orders (8, 9), near the few-percent quantile of the exponents measured between
# a run and its check over the many-start benchmark (bench/auto_starts.py prints them): at
# 0.85 a run on the flat base said met at 1.1 times the request; the Taylor backend's
# error is far less regular in its order's tol, so its exponent is taken lower still
ALPHA = {"dop853": 0.75, "vern9": 0.75, wp.TAYLOR: 0.6}
# within FLOOR_MARGIN of its precision's round-off floor (taylor_backend.floor) a Taylor
# run's error is round-off as much as truncation and does not shrink with tol: there the
# estimate is the difference itself (factor 1), not its extrapolation
FLOOR_MARGIN = 100.0
# no estimate is below ROUNDING times that floor (eps sqrt(T), the round-off the precision
# rule takes a run of length T to carry): an extrapolated difference does not see it
ROUNDING = 10.0
MAX_ROUNDS = 3
AIM = 0.5                       # a tightened run aims at this fraction of the request
RK_MIN_TOL = 1e-16              # simulate's smallest rtol
RK_MIN_RUN = 1e-14              # the tightest Runge-Kutta run auto returns
EXTENDED_BELOW = 1e-14          # only requests at or below this may run in long double
# past double's floor of the runs above (a request above EXTENDED_BELOW): the most accurate
# pair with compensated summation at this tol, and no tighter: at 1e-16 round-off makes its
# error no longer fall with tol (on the round disk over T = 1000 it rose 3x on one start)
PAST_FLOOR_METHOD = "vern9"
PAST_FLOOR_TOL = 1e-15
# ... and only where the run at the floor was estimated within this factor of the request:
# compensated sums take back the update's round-off, not the field's; on the round disk
# they gained 15x over the Taylor backend's floor, while on a flat-base start whose floor
# run was 110x above the request the pair's estimate fell 18x under its error
PAST_FLOOR_REACH = 30.0
CHECK_SHARE = 0.4               # the looser check run's share of the step budget
# the check starts beside the run once the run has gone on this long (bench/auto_diagnose.py
# measures the pair three ways): a shorter run ends first and its check runs after it
CHECK_DEFER_S = 0.0005
# ... and only where the choice expects PARALLEL_MIN_S or more (its median over the
# measured starts): handing a check to the thread costs a short run about 0.05 ms of wall,
# as much as the overlap could give it
PARALLEL_MIN_S = 0.005
TAYLOR_MIN_TOL = 10.0 ** -18.5


def _taylor_available() -> bool:
    try:
        import heyoka  # noqa: F401  # lazy: heyoka, an optional extra slow to import
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


def _one_start_front(case_id, rtol, allowed):
    """The method and tol of the one-start front (work_precision.json), or (None, ...)."""
    try:
        data = wp.load_results()
    except FileNotFoundError:
        data = {"runs": [], "cases": []}
    runs, measured = data["runs"], {c["id"] for c in data["cases"]}
    if case_id in measured:
        front = _winner(runs, case_id, rtol, allowed)
        if front is None:
            return None, None, None, None
        tol = min(snap_tol(front["tol"]), 0.1)
        return (front["method"], tol, front.get("precision"),
                f"cheapest at error {rtol:.0e} on the measured front of {case_id} (one "
                f"start): {front['method']} at tol {tol:.3g}, error {front['error']:.1e}")
    wins = Counter()
    for cid in sorted(measured):
        w = _winner(runs, cid, rtol, allowed)
        if w is not None:
            wins[w["method"]] += 1
    if not wins:
        return None, None, None, None
    m = wins.most_common(1)[0][0]
    return m, rtol, None, (f"{case_id} is not measured: the method cheapest at {rtol:.0e} "
                           f"on most measured cases ({dict(wins)})")


def choose(case_id: str, model: int, rtol: float, t_end: float, project: bool = False,
           step=None, precision: str | None = None) -> dict:
    """{"method", "precision", "tol", "compensated", "requested_rtol", "reason",
    "taylor_allowed"}: what auto runs first, with which tolerance, and why."""
    allowed = list(CANDIDATES)
    notes = []
    if project or step is not None or model not in GENERATED_MODELS:
        allowed.remove(wp.TAYLOR)
        notes.append("taylor left out (projection, a step, or no generated field)")
    elif not _taylor_available():
        allowed.remove(wp.TAYLOR)
        notes.append("taylor left out: heyoka is not installed")
    pick = auto_choice.first_choice(case_id, rtol, allowed)
    expected = None
    if pick is not None:
        method, tol, front_prec, reason = pick["method"], pick["tol"], None, pick["reason"]
        expected = pick["expected_s"]
    else:
        method, tol, front_prec, reason = _one_start_front(case_id, rtol, allowed)
    if method is None and wp.TAYLOR in allowed:
        method, tol = wp.TAYLOR, rtol
        reason = (f"no measured run reaches error {rtol:.0e}; the Taylor backend in the "
                  "precision the request needs")
    elif method is None:
        method, tol = "vern9", rtol
        reason = (f"no measured run reaches error {rtol:.0e}; vern9, the most accurate "
                  "in-house pair (double precision limits it)")
    if method == wp.TAYLOR and precision is None and rtol <= EXTENDED_BELOW:
        precision = front_prec      # above EXTENDED_BELOW: double (_rung), whatever the front
    return {"method": method, "precision": precision if method == wp.TAYLOR else None,
            "tol": max(tol, RK_MIN_TOL), "compensated": False, "requested_rtol": rtol,
            "reason": "; ".join([reason, *notes]), "taylor_allowed": wp.TAYLOR in allowed,
            # the run's CPU time on the measured starts (median), None where not measured:
            # run_checked hands the check to a thread only where it expects PARALLEL_MIN_S
            "expected_s": expected}


# --- the runs: one returned, one looser beside it, tighter ones only if the estimate misses
def error_between(Y, Yref) -> float:
    """max over the output times of |Y - Yref|_inf / max(1, max |Yref|_inf): the error
    measure of bench/work_precision.py, the one auto reads the requested rtol as."""
    Y, Yref = np.asarray(Y, dtype=float), np.asarray(Yref, dtype=float)
    return float(np.max(np.abs(Y - Yref)) / max(1.0, float(np.max(np.abs(Yref)))))


def _snap(tol: float, floor: float) -> float:
    return max(snap_tol(tol * (1.0 + 1e-9)), floor)   # 1e-9: 10^(j/4) itself stays


def _rung(method: str, tol: float, precision: str | None, compensated: bool,
          t_end: float, extended: bool = True) -> dict:
    """One run auto may make. A Taylor run below its precision's floor widens precision
    (taylor_backend.choose_precision) up to long double, never narrows it; with
    extended = False (a request above EXTENDED_BELOW) it stays in double, at no tighter
    tol than double's floor."""
    if method == wp.TAYLOR:
        if not extended and precision in (None, "double"):
            return {"method": method, "precision": "double", "compensated": False,
                    "tol": _snap(max(tol, floor("double", t_end)), TAYLOR_MIN_TOL)}
        need = choose_precision(tol, t_end)
        if need == "quad" and precision != "quad":
            need = "long double"
        if precision is None or PRECISIONS.index(need) > PRECISIONS.index(precision):
            precision = need
        return {"method": method, "tol": _snap(tol, TAYLOR_MIN_TOL), "precision": precision,
                "compensated": False}
    return {"method": method, "tol": max(tol, RK_MIN_TOL), "precision": None,
            "compensated": compensated}


def _tighter(rung: dict, tol: float, t_end: float, taylor_ok: bool, extended: bool) -> dict:
    """The run at `tol`: the same method, or the Taylor backend below RK_MIN_RUN (a
    compensated pair, past double's floor, stays at PAST_FLOOR_TOL: _past_floor)."""
    if rung["method"] != wp.TAYLOR and rung["compensated"]:
        tol = max(tol, PAST_FLOOR_TOL)
    elif rung["method"] != wp.TAYLOR and tol < RK_MIN_RUN * (1 - 1e-9):
        if taylor_ok:
            return _rung(wp.TAYLOR, tol, None, False, t_end, extended)
        tol = RK_MIN_RUN
    return _rung(rung["method"], tol, rung["precision"], rung["compensated"], t_end, extended)


def _past_floor(rung: dict) -> dict | None:
    """The run after `rung` where it is as tight as its kind runs in double (the Taylor
    backend at double's floor, a pair at RK_MIN_RUN): PAST_FLOOR_METHOD with compensated
    summation at PAST_FLOOR_TOL; None after a compensated pair. Where a truncation error,
    not round-off, is what stays above the request (a fast start over a long T), this
    pair's tighter tol still buys accuracy in double (bench/auto_coverage.py); run_checked
    takes it only within PAST_FLOOR_REACH of the request."""
    if rung["method"] != wp.TAYLOR and rung["compensated"]:
        return None
    return _rung(PAST_FLOOR_METHOD, PAST_FLOOR_TOL, None, True, 0.0)


def taylor_order(tol: float) -> int:
    """The order heyoka's adaptive Taylor integrator picks for tol: ceil(-ln(tol)/2 + 1)
    (Jorba & Zou). Its step follows from the series' radius of convergence, not from tol,
    so two tols of one order run the same steps to the same result: the tol that matters
    is the order's, exp(-2 (order - 1)) (effective_tol)."""
    return int(np.ceil(-np.log(tol) / 2.0 + 1.0 - 1e-12))


def effective_tol(rung: dict, res=None) -> float:
    """The tolerance a run's error scales with: its tol; a Taylor run's order's."""
    if rung["method"] != wp.TAYLOR:
        return rung["tol"]
    order = getattr(res, "extra", {}).get("taylor_order") if res is not None else None
    return float(np.exp(-2.0 * ((order or taylor_order(rung["tol"])) - 1)))


def _tol_of_order(order: int) -> float:
    """The loosest tol of the quarter-decade grid whose order is `order`."""
    return _snap(float(np.exp(-2.0 * (order - 2))) * (1 - 1e-9), TAYLOR_MIN_TOL)


def _looser(rung: dict, t_end: float) -> dict:
    """The check run of `rung`: the same method and precision, CHECK_LOOSER looser (a
    Taylor run: TAYLOR_CHECK_ORDERS orders lower, a tol e^(2 x orders) looser); where
    that is looser than CHECK_MAX_TOL (errors there are not yet a power of tol), as much
    TIGHTER instead."""
    if rung["method"] == wp.TAYLOR:
        p = taylor_order(rung["tol"])
        loose = {**rung, "tol": _tol_of_order(max(p - TAYLOR_CHECK_ORDERS, 2))}
        tight = {**rung, "tol": _tol_of_order(p + TAYLOR_CHECK_ORDERS)}
    else:
        loose = {**rung, "tol": rung["tol"] * CHECK_LOOSER}
        tight = {**rung, "tol": max(rung["tol"] / CHECK_LOOSER, RK_MIN_TOL)}
    return loose if effective_tol(loose) <= CHECK_MAX_TOL * (1 + 1e-9) else tight


def scale(method: str, tol_run: float, tol_check: float) -> float:
    """The returned run's error per unit of its difference from the check run (module
    doc), effective tols: rho / (1 - rho), rho = (tol_run / tol_check)^alpha, for a looser
    check; 1 / (1 - rho), rho = (tol_check / tol_run)^alpha, for a tighter one; inf for
    the same tol."""
    if tol_check == tol_run:
        return float("inf")
    rho = (min(tol_run, tol_check) / max(tol_run, tol_check)) ** ALPHA[method]
    return (rho if tol_check > tol_run else 1.0) / (1.0 - rho)


def plan(choice: dict, t_end: float) -> list[dict]:
    """The runs a request fixes before it runs (solvers/compile_state.py rungs): the
    first run and its check; a tighter round depends on the estimate."""
    extended = choice["requested_rtol"] <= EXTENDED_BELOW
    first = _rung(choice["method"], choice["tol"], choice["precision"],
                  choice["compensated"], t_end, extended)
    return [first, _looser(first, t_end)]


def _describe(r: dict) -> str:
    return (f"{r['method']} at tol {r['tol']:.3g}"
            + (f" in {r['precision']}" if r["precision"] else "")
            + (" with compensated sums" if r.get("compensated") else ""))


_pool: list = []
_pool_lock = threading.Lock()


def _checker():
    """The process's threads for check runs (started once: a thread's start costs as
    much as a short run; a forked child starts its own: threads do not cross a fork)."""
    with _pool_lock:
        if not _pool or _pool[0][0] != os.getpid():
            _pool[:] = [(os.getpid(), ThreadPoolExecutor(
                max_workers=max(os.cpu_count() or 1, 2), thread_name_prefix="auto-check"))]
        return _pool[0][1]


def _pair(runner, a: dict, budget_a: int, b: dict, budget_b: int,
          defer: float | None = None):
    """Run a here and b beside it on a check thread once a has run for `defer` seconds
    (CHECK_DEFER_S); where a ends first, b runs here after it. The start's own run
    decides: a short run (where a thread's wake-up and the GIL's hand-over cost as much
    as the overlap gains) runs its check after it, a long one beside it. defer < 0: one
    after the other, no thread. Both results, a's first."""
    defer = CHECK_DEFER_S if defer is None else defer
    if defer < 0:
        return runner(a, budget_a), runner(b, budget_b)
    done, claim = threading.Event(), threading.Lock()

    def late():
        # b is run by whichever side takes `claim` first: this thread once the wait is
        # over with a still running, else the caller after a
        if done.wait(defer) or not claim.acquire(blocking=False):
            return None
        return runner(b, budget_b)

    fut = _checker().submit(late)
    try:
        ra = runner(a, budget_a)
    finally:
        done.set()
        here = claim.acquire(blocking=False)
        if not here:
            rb = fut.result()      # the thread runs b: wait for it (and its error)
    if here:
        rb = runner(b, budget_b)
    return ra, rb


def _estimate(res, rung, ref, ref_rung, t_end):
    """(estimate of res's error, how) from the check run ref; (None, why) without one."""
    if not ref.success or len(ref.t) != len(res.t):
        return None, f"the check run of {_describe(ref_rung)} stopped early ({ref.message})"
    e_run, e_ref = effective_tol(rung, res), effective_tol(ref_rung, ref)
    k = scale(rung["method"], e_run, e_ref)
    if not np.isfinite(k):
        return None, f"the check run of {_describe(ref_rung)} runs the same order"

    rounding = floor(rung["precision"] or "double", t_end)
    near_floor = rung["method"] == wp.TAYLOR and e_run < FLOOR_MARGIN * rounding
    k = max(k, 1.0) if near_floor else k
    # the difference of two runs does not see the round-off both carry: never below it
    est = max(error_between(res.y[:len(res.t)], ref.y[:len(ref.t)]) * k, ROUNDING * rounding)
    side = "looser" if e_ref > e_run else "tighter"
    ratio = max(e_ref, e_run) / min(e_ref, e_run)
    return est, (f"{'upper estimate by extrapolation' if side == 'looser' else 'estimate'}: "
                 f"the difference from a run of {_describe(ref_rung)} ({ratio:.3g} times "
                 f"{side}" + (", by the Taylor orders' tolerances"
                              if rung["method"] == wp.TAYLOR else "")
                 + f") times {k:.3g} (error ~ tol^{ALPHA[rung['method']]}, the exponent "
                 "taken low" + ("; near the round-off floor: the difference itself"
                                if near_floor else "")
                 + "); the difference: max over the output times of |y - y_check| / "
                 "max(1, max |y_check|)")


def run_checked(choice: dict, runner, t_end: float, max_steps: int, taylor_ok: bool = False):
    """Run auto's choice and its check beside it; estimate the returned run's global
    error from their difference (module doc); tighten while the estimate exceeds the
    request. The estimate returned is always the returned run's.

    runner(rung, max_steps) -> an integrator result (t, y, success, steps, ...); it is
    called from two threads at once for a run and its check.
    Returns (the result to return, {"error_estimate", "error_estimate_method", "met",
    "rounds", "runs", "compiled_runs", "steps_total", "rhs_calls_total", "wall_s_total",
    "returned"})."""
    requested = choice["requested_rtol"]
    extended = requested <= EXTENDED_BELOW
    runs, done = [], []          # done: (rung, res) of every successful run, for checks

    def spent():
        return sum(x.steps for x in runs)

    def checked_run(want, budget):
        """Run `want` with a check: a looser earlier run of its kind (the closest in
        tol, within CHECK_MAX_TOL) or else a check run beside it."""
        kin = [(r, x) for r, x in done if (r["method"], r["precision"], r["compensated"]) ==
               (want["method"], want["precision"], want["compensated"])
               and effective_tol(want) < effective_tol(r, x) <= CHECK_MAX_TOL * (1 + 1e-9)]
        if kin:
            chk, ref = min(kin, key=lambda rx: effective_tol(*rx))
            res = runner(want, budget)
            runs.append(res)
        else:
            chk = _looser(want, t_end)
            b = max(int(budget * CHECK_SHARE), 1)
            long = (choice.get("expected_s") or np.inf) >= PARALLEL_MIN_S
            res, ref = _pair(runner, want, max(budget - b, 1), chk, b,
                             defer=None if long else -1.0)
            runs.extend([res, ref])
            if ref.success:
                done.append((chk, ref))
        if not res.success:
            return res, chk, None, f"the run of {_describe(want)} stopped early ({res.message})"
        done.append((want, res))
        est, how = _estimate(res, want, ref, chk, t_end)
        return res, chk, est, how

    rung = plan(choice, t_end)[0]
    res, chk, est, how = checked_run(rung, max_steps)
    rounds, checked, why = [], None, ""
    if est is None:
        why = how
    else:
        checked = (res, rung, est, how)
        rounds.append({**rung, "check": _describe(chk), "error_estimate": est})
    results = [checked] if checked is not None else []
    while checked is not None and checked[2] > requested and len(rounds) < MAX_ROUNDS:
        res0, rung0, est0, _ = checked
        factor = max((est0 / (AIM * requested)) ** (1.0 / ALPHA[rung0["method"]]),
                     MIN_TIGHTEN)
        eff = effective_tol(rung0, res0) / factor
        if rung0["method"] == wp.TAYLOR:     # the order that tol needs, and its tol
            eff = _tol_of_order(max(taylor_order(eff), taylor_order(rung0["tol"]) + 1))
        want = _tighter(rung0, eff, t_end, taylor_ok, extended)
        if (want["method"] == rung0["method"] and want["precision"] == rung0["precision"]
                and effective_tol(want) >= effective_tol(rung0, res0) * (1 - 1e-9)):
            # as tight as its kind runs: past double's floor (above EXTENDED_BELOW), where
            # the floor is near enough the request
            want = (None if extended or est0 > PAST_FLOOR_REACH * requested
                    else _past_floor(rung0))
            if want is None:
                why = f"{_describe(rung0)} is as tight as auto runs here"
                break
        budget = max_steps - spent()
        if budget <= 0:
            why = "the step budget was spent before a tighter run"
            break
        new, chk, est, how = checked_run(want, budget)
        if est is None:
            why = how
            break
        checked = (new, want, est, how)
        rounds.append({**want, "check": _describe(chk), "error_estimate": est})
        results.append(checked)
    else:
        if checked is not None and checked[2] > requested and not why:
            why = f"{MAX_ROUNDS} rounds spent"
    if checked is not None:
        if checked[2] > requested:    # not met: the run of the least estimate, not the last
            checked = min(results, key=lambda c: c[2])
        res, rung, estimate, how = checked
        if estimate > requested and why:
            how += f"; no further round: {why}"
    else:
        estimate, how = None, f"none: {why}"
    info = {"error_estimate": estimate, "error_estimate_method": how,
            "met": estimate is not None and estimate <= requested,
            "rounds": rounds, "runs": len(runs),
            # Taylor runs that compiled their integrator here (not from a cache): what a
            # request's deadline paid for (app/services/kernel_prepare.py prepares them)
            "compiled_runs": sum(1 for x in runs if getattr(x, "extra", {}).get("compiled")),
            "steps_total": int(spent()),
            "rhs_calls_total": int(sum(x.rhs_calls for x in runs)),
            "wall_s_total": float(sum(x.wall_s for x in runs)),
            "returned": rung}
    return res, info
