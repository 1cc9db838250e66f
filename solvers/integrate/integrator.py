"""Python entry point of the compiled Runge-Kutta integrators (diffrax-style separation).

*What* is integrated: a model code and its parameter vector (`solvers.kernels.layout`);
*how*: a method name (a tableau of `solvers.integrate.tableaux`) and a `StepControl`; *what to
record*: the output times `t_out`, integrals to project onto, a `Section` to cross. This
layer converts everything to the float/int arrays the kernel takes (poliastro style) and
turns the kernel's status code into a message; the kernel knows nothing of it.

`solve_ivp_reference` runs scipy's solve_ivp on the same field, as an independent check.
"""

import time
from dataclasses import dataclass, field

import numpy as np

from solvers.integrate import collocation, tableaux
from solvers.kernels import gauss, generate, rk, unroll
from solvers.kernels import layout as L
from solvers.kernels.fields import rhs


@dataclass(frozen=True)
class StepControl:
    """Step-size control (Hairer's DOPRI5 PI controller): h_new = h * clip(safety *
    err^-(1/(q+1) - 0.75 beta) * err_prev^beta, fac_min, fac_max); beta = 0 gives the
    classical controller. h0 = 0: Hairer's automatic initial step."""

    safety: float = 0.9
    fac_min: float = 0.2
    fac_max: float = 10.0
    beta: float = 0.04
    h0: float = 0.0
    h_max: float = np.inf


@dataclass(frozen=True)
class Section:
    """The section s(y) = coef . y - offset = 0, crossed with s increasing (direction
    +1), decreasing (-1) or either (0). Crossings are located by Henon's trick."""

    coef: tuple
    offset: float = 0.0
    direction: int = 1
    code: int = rk.SECTION_LINEAR

    def packed(self, n):
        c = np.zeros(n + 1)
        c[:n] = np.asarray(self.coef, dtype=np.float64)
        c[n] = self.offset
        return c


@dataclass(frozen=True)
class IntegrationResult:
    t: np.ndarray                 # output times reached (a prefix of t_out)
    y: np.ndarray                 # (len(t), n) states there
    status: int
    message: str
    t_stop: float                 # where the integration stopped
    y_stop: np.ndarray
    steps: int
    rejected: int
    rhs_calls: int
    wall_s: float
    method: str
    crossings_t: np.ndarray = field(default_factory=lambda: np.empty(0))
    crossings_y: np.ndarray = field(default_factory=lambda: np.empty((0, 0)))

    @property
    def success(self) -> bool:
        return self.status in rk.SUCCESS

    @property
    def budget_exhausted(self) -> bool:
        return self.status == rk.MAX_STEPS


_INTEGRATOR_STATUS_TEXT = {**rk.STATUS_TEXT, **gauss.STATUS_TEXT}


def status_message(status: int) -> str:
    if 0 <= status < len(L.STATUS_TEXT):
        return L.STATUS_TEXT[status]
    return _INTEGRATOR_STATUS_TEXT.get(status, f"unknown status {status}")


def method_arrays(name: str):
    """The kernel's view of a tableau: (A, c, b, E, P, meth); P holds the dense-output
    weights in Chebyshev form (rows: stages), shape (0, 1) if there is none."""
    tab = tableaux.load(name)
    s = tab.stages
    E = np.zeros((2, s))
    E[:len(tab.e)] = tab.e
    P = np.zeros((0, 1)) if tab.dense is None else np.ascontiguousarray(tab.dense_cheb)
    kind = tableaux.ERROR_ESTIMATES.index(tab.error_estimate)
    meth = np.array([s, tab.new_stage, kind, tab.order, tab.error_order], dtype=np.int64)
    return (np.ascontiguousarray(tab.A), np.ascontiguousarray(tab.c),
            np.ascontiguousarray(tab.b), E, P, meth)


# the generated kernels unroll these tableaux (the kernels layer cannot import this one)
unroll.set_provider(lambda: {name: method_arrays(name) for name in tableaux.METHODS})


def initial_integrals(model, p, y0, codes) -> np.ndarray:
    y0 = np.array(y0, dtype=np.float64)
    p = np.array(p, dtype=np.float64)
    return np.array([rk.model_integral(int(k), int(model), y0, p) for k in codes])


