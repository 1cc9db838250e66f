"""One entry point for a run: `simulate(case, params, state0, t_end, ...)`.

It validates everything first (InputError, nothing runs), integrates with the compiled
in-house Runge-Kutta kernels or, for `scipy-*` methods, with scipy's solve_ivp on the
independent NumPy field of solvers/models/reference.py, and reports the drift of every
invariant the case carries. A run that meets a singularity returns what it computed up to
there, with status "singular" and a message saying where: never NaN as a result.
"""

import math
from dataclasses import dataclass, field

import numpy as np

from solvers.errors import InputError
from solvers.kernels.integrals import integral_series
from solvers.models.cases import Model, build, initial_state

SCIPY_METHODS = {"scipy-dop853": "DOP853", "scipy-rk45": "RK45", "scipy-lsoda": "LSODA",
                 "scipy-radau": "Radau"}
DEFAULT_METHOD = "dop853"
MAX_SAMPLES = 200_000


def compiled_methods() -> tuple[str, ...]:
    """The adaptive explicit Runge-Kutta methods (solvers/tableaux)."""
    from solvers.integrate.tableaux import TABLEAUX
    return tuple(TABLEAUX)


def symmetric_methods() -> tuple[str, ...]:
    """The symmetric fixed-step Gauss collocation methods (they take `step`, not rtol)."""
    from solvers.integrate.collocation import METHODS
    return tuple(METHODS)


TAYLOR_METHODS = ("taylor", "auto")   # heyoka's Taylor backend; auto: chosen from the front


def methods() -> tuple[str, ...]:
    return (*compiled_methods(), *symmetric_methods(), *TAYLOR_METHODS, *SCIPY_METHODS)


@dataclass
class SimulationResult:
    case: str
    params: dict[str, float]
    state_labels: tuple[str, ...]
    t: np.ndarray
    state: np.ndarray
    invariants: dict[str, np.ndarray]
    stats: dict = field(default_factory=dict)
    status: str = "ok"          # ok | singular | budget
    message: str = ""

    @property
    def ok(self) -> bool:
        return self.status == "ok"

    def drift(self, name: str) -> float:
        """max |F(t) - F(0)| / max(|F(0)|, 1) along the run."""
        v = self.invariants[name]
        return float(np.max(np.abs(v - v[0])) / max(abs(v[0]), 1.0)) if len(v) else 0.0

    def to_json(self) -> dict:
        return {
            "case": self.case,
            "params": self.params,
            "status": self.status,
            "message": self.message,
            "state_labels": list(self.state_labels),
            "t": self.t.tolist(),
            "state": self.state.tolist(),
            "invariants": {k: v.tolist() for k, v in self.invariants.items()},
            "stats": self.stats,
        }


def check_step(method, step, t_end, max_steps=None, project=False):
    """The step of a symmetric fixed-step method: required there, refused elsewhere."""
    if method in symmetric_methods():
        if step is None:
            raise InputError(f"method = {method!r} is a symmetric fixed-step method: give its "
                             "step (e.g. step = 0.1); rtol and atol do not apply to it")
        if isinstance(step, bool) or not isinstance(step, int | float) \
                or not math.isfinite(step) or not step > 0:
            raise InputError(f"step = {step!r}: must be a positive finite number")
        if max_steps is not None and t_end / step > max_steps:
            raise InputError(f"step = {step!r}: t_end / step = {t_end / step:.3g} steps, more "
                             f"than the budget of {max_steps}; take a larger step")
    elif step is not None:
        raise InputError(f"step = {step!r}: only the symmetric fixed-step methods "
                         f"({', '.join(symmetric_methods())}) take a step; {method} "
                         "chooses its own from rtol and atol")
    if project and method in symmetric_methods():
        raise InputError(f"project = true: {method} is symmetric and holds the integrals "
                         "without projection (a projection would break its symmetry)")


def _check_run_options(t_end, method, rtol, atol, samples):
    for name, v in (("t_end", t_end), ("rtol", rtol), ("atol", atol)):
        if not isinstance(v, int | float) or not math.isfinite(v):
            raise InputError(f"{name} = {v!r}: must be a finite number")
    if not t_end > 0:
        raise InputError(f"t_end = {t_end!r}: must be positive")
    if not 1e-16 <= rtol <= 0.1:
        raise InputError(f"rtol = {rtol!r}: must lie in [1e-16, 0.1]")
    if not 0 < atol <= 1.0:
        raise InputError(f"atol = {atol!r}: must lie in (0, 1]")
    if isinstance(samples, bool) or not isinstance(samples, int) or not 2 <= samples <= MAX_SAMPLES:
        raise InputError(f"samples = {samples!r}: must be an integer in [2, {MAX_SAMPLES}]")
    if method not in methods():
        raise InputError(f"method = {method!r}: unknown; choose one of {', '.join(methods())}")


