"""One entry point for a run: `simulate(case, params, state0, t_end, ...)`.

It validates everything first (InputError, nothing runs), integrates the equations of
motion (eq1.1 with eq1.2 on a plane, eq1.3 on a sphere) with the compiled in-house
Runge-Kutta kernels or, for `scipy-*` methods, with scipy's solve_ivp on the independent
NumPy field of solvers/models/reference.py, and reports the drift of every invariant the
case carries. A run that meets a singularity returns what it computed up to there, with
status "singular" and a message saying where: never NaN as a result.

A rubber case (CaseSpec.constraint "rubber": no spin about the normal) runs the same
way: its fields add the reaction of (omega, gamma) = 0, its scipy route runs the
Lagrange-d'Alembert NumPy field (solvers/models/rubber_lagrange.py), and it reports the
integral "spin", (omega, gamma), beside the energy and gamma^2.

A plain run of a compiled Runge-Kutta method (dop853 or vern9, no projection) runs the
case's generated field (solvers/kernels/generate.py) in its small kernel, any other run the
general field (`field`, FIELDS): the route depends on the request, never on what happens
to be compiled, so the same request gives the same numbers. A repeated run of the same
case is thin: the model, the initial state, the options and the output times are
validated once and memoized, and the invariants and their drift come from one compiled
call (bench/entry_overhead.py measures that overhead).
"""

import math
from dataclasses import dataclass, field
from functools import cache

import numpy as np

from solvers.errors import InputError
from solvers.integrate import auto as automatic
from solvers.integrate import taylor_backend
from solvers.integrate.collocation import METHODS
from solvers.integrate.integrator import integrate, output_times
from solvers.integrate.reference import solve_ivp_reference
from solvers.integrate.tableaux import TABLEAUX
from solvers.kernels.integrals import integral_table
from solvers.models import rubber_lagrange
from solvers.models.cases import Model, build, initial_state
from solvers.models.observables import Invariants, public_name
from solvers.models.reference import field as ref_field
from solvers.models.rubber_bodies import from_vector

SCIPY_METHODS = {"scipy-dop853": "DOP853", "scipy-rk45": "RK45", "scipy-lsoda": "LSODA",
                 "scipy-radau": "Radau"}
DEFAULT_METHOD = "dop853"
MAX_SAMPLES = 200_000
# which vector field the compiled Runge-Kutta kernels run (solvers/integrate/integrator.py):
# auto: integrate()'s rule: the generated field in the small kernel for a plain run, else
# the general one; generated: the generated field for every compiled run (a projected run
# compiles rk.py on it on first use of a structure, which takes a while); general: the
# general support-function field, the reference
FIELDS = {"auto": None, "generated": True, "general": False}


@cache
def compiled_methods() -> tuple[str, ...]:
    """The adaptive explicit Runge-Kutta methods (solvers/tableaux)."""
    return tuple(TABLEAUX)


@cache
def symmetric_methods() -> tuple[str, ...]:
    """The symmetric fixed-step Gauss collocation methods (they take `step`, not rtol)."""
    return tuple(METHODS)


TAYLOR_METHODS = ("taylor", "auto")   # heyoka's Taylor backend; auto: chosen from the front


@cache
def methods() -> tuple[str, ...]:
    """The integration methods `simulate` accepts, by name.

    The adaptive explicit Runge-Kutta methods compiled in-house (tableaux in
    solvers/integrate/tableaux), the symmetric fixed-step Gauss collocation methods (they take
    `step`, not rtol and atol), heyoka's Taylor integrator ("taylor") and its automatic
    choice ("auto", from the measured work-precision front per case and tolerance), and
    scipy's solve_ivp on an independent NumPy field ("scipy-*", the reference).

    Returns
    -------
    tuple of str
        The method names, in that order; the first, "dop853", is the default.

    Examples
    --------
    >>> import solvers
    >>> m = solvers.methods()
    >>> m[0], "vern9" in m, "gauss4" in m, "scipy-radau" in m
    ('dop853', True, True, True)
    """
    return (*compiled_methods(), *symmetric_methods(), *TAYLOR_METHODS, *SCIPY_METHODS)