def integrate(model, p, y0, t_out, *, method="dop853", rtol=1e-10, atol=1e-12,
              max_steps=10_000_000, compensated=False, project_codes=(), project_values=None,
              project_every=1, section=None, max_crossings=100_000, h_fixed=None,
              dense_output=True, control=StepControl(),
              generated=False) -> IntegrationResult:
    """Integrate `model` from (t_out[0], y0) and return the states at the times t_out.

    rtol/atol: scaled RMS error per step (atol may be a vector); h_fixed: run with this
    fixed step and no error control instead. max_steps bounds the attempted steps.
    project_codes: integral codes (`solvers.kernels.integrals`, or rk.TEST_* for the test
    models) kept at project_values (default: their values at y0), every project_every-th
    step. section: record up to max_crossings crossings; the run stops at that number.
    dense_output=False: clip the steps to land on every output time instead of
    interpolating (the states are then step endpoints; it costs steps).
    generated: run the same kernel compiled against the case's generated field
    (solvers/kernels/generate.py) for the models that have one.
    """
    # fresh writable C arrays: a read-only or strided input would be another numba
    # specialization (another ~12 s compile)
    t_out = np.array(t_out, dtype=np.float64).ravel()
    y0 = np.array(y0, dtype=np.float64).ravel()
    p = np.array(p, dtype=np.float64)
    n = y0.size
    if t_out.size == 0 or np.any(np.diff(t_out) <= 0) or not np.all(np.isfinite(t_out)):
        raise ValueError("t_out must be finite and strictly increasing; t_out[0] is t0")
    if n != L.STATE_DIM[model]:
        raise ValueError(f"model {model} has a state of dimension {L.STATE_DIM[model]}")
    if method in collocation.METHODS:
        if project_codes or section is not None or not h_fixed or not h_fixed > 0:
            raise ValueError(f"{method} is a symmetric fixed-step method: give h_fixed > 0; "
                             "it takes no projection and no section")
        return _integrate_symmetric(model, p, y0, t_out, method, float(h_fixed), max_steps)
    A, c, b, E, P, meth = method_arrays(method)
    if not dense_output:
        P = np.zeros((0, 1))
    codes = np.asarray(project_codes, dtype=np.int64).ravel()
    if project_values is None:
        project_values = initial_integrals(model, p, y0, codes)
    vals = np.array(project_values, dtype=np.float64).ravel()
    if vals.size != codes.size or project_every < 1:
        raise ValueError("one project_value per code, and project_every >= 1")
    fixed = h_fixed is not None
    if fixed and not h_fixed > 0:
        raise ValueError("h_fixed must be positive")
    sec = section if section is not None else Section(coef=(0.0,) * n, code=rk.SECTION_NONE)
    n_cross = max(1, int(max_crossings)) if section is not None else 1
    iopt = np.array([max_steps, int(compensated), project_every, sec.code,
                     int(np.sign(sec.direction)), n_cross, int(fixed)], dtype=np.int64)
    fopt = np.array([rtol, h_fixed if fixed else control.h0, control.h_max, control.safety,
                     control.fac_min, control.fac_max, control.beta], dtype=np.float64)
    atol_v = np.array(np.broadcast_to(np.asarray(atol, dtype=np.float64), (n,)))
    Y = np.empty((t_out.size, n))
    cross_t = np.empty(n_cross)
    cross_y = np.empty((n_cross, n))
    y_stop = np.empty(n)
    stats = np.zeros(5, dtype=np.int64)
    t0 = time.perf_counter()
    kern = rk.rk_integrate
    if generated and model in generate.GENERATED_MODELS:
        kern = generate.generated_integrator(model, p).rk_integrate
    status, t_stop = kern(int(model), p, y0, t_out, A, c, b, E, P, meth, iopt,
                                     fopt, atol_v, codes, vals, sec.packed(n), Y, cross_t,
                                     cross_y, y_stop, stats)
    wall = time.perf_counter() - t0
    m, k = stats[rk.S_SAMPLES], stats[rk.S_CROSSINGS]
    message = status_message(status)
    if status != L.OK:
        message += f" (stopped at t = {t_stop:.17g})"
    return IntegrationResult(
        t=t_out[:m].copy(), y=Y[:m], status=int(status), message=message,
        t_stop=float(t_stop), y_stop=y_stop, steps=int(stats[rk.S_ACCEPTED]),
        rejected=int(stats[rk.S_REJECTED]), rhs_calls=int(stats[rk.S_RHS]), wall_s=wall,
        method=method, crossings_t=cross_t[:k].copy(), crossings_y=cross_y[:k].copy())


def _integrate_symmetric(model, p, y0, t_out, method, h, max_steps, max_iter=60):
    """The Gauss collocation kernel (solvers.kernels.gauss): equal steps <= h in each
    output interval, stages iterated to round-off, compensated summation."""
    m = collocation.load(method)
    n = y0.size
    Y = np.empty((t_out.size, n))
    y_stop = np.empty(n)
    stats = np.zeros(4, dtype=np.int64)
    t0 = time.perf_counter()
    status, t_stop = gauss.gauss_integrate(int(model), p, y0, t_out, m.A, m.b, m.c, m.X, h,
                                           int(max_steps), int(max_iter), Y, y_stop, stats)
    wall = time.perf_counter() - t0
    k = stats[gauss.G_SAMPLES]
    message = status_message(status)
    if status != L.OK:
        message += f" (stopped at t = {t_stop:.17g})"
    return IntegrationResult(
        t=t_out[:k].copy(), y=Y[:k], status=int(status), message=message,
        t_stop=float(t_stop), y_stop=y_stop, steps=int(stats[gauss.G_STEPS]), rejected=0,
        rhs_calls=int(stats[gauss.G_RHS]), wall_s=wall, method=method)


class _Singular(Exception):
    pass


def solve_ivp_reference(model, p, y0, t_out, method="DOP853", rtol=1e-10, atol=1e-12,
                        fun=None) -> IntegrationResult:
    """scipy.integrate.solve_ivp on the same problem. `fun(t, y) -> dy/dt` defaults to a
    plain-Python wrapper of the compiled rhs (the lead's independent numpy field can be
    passed instead)."""
    from scipy.integrate import solve_ivp  # lazily: scipy costs ~0.9 s of start-up

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

    def counted(t, y):
        calls[0] += 1
        last_t[0] = t
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
