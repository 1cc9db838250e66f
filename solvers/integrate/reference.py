"""scipy's solve_ivp on the same problem as the compiled kernels: the independent check
(`solve_ivp_reference`; method "scipy-*" of simulate)."""

import time

import numpy as np

from solvers.integrate.result import IntegrationResult, status_message
from solvers.kernels import layout as L
from solvers.kernels import rk
from solvers.kernels.fields import rhs

SCIPY_CALLS_PER_STEP = 16


class _Singular(Exception):
    pass


def solve_ivp_reference(model, p, y0, t_out, method="DOP853", rtol=1e-10, atol=1e-12,
                        fun=None, max_steps=None) -> IntegrationResult:
    """scipy.integrate.solve_ivp on the same problem. `fun(t, y) -> dy/dt` defaults to a
    plain-Python wrapper of the compiled rhs (the lead's independent numpy field can be
    passed instead). max_steps bounds the work as for the compiled kernels: solve_ivp has
    no step budget, so the run stops with MAX_STEPS once its rhs calls exceed max_steps
    steps' worth (SCIPY_CALLS_PER_STEP calls a step: DOP853's 12 stages, or an implicit
    method's Newton iterations and a finite-difference Jacobian of the 6 to 12 variables)."""
    # lazy: scipy.integrate, slow to import, kept out of importing solvers.simulate
    from scipy.integrate import solve_ivp

    t_out = np.asarray(t_out, dtype=np.float64)
    p = np.ascontiguousarray(p, dtype=np.float64)
    calls = [0]
    last_t = [float(t_out[0])]
    if fun is None:
        def fun(t, y):
            dy = np.empty_like(y)
            st = rhs(model, t, np.ascontiguousarray(y), p, dy)
            if st != L.OK:
                raise _Singular(st)
            return dy

    max_calls = None if max_steps is None else SCIPY_CALLS_PER_STEP * int(max_steps)

    def counted(t, y):
        calls[0] += 1
        last_t[0] = t
        if max_calls is not None and calls[0] > max_calls:
            raise _Singular(rk.MAX_STEPS)
        dy = fun(t, y)
        if not np.all(np.isfinite(dy)):
            raise _Singular(L.SING_NONFINITE)
        return dy

    t0 = time.perf_counter()
    try:
        sol = solve_ivp(counted, (t_out[0], t_out[-1]), np.asarray(y0, dtype=np.float64),
                        method=method, t_eval=t_out, rtol=rtol, atol=atol)
        status = L.OK if sol.status == 0 else rk.STEP_UNDERFLOW
        t, y, message = sol.t, sol.y.T, sol.message
        steps = int(sol.t.size)
    except _Singular as exc:
        status, t, y, steps = exc.args[0], t_out[:0], np.empty((0, len(y0))), 0
        message = f"{status_message(status)} (stopped at t = {last_t[0]:.17g})"
    wall = time.perf_counter() - t0
    return IntegrationResult(
        t=t, y=y, status=int(status), message=message,
        t_stop=float(t[-1]) if len(t) else float(t_out[0]),
        y_stop=y[-1] if len(t) else np.asarray(y0, dtype=np.float64), steps=steps,
        rejected=0, rhs_calls=calls[0], wall_s=wall, method=f"scipy-{method}")
