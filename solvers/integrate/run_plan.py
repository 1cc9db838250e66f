"""What a run will compile, from its request alone (the explorer compiles it in a job
without a deadline before the request's deadline starts, so that no request pays a compile
inside its deadline: app/services/kernel_prepare.py).

A run of method "taylor" compiles heyoka's integrator of its case structure for the
precision and the tol it runs in: taylor_backend.run picks them from rtol and the length
of the WHOLE run (choose_precision, snap_tol), so a tiny run would compile another one
(rtol 1e-15: double over 1 time unit, long double over 100).

A run of method "auto" (solvers/integrate/auto.py) runs its choice and, beside it, a check
run of the same method looser by auto.CHECK_LOOSER (auto.plan): those two rungs are fixed
by the request. A tighter round, when the estimate misses the request, runs at a
tolerance computed from the measured estimate, which no plan knows before the run (a
Taylor run compiled then says so: stats "compiled").

The Runge-Kutta kernels do not depend on the tolerance (compensated summation is a
run-time flag of the same kernel), so their rungs name only the method.
"""

from __future__ import annotations

TAYLOR = "taylor"


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
    from solvers.integrate.auto import choose
    from solvers.integrate.auto import plan as auto_plan

    choice = choose(case_id, model.model, rtol, t_end, project, step, precision)
    out = auto_plan(choice, t_end)
    seen, plan = set(), []
    for r in out:
        key = (r["method"], r["tol"] if r["method"] == TAYLOR else None, r["precision"])
        if key not in seen:
            seen.add(key)
            plan.append({"method": r["method"], "tol": r["tol"], "precision": r["precision"]})
    return plan