def _integrate(model: Model, y0, t_out, method, rtol, atol, project, max_steps, step=None,
               precision=None, compensated=False):
    """Compiled kernels, heyoka's Taylor integrator, or scipy's solve_ivp on the
    independent NumPy field."""
    from solvers.integrate.integrator import integrate, solve_ivp_reference

    if method == "taylor":
        from solvers.integrate import taylor_backend

        return taylor_backend.run(model.model, model.p, y0, t_out, rtol=rtol,
                                  precision=precision, max_steps=max_steps)

    if method in SCIPY_METHODS:
        from solvers.models.reference import field as ref_field

        def fun(t, y):
            return ref_field(model.model, model.p, y)

        with np.errstate(all="ignore"):
            return solve_ivp_reference(model.model, model.p, y0, t_out,
                                       method=SCIPY_METHODS[method], rtol=rtol, atol=atol,
                                       fun=fun)
    if method in symmetric_methods():
        return integrate(model.model, model.p, y0, t_out, method=method, h_fixed=step,
                         max_steps=max_steps)
    return integrate(model.model, model.p, y0, t_out, method=method, rtol=rtol, atol=atol,
                     max_steps=max_steps, compensated=compensated,
                     project_codes=model.integral_codes if project else ())


def simulate(case: str, params: dict | None, state0, t_end: float, *,
             method: str = DEFAULT_METHOD, rtol: float = 1e-10, atol: float = 1e-12,
             samples: int = 201, project: bool = False, max_steps: int = 50_000_000,
             allow_any_inertia: bool = False, step: float | None = None,
             precision: str | None = None) -> SimulationResult:
    """Integrate `case` from `state0` over [0, t_end]; see the module docstring.
    precision (method "taylor" only): "double", "long double" or "quad"; None chooses
    (solvers/integrate/taylor_backend.py)."""
    model = build(case, params, allow_any_inertia=allow_any_inertia)
    y0 = initial_state(model, state0)
    _check_run_options(t_end, method, rtol, atol, samples)
    auto = None
    if method == "auto":   # from the measured work-precision front, per case and tolerance
        from solvers.integrate.auto import choose

        auto = choose(case, model.model, rtol, float(t_end), project, step, precision)
        method, precision = auto["method"], auto["precision"]
        rtol = atol = auto["tol"]   # the front point's tolerance (auto.py)
    if method == "taylor" or precision is not None:
        from solvers.integrate.taylor_backend import check_taylor_options

        check_taylor_options(method, precision, project, step)
    if project and method in SCIPY_METHODS:
        raise InputError("project = true needs a compiled method (projection happens inside "
                         f"the step); {method} is a scipy reference method")
    check_step(method, step, t_end, max_steps, project)
    t_out = np.linspace(0.0, float(t_end), samples)
    if not np.all(np.diff(t_out) > 0):
        raise InputError(f"t_end = {t_end!r} is too small for {samples} distinct sample times")
    res = _integrate(model, y0, t_out, method, rtol, atol, project, max_steps, step, precision,
                     compensated=bool(auto and auto["compensated"]))   # as measured
    status = "ok" if res.success else ("budget" if res.budget_exhausted else "singular")
    message = "" if res.success else res.message
    stats = {"steps": res.steps, "rejected": res.rejected, "rhs_calls": res.rhs_calls,
             "wall_s": res.wall_s, "method": method}
    t, Y = res.t, res.y[:len(res.t)]
    inv = {}
    for name, code in zip(model.integral_names, model.integral_codes, strict=True):
        out = np.empty(len(t))
        integral_series(code, model.model, np.ascontiguousarray(Y), model.p, out)
        inv[name] = out
    stats.update(rtol=rtol, atol=atol, projected=bool(project), samples=len(t))
    stats.update(getattr(res, "extra", {}))
    if auto is not None:
        stats["auto"] = auto
    if step is not None:   # the equal steps the kernel took to land on the samples
        stats["step"] = res.t_stop / res.steps if res.steps else step
        stats["step_requested"] = step
    result = SimulationResult(case, model.params, model.state_labels, np.asarray(t),
                              np.asarray(Y), inv, stats, status, message)
    stats["drift"] = {name: result.drift(name) for name in inv}
    return result
