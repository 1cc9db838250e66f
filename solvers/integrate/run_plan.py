"""What a run will compile, from its request alone (the explorer compiles it in a job
without a deadline before the request's deadline starts, so that no request pays a compile
inside its deadline: app/services/kernel_prepare.py).

A run of method "taylor" compiles heyoka's integrator of its case structure for the
precision and the tol it runs in: taylor_backend.run picks them from rtol and the length
of the WHOLE run (choose_precision, snap_tol), so a tiny run would compile another one
(rtol 1e-15: double over 1 time unit, long double over 100).

A run of method "auto" (solvers/integrate/auto.py) runs its choice from the front, then a
check run CHECK_FACTOR tighter (the Taylor backend, possibly in long double, where a
Runge-Kutta pair cannot be checked), and, when the check finds the first run missed the
request by at most CHECK_FACTOR / AIM (misses of that size were measured on other starts
than the front's: bench/auto_coverage.py), the check run becomes the run and one more check
CHECK_FACTOR tighter follows. Those three rungs are fixed by the request; a larger miss,
or a third round, tightens to a tolerance computed from the measured estimate, which no
plan knows before the run (a Taylor run compiled then says so: stats "compiled").

The third rung is prepared ahead of need (CHECKS_AHEAD = 2): it costs the first request of
a structure and level its compile even when the first estimate meets the request. For
example auto at rtol 1e-10 on the Chaplygin ball runs vern9 at 1e-12, checks with vern9 at
3.2e-14, and a second round's check is Taylor in double at 1e-15, a cold compile of its own
(once per machine: the disk cache); at rtol 1e-15 the three rungs are long double Taylor
integrators (their compile times: bench/taylor_compile.py, docs/performance.md).

The Runge-Kutta kernels do not depend on the tolerance (compensated summation is a
run-time flag of the same kernel), so their rungs name only the method.
"""

from __future__ import annotations

TAYLOR = "taylor"
CHECKS_AHEAD = 2     # the check run, and the check's check (module doc)


def rungs(case_id: str, model, method: str, rtol: float, t_end: float, *,
          project: bool = False, step=None, precision: str | None = None) -> list[dict]:
    """The distinct runs (method, tol, precision) whose compiled code a run of `method`
    needs, in the order it needs them (module doc). model: the case's built Model."""
    if method == TAYLOR:
        from solvers.integrate.taylor_backend import check_precision, choose_precision, snap_tol

        prec = precision or choose_precision(rtol, t_end)
        check_precision(prec)
        return [{"method": TAYLOR, "tol": snap_tol(rtol), "precision": prec}]
    if method != "auto":
        return [{"method": method, "tol": rtol, "precision": None}]
    from solvers.integrate.auto import CHECK_FACTOR, _rung, _tightened, choose

    choice = choose(case_id, model.model, rtol, t_end, project, step, precision)
    first = _rung(choice["method"], choice["tol"], choice["precision"],
                  choice["compensated"], t_end)
    out = [first]
    for _ in range(CHECKS_AHEAD):
        out.append(_tightened(out[-1], out[-1]["tol"] / CHECK_FACTOR, t_end,
                              choice["taylor_allowed"]))
    seen, plan = set(), []
    for r in out:
        key = (r["method"], r["tol"] if r["method"] == TAYLOR else None, r["precision"])
        if key not in seen:
            seen.add(key)
            plan.append({"method": r["method"], "tol": r["tol"], "precision": r["precision"]})
    return plan