@dataclass
class SimulationResult:
    """One run of `simulate`: the sampled trajectory, its invariants and how it went.

    Attributes
    ----------
    case : str
        The case id.
    params : dict of str to float
        Every parameter of the run, the optional ones with their defaults.
    state_labels : tuple of str
        The names of the state's components: ("M1", "M2", "M3", "g1", "g2", "g3") for
        (M, gamma), the angular momentum about the contact point and the unit normal in
        body axes; ("M1", "M2", "M3", "r1", "r2") for the flat-base cases.
    t : numpy.ndarray, shape (n,)
        The sample times; fewer than asked when the run stopped early.
    state : numpy.ndarray, shape (n, len(state_labels))
        The state at the sample times.
    invariants : dict of str to numpy.ndarray
        Every first integral the case carries at the sample times, "energy" first, under
        its output name (solvers/models/observables.py PUBLIC_NAMES), the same in JSON, CSV
        and Arrow: "gamma_squared" is |gamma|^2, "M_squared" is |M|^2 (never "M2", the
        component). A lookup by the kernels' code name ("M2") finds the same series.
    stats : dict
        How the run went: steps, rejected steps, right-hand-side calls, the method, field
        and kernel that ran, the tolerances, and "drift", the drift of every invariant.
    status : {"ok", "singular", "budget"}
        "singular": the run met a singularity and stopped there (see `message`);
        "budget": it ran out of steps (max_steps).
    message : str
        Why the run stopped early; empty when status is "ok".
    ok : bool
        status == "ok".

    Examples
    --------
    >>> import solvers
    >>> spec = solvers.cases()["plane/chaplygin-ball"]
    >>> res = solvers.simulate(spec.id, spec.example, spec.state, t_end=2.0, samples=5)
    >>> res.ok, res.t.shape, res.state.shape, res.state_labels
    (True, (5,), (5, 6), ('M1', 'M2', 'M3', 'g1', 'g2', 'g3'))
    >>> list(res.invariants), res.drift("area") < 1e-10
    (['energy', 'gamma_squared', 'area', 'M_squared'], True)
    >>> sorted(res.to_json())[:4]
    ['case', 'invariants', 'message', 'params']
    """

    case: str
    params: dict[str, float]
    state_labels: tuple[str, ...]
    t: np.ndarray
    state: np.ndarray
    invariants: dict[str, np.ndarray]
    stats: dict = field(default_factory=dict)
    status: str = "ok"          # ok | singular | budget
    message: str = ""

    def __post_init__(self):
        # one name per quantity: whatever vocabulary the caller built it with
        self.invariants = Invariants({public_name(k): v for k, v in self.invariants.items()})

    @property
    def ok(self) -> bool:
        """status == "ok"."""
        return self.status == "ok"

    def drift(self, name: str) -> float:
        """The drift of invariant `name` along the run: max |F(t) - F(0)| / max(|F(0)|, 1).

        Parameters
        ----------
        name : str
            An invariant of the run (a key of `invariants`).

        Returns
        -------
        float
            0.0 for a run without samples.
        """
        v = self.invariants[name]
        return float(np.max(np.abs(v - v[0])) / max(abs(v[0]), 1.0)) if len(v) else 0.0

    def to_json(self, arrays: bool = False) -> dict:
        """The result as plain data for JSON (what `rolling simulate --json` prints).

        Parameters
        ----------
        arrays : bool, default False
            Leave t, state and the invariants as numpy arrays, for a serializer that
            writes them directly (such as orjson); else nested lists.

        Returns
        -------
        dict
            case, params, status, message, state_labels, t, state, invariants, stats.
        """
        conv = (lambda a: a) if arrays else (lambda a: a.tolist())
        return {
            "case": self.case,
            "params": self.params,
            "status": self.status,
            "message": self.message,
            "state_labels": list(self.state_labels),
            "t": conv(self.t),
            "state": conv(self.state),
            "invariants": {k: conv(v) for k, v in self.invariants.items()},
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


# --- the thin entry: a repeated run of the same case validates and builds nothing twice ----
# Bounded memos of validated inputs (InputError is raised before anything is stored, so
# a bad input is never remembered). Their values are never handed to the caller as they
# are: the result's params is a copy, and arrays are fresh per run.
_CACHE_MAX = 512
_MODELS: dict = {}
_STATES: dict = {}


def _remember(memo: dict, key, value):
    if len(memo) >= _CACHE_MAX:
        memo.clear()
    memo[key] = value
    return value


_OPTIONS: dict = {}


def _check_options(t_end, method, rtol, atol, samples, project, max_steps, step, field):
    """Every run option checked (InputError), memoized on the options and their types
    (2 and 2.0 are equal keys but not equally valid sample counts)."""
    opts = (t_end, method, rtol, atol, samples, project, max_steps, step, field)
    try:
        key = (opts, tuple(map(type, opts)))
        if key in _OPTIONS:
            return
    except TypeError:
        key = None
    _check_run_options(t_end, method, rtol, atol, samples)
    if field not in FIELDS:
        raise InputError(f"field = {field!r}: choose one of {', '.join(FIELDS)}")
    if field == "generated" and method not in compiled_methods():
        raise InputError(f"field = 'generated': only the compiled Runge-Kutta methods "
                         f"({', '.join(compiled_methods())}) run the generated field; "
                         f"{method} does not")
    if project and method in SCIPY_METHODS:
        raise InputError("project = true needs a compiled method (projection happens inside "
                         f"the step); {method} is a scipy reference method")
    check_step(method, step, t_end, max_steps, project)
    if key is not None:
        _remember(_OPTIONS, key, True)


def _built(case, params, allow_any_inertia):
    model = build(case, params, allow_any_inertia=allow_any_inertia)
    return model, np.array(model.integral_codes, dtype=np.int64)


def _model(case, params, allow_any_inertia) -> tuple[Model, np.ndarray, object]:
    """build(), memoized on (case, params, allow_any_inertia): (model, its integral codes
    as the kernel's array, the memo key)."""
    try:
        key = (case, tuple(params.items()) if params else (), bool(allow_any_inertia))
        hit = _MODELS.get(key)
    except (TypeError, AttributeError):   # unhashable input: build() says what is wrong
        return (*_built(case, params, allow_any_inertia), None)
    if hit is None:
        hit = _remember(_MODELS, key, _built(case, params, allow_any_inertia))
    return (*hit, key)


def _initial(model: Model, key, state0) -> np.ndarray:
    """initial_state(), memoized per model and state (a read-only array)."""
    try:
        skey = (key, tuple(state0)) if key is not None else None
        y0 = _STATES.get(skey) if skey is not None else None
    except TypeError:
        skey = y0 = None
    if y0 is None:
        y0 = initial_state(model, state0)
        y0.setflags(write=False)
        if skey is not None:
            _remember(_STATES, skey, y0)
    return y0


def _sample_times(t_end, samples) -> np.ndarray:
    """linspace(0, t_end, samples), checked distinct once (integrator.output_times)."""
    t_out = output_times(t_end, samples)
    if t_out is None:
        raise InputError(f"t_end = {t_end!r} is too small for {samples} distinct sample "
                         "times")
    return t_out


def _integrate(model: Model, y0, t_out, method, rtol, atol, project, max_steps, step=None,
               generated=None, precision=None, compensated=False):
    """Compiled kernels, heyoka's Taylor integrator, or scipy's solve_ivp on the
    independent NumPy field."""
    if method == "taylor":
        return taylor_backend.run(model.model, model.p, y0, t_out, rtol=rtol,
                                  precision=precision, max_steps=max_steps)

    if method in SCIPY_METHODS and model.case.constraint == "rubber":
        body = from_vector(model.p)

        def fun(t, y):   # the Lagrange-d'Alembert derivation, independent of the kernels
            return rubber_lagrange.field(body, y)
    elif method in SCIPY_METHODS:
        def fun(t, y):
            return ref_field(model.model, model.p, y)
    if method in SCIPY_METHODS:
        with np.errstate(all="ignore"):
            return solve_ivp_reference(model.model, model.p, y0, t_out,
                                       method=SCIPY_METHODS[method], rtol=rtol, atol=atol,
                                       fun=fun, max_steps=max_steps)
    if method in symmetric_methods():
        return integrate(model.model, model.p, y0, t_out, method=method, h_fixed=step,
                         max_steps=max_steps)
    return integrate(model.model, model.p, y0, t_out, method=method, rtol=rtol, atol=atol,
                     max_steps=max_steps, compensated=compensated,
                     project_codes=model.integral_codes if project else (),
                     generated=generated)


def simulate(case: str, params: dict | None, state0, t_end: float, *,
             method: str = DEFAULT_METHOD, rtol: float = 1e-10, atol: float = 1e-12,
             samples: int = 201, project: bool = False, max_steps: int = 50_000_000,
             allow_any_inertia: bool = False, step: float | None = None,
             field: str = "auto", precision: str | None = None) -> SimulationResult:
    """Integrate a case from an initial state over [0, t_end] and check its invariants.

    Every input is validated before anything runs (InputError). The equations of motion
    are eq1.1 with eq1.2 on a plane, eq1.3 on a sphere. A run that meets a singularity
    returns what it computed up to there with status "singular", never NaN.

    Parameters
    ----------
    case : str
        A case id, a key of `cases()`, e.g. "plane/chaplygin-ball".
    params : dict of str to float, or None
        The case's parameters by name (`CaseSpec.required`; the `CaseSpec.optional` ones
        default). `CaseSpec.example` is a valid set.
    state0 : sequence of float
        The initial state, in the order of `SimulationResult.state_labels`: (M, gamma)
        with |gamma| = 1, or (M, r1, r2) for the flat-base cases. `CaseSpec.state` is one.
    t_end : float
        The end time, positive.
    method : str, default "dop853"
        One of `methods()`.
    rtol, atol : float, default 1e-10, 1e-12
        Relative and absolute tolerances of the adaptive methods; rtol in [1e-16, 0.1],
        atol in (0, 1].
    samples : int, default 201
        The number of equally spaced output times in [0, t_end], from 2 to 200 000.
    project : bool, default False
        Project the state back onto the level set of the invariants after every step
        (compiled adaptive methods only).
    max_steps : int, default 50 000 000
        The step budget; a run that exhausts it returns with status "budget".
    allow_any_inertia : bool, default False
        Accept a tensor of inertia that no rigid body has (the triangle inequalities).
    step : float or None, default None
        The step of a symmetric fixed-step method (gauss4, gauss6, gauss8), required there
        and refused elsewhere.
    field : {"auto", "generated", "general"}, default "auto"
        The vector field of the compiled Runge-Kutta methods: "auto" runs the case's
        generated field for a plain run (dop853 or vern9, no projection) and the general
        one otherwise; "general" is the reference. stats["field"] and stats["kernel"] say
        which ran.
    precision : {"double", "long double", "quad"} or None, default None
        The floating-point precision of method "taylor"; None chooses
        (solvers/integrate/taylor_backend.py).

    Returns
    -------
    SimulationResult
        The samples, the invariants along them, stats (with stats["drift"]) and status.

    Raises
    ------
    InputError
        Unknown case or parameter, a missing parameter, a non-finite number, a body that
        cannot exist, a state off |gamma| = 1, or an option out of range.

    Examples
    --------
    >>> import solvers
    >>> spec = solvers.cases()["plane/chaplygin-ball"]
    >>> res = solvers.simulate(spec.id, spec.example, spec.state, t_end=1.0, samples=3)
    >>> res.status, res.state.shape
    ('ok', (3, 6))
    >>> res.drift("energy") < 1e-10 and res.stats["drift"]["M_squared"] < 1e-10
    True
    >>> solvers.simulate(spec.id, {"m": 1.0}, spec.state, t_end=1.0)
    Traceback (most recent call last):
    ...
    solvers.errors.InputError: missing parameters I1, I2, I3, R for case plane/chaplygin-ball ...
    """
    model, codes, key = _model(case, params, allow_any_inertia)
    y0 = _initial(model, key, state0)
    auto = None
    if method == "auto":   # from the measured work-precision front, per case and tolerance
        _check_run_options(t_end, method, rtol, atol, samples)
        auto = automatic.choose(case, model.model, rtol, float(t_end), project, step, precision)
        method, precision = auto["method"], auto["precision"]
        rtol = atol = auto["tol"]   # the front point's tolerance (auto.py)
    if method == "taylor" or precision is not None:
        taylor_backend.check_taylor_options(method, precision, project, step)
    _check_options(t_end, method, rtol, atol, samples, project, max_steps, step, field)
    t_out = _sample_times(t_end, samples)
    checked = None
    if auto is None:
        res = _integrate(model, y0, t_out, method, rtol, atol, project, max_steps, step,
                         FIELDS[field], precision)
    else:   # the choice, checked by a tighter run and tightened until it meets rtol
        def runner(rung, budget):
            return _integrate(model, y0, t_out, rung["method"], rung["tol"], rung["tol"],
                              project, budget, step, FIELDS[field], rung["precision"],
                              compensated=rung["compensated"])   # as measured

        res, checked = automatic.run_checked(auto, runner, float(t_end), max_steps,
                                             taylor_ok=auto["taylor_allowed"])
        method, precision = checked["returned"]["method"], checked["returned"]["precision"]
        rtol = atol = checked["returned"]["tol"]
    status = "ok" if res.success else ("budget" if res.budget_exhausted else "singular")
    message = "" if res.success else res.message
    t, Y = res.t, res.y[:len(res.t)]
    inv, drift = _invariants(model, codes, Y)
    vector_field = ("numpy" if method in SCIPY_METHODS else
                    "generated (heyoka)" if method == "taylor" else res.vector_field)
    stats = {"steps": res.steps, "rejected": res.rejected, "rhs_calls": res.rhs_calls,
             "wall_s": res.wall_s, "method": method, "field": vector_field,
             "kernel": getattr(res, "kernel", method),
             "rtol": rtol, "atol": atol, "projected": bool(project), "samples": len(t)}
    stats.update(getattr(res, "extra", {}))
    if auto is not None:
        stats["auto"] = {**auto, **{k: v for k, v in checked.items() if k != "returned"}}
        stats["error_estimate"] = checked["error_estimate"]
        stats["error_estimate_method"] = checked["error_estimate_method"]
    if step is not None:   # the equal steps the kernel took to land on the samples
        stats["step"] = res.t_stop / res.steps if res.steps else step
        stats["step_requested"] = step
    stats["drift"] = drift
    return SimulationResult(case, dict(model.params), model.state_labels, np.asarray(t),
                            np.asarray(Y), inv, stats, status, message)


def _invariants(model: Model, codes: np.ndarray, Y) -> tuple[dict, dict]:
    """Every integral the case carries along the rows of Y (rows of one fresh array) and
    its drift max |F(t) - F(0)| / max(|F(0)|, 1) (SimulationResult.drift), in one call."""
    out = np.empty((codes.size, len(Y)))
    drift = np.empty(codes.size)
    integral_table(codes, model.model, np.ascontiguousarray(Y), model.p, out, drift)
    names = [public_name(n) for n in model.integral_names]
    return (Invariants(zip(names, out, strict=True)),
            dict(zip(names, drift.tolist(), strict=True)))
