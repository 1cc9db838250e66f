"""Python entry point of the compiled Runge-Kutta integrators (diffrax-style separation).

*What* is integrated: a model code and its parameter vector (`solvers.kernels.layout`);
*how*: a method name (a tableau of `solvers.integrate.tableaux`) and a `StepControl`; *what to
record*: the output times `t_out`, integrals to project onto, a `Section` to cross.
integrate()'s keywords make one typed record of the run's options (`RunOptions`,
solvers/integrate/options.py), which `run_options` packs into the float/int arrays the
kernel takes (poliastro style) only at the compiled call, and the kernel's status code
becomes a message; the kernel knows nothing of it.

What a run returns is solvers/integrate/result.py's; scipy's run of the same problem,
the independent check, solvers/integrate/reference.py's; whether a kernel is compiled,
solvers/compile_state.py's.
"""

import time
from functools import cache

import numpy as np

from solvers.integrate import collocation, tableaux
from solvers.integrate.options import (
    Projection,
    RunOptions,
    Section,  # noqa: F401 (its callers import it from here)
    StepControl,
    fopt,
)
from solvers.integrate.result import OK_TEXT, IntegrationResult, result, status_message
from solvers.integrate.times import (
    TRUSTED_TIMES,
    checked_times,
    f64,
    output_times,  # noqa: F401 (its callers import it from here)
    trusted_or_checked,
)
from solvers.kernels import (
    baked,
    field_modules,
    gauss,
    generate,
    loop_kernel,
    module_cache,
    rk,
    small,
)
from solvers.kernels import layout as L


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


# the small kernels bake these tableaux in (the kernels layer cannot import this one)
baked.set_provider(lambda: {name: method_arrays(name) for name in tableaux.METHODS})


def initial_integrals(model, p, y0, codes) -> np.ndarray:
    y0 = np.array(y0, dtype=np.float64)
    p = np.array(p, dtype=np.float64)
    return np.array([rk.model_integral(int(k), int(model), y0, p) for k in codes])


# --- the thin entry: what does not change between calls is computed once ------------------

# the kernel only reads the method arrays (tableau coefficients), so one copy per tableau
# serves every call; private, writable (a read-only array is another numba type)
_method_arrays = cache(method_arrays)
_NO_DENSE = np.zeros((0, 1))
_NO_CODES = np.zeros(0, dtype=np.int64)
_NO_VALUES = np.zeros(0)
_NO_SECTION: dict = {}   # state dimension -> zero section coefficients
_CACHE_MAX = 1024
_F64 = np.dtype(np.float64)


# the option vectors of a call, memoized on their values (the kernel only reads them)
_OPTION_ARRAYS: dict = {}


def _option_arrays(iopt: tuple, fopt: tuple):
    key = (iopt, fopt)
    hit = _OPTION_ARRAYS.get(key)
    if hit is None:
        if len(_OPTION_ARRAYS) > _CACHE_MAX:
            _OPTION_ARRAYS.clear()
        hit = _OPTION_ARRAYS[key] = (np.array(iopt, dtype=np.int64),
                                     np.array(fopt, dtype=np.float64))
    return hit


# generated integrators: (model, p bytes) -> module (whether one is compiled is
# solvers/compile_state.py's question). The loop kernel's tableau loops on the generated
# field: the
# dop853 and vern9 stages written out as straight-line code saved little time per rhs call
# on this opt-in path for twice the compile, so they are not used (docs/performance.md)
_GEN_MODULES: dict = {}


def generated_module(model: int, p: np.ndarray):
    """The loop kernel on the case's generated field (field_modules.generated_integrator),
    memoized per parameter vector."""
    key = (int(model), p.tobytes())
    mod = _GEN_MODULES.get(key)
    if mod is None:
        if len(_GEN_MODULES) > _CACHE_MAX:
            _GEN_MODULES.clear()
        mod = _GEN_MODULES[key] = field_modules.generated_integrator(model, p)
    return mod


# The tableaux with small kernels (solvers/kernels/small.py): a plain run of a model with a
# generated field and one of these runs its small kernel, whatever is compiled (so the same
# request gives the same bits whatever the cache holds).
SMALL_METHODS = ("dop853", "vern9")
SMALL_SECTIONS = "small-sections"     # the kernel's name in a result (a plain run's: "small")
SMALL_PROJECTION = "small-projection"
SMALL_REFUSED = (f"kernel = 'small': a run of a model with a generated field, a tableau of "
                 f"{', '.join(SMALL_METHODS)}, dense output, no fixed step, and a section "
                 "or a projection but not both")
_SMALL_MODULES: dict = {}


def small_module(model: int, p, method: str, sections: bool = False,
                 projection: bool = False):
    """The small kernel of the case's structure and tableau (sections: the one with
    section crossings; projection: the one with projection), compiled on its first call,
    then loaded from numba's on-disk cache, memoized per parameter vector."""
    p = np.asarray(p, dtype=np.float64)
    key = (int(model), p.tobytes(), method, bool(sections), bool(projection))
    mod = _SMALL_MODULES.get(key)
    if mod is None:
        if len(_SMALL_MODULES) > _CACHE_MAX:
            _SMALL_MODULES.clear()
        mod = _SMALL_MODULES[key] = small.small_kernel(model, p, method, bool(sections),
                                                       bool(projection))
    return mod


def is_plain(model, method, *, project=False, section=None, compensated=False,
             fixed=False, dense_output=True) -> bool:
    """Whether integrate() runs the small kernel for these options (and generated is
    not False): what the route depends on is the request, never the cache. Compensated
    sums are a run-time flag of the small kernels (method "auto" uses them)."""
    del compensated
    return section is None and not project and small_fits(model, method, fixed=fixed,
                                                          dense_output=dense_output)


def small_fits(model, method, *, fixed=False, dense_output=True) -> bool:
    """Whether the small kernels (solvers/kernels/small.py) take a run of these options:
    a plain run's kernel, or with a section or a projection the one kernel="small" runs
    (a model with a generated field, a tableau of SMALL_METHODS, dense output, no fixed
    step)."""
    return (model in generate.GENERATED_MODELS and method in SMALL_METHODS and not fixed
            and dense_output)


_CONTROL = StepControl()     # the default (one object: the plain entry's memos key on it)


def integrate(model, p, y0, t_out, *, method="dop853", rtol=1e-10, atol=1e-12,
              max_steps=10_000_000, compensated=False, project_codes=(), project_values=None,
              project_every=1, section=None, max_crossings=100_000, h_fixed=None,
              dense_output=True, control=_CONTROL,
              generated=None, kernel=None) -> IntegrationResult:
    """Integrate `model` from (t_out[0], y0) and return the states at the times t_out.

    rtol/atol: scaled RMS error per step (atol may be a vector); h_fixed: run with this
    fixed step and no error control instead. max_steps bounds the attempted steps.
    project_codes: integral codes (`solvers.kernels.integrals`, or rk.TEST_* for the test
    models) kept at project_values (default: their values at y0), every project_every-th
    step. section: record up to max_crossings crossings; the run stops at that number.
    dense_output=False: clip the steps to land on every output time instead of
    interpolating (the states are then step endpoints; it costs steps).
    generated: which field the kernel is compiled against, for the models that have a
    generated one (solvers/kernels/generate.py; the others always run the general field).
    None (default): a plain run (`is_plain`: samples by dense output, no projection, no
    section, not fixed, a tableau of SMALL_METHODS; compensated or not) runs the small
    kernel of the case's structure (solvers/kernels/small.py: the generated field; a few
    seconds of compile on the first use of a structure, then numba's cache), any other run
    the general kernel: the route depends on the request only, so the same request gives
    the same bits whatever the cache holds (the small kernel equals the generated loop
    kernel bit for bit: tests/test_small.py). True: the generated field, by the small
    kernel for a plain run, else by the generated loop kernel (compiled on first use
    of a structure, a long compile); False: the general support-function field, the
    reference.
    The result's `vector_field` says which field ran, `kernel` which compiled form.
    kernel: None (default) the rule above; "rk": the loop kernel whatever the run (the
    tests' reference for the small kernels); "small": the small kernel, a run with a
    section or a projection included (its kernel with sections: the steps and samples of
    the generated loop kernel bit for bit, the crossings located by rk.py's own code on
    the general field, result kernel "small-sections"; with projection: the generated
    integrator's bits, the loop kernel's own projection, "small-projection"), ValueError for a run
    no small kernel takes.
    A run with a section or a projection takes it only when asked (a Poincare map decides
    by its size: solvers/maps/poincare.py map_kernel): it compiles once per structure.
    """
    if generated is None and kernel is None and not module_cache.disk_cache_ok():
        generated = False   # no kernel cache to write: the general kernels
    if (kernel is None and generated is not False and method in SMALL_METHODS
            and h_fixed is None and section is None and dense_output
            and project_values is None and not len(project_codes) and project_every >= 1
            and model in generate.GENERATED_MODELS):
        # a plain run (is_plain): the small kernel, by the short entry below
        return _integrate_small(model, p, y0, t_out, method, rtol, atol, max_steps,
                                compensated, control)
    t_out, y0, p, _ = _inputs(model, p, y0, t_out)
    if method in collocation.METHODS:
        if project_codes or section is not None or not h_fixed or not h_fixed > 0:
            raise ValueError(f"{method} is a symmetric fixed-step method: give h_fixed > 0; "
                             "it takes no projection and no section")
        return _integrate_symmetric(model, p, y0, t_out, method, float(h_fixed), max_steps)
    if kernel not in (None, "rk", "small"):
        raise ValueError(f"kernel = {kernel!r}: None, 'rk' or 'small'")
    if len(project_codes):
        codes = np.asarray(project_codes, dtype=np.int64).ravel()
        if project_values is None:
            project_values = initial_integrals(model, p, y0, codes)
        vals = np.array(project_values, dtype=np.float64).ravel()
    else:
        codes, vals = _NO_CODES, (_NO_VALUES if project_values is None
                                  else np.array(project_values, dtype=np.float64).ravel())
    if vals.size != codes.size or project_every < 1:
        raise ValueError("one project_value per code, and project_every >= 1")
    projection = (Projection(tuple(codes.tolist()), tuple(vals.tolist()), int(project_every))
                  if codes.size else None)
    opts = RunOptions(method=method, rtol=rtol, atol=atol, control=control, h_fixed=h_fixed,
                      dense_output=dense_output, compensated=compensated, section=section,
                      max_crossings=max_crossings, projection=projection,
                      max_steps=max_steps)
    return run_options(model, p, y0, t_out, opts, generated=generated, kernel=kernel)


def run_options(model, p, y0, t_out, opts: RunOptions, *, generated=None,
                kernel=None) -> IntegrationResult:
    """integrate() of checked inputs (float64 arrays: y0, t_out strictly increasing) and a
    RunOptions: the kernel chosen by integrate()'s rule, the options packed into its
    arrays here, at the compiled call."""
    n = y0.size
    method = opts.method
    A, c, b, E, P, meth = _method_arrays(method)
    if not opts.dense_output:
        P = _NO_DENSE
    proj = opts.projection
    if proj is None:
        codes, vals, project_every = _NO_CODES, _NO_VALUES, 1
    else:
        codes = np.array(proj.codes, dtype=np.int64)
        vals = (initial_integrals(model, p, y0, codes) if proj.values is None
                else np.array(proj.values, dtype=np.float64))
        project_every = proj.every
    section = opts.section
    if section is None:
        sec_coef = _NO_SECTION.get(n)
        if sec_coef is None:
            sec_coef = _NO_SECTION[n] = np.zeros(n + 1)
    else:
        sec_coef = section.packed(n)
    ipack, fpack = opts.packed()
    sec_code, sec_dir, n_cross = (ipack[rk.I_SECTION], ipack[rk.I_DIRECTION],
                                  ipack[rk.I_MAX_CROSS])
    iopt, fopt_v = _option_arrays(ipack, fpack)
    atol_v = opts.atol_vector(n)
    compensated, max_steps = opts.compensated, opts.max_steps
    # fresh outputs on every call: Y and y_stop are handed to the caller
    Y = np.empty((t_out.size, n))
    cross_t = np.empty(n_cross)
    cross_y = np.empty((n_cross, n))
    y_stop = np.empty(n)
    stats = np.zeros(5, dtype=np.int64)
    if kernel in (None, "small") and generated is not False and is_plain(
            model, method, project=bool(codes.size), section=section,
            compensated=compensated, fixed=opts.fixed, dense_output=opts.dense_output):
        run = small_module(model, p, method).run
        t0 = time.perf_counter()
        status, t_stop = run(p, y0, t_out, int(max_steps), bool(compensated), fopt_v, atol_v,
                             Y, y_stop, stats)
        wall = time.perf_counter() - t0
        return result(t_out, Y, y_stop, stats, status, t_stop, wall, method, cross_t,
                       cross_y, "generated", "small")
    if kernel == "small":   # a section or a projection: the small kernel with it
        if (generated is False or (section is not None and codes.size) or not small_fits(
                model, method, fixed=opts.fixed, dense_output=opts.dense_output)):
            raise ValueError(SMALL_REFUSED)
        t0 = time.perf_counter()
        if section is not None:
            run = small_module(model, p, method, sections=True).run
            status, t_stop = run(p, y0, t_out, int(max_steps), bool(compensated), fopt_v,
                                 atol_v, Y, y_stop, stats, int(model), sec_code, sec_dir,
                                 n_cross, sec_coef, A, c, b, meth, cross_t, cross_y)
            used = SMALL_SECTIONS
        else:
            run = small_module(model, p, method, projection=True).run
            status, t_stop = run(p, y0, t_out, int(max_steps), bool(compensated), fopt_v,
                                 atol_v, Y, y_stop, stats, int(model), codes, vals,
                                 int(project_every))
            used = SMALL_PROJECTION
        wall = time.perf_counter() - t0
        return result(t_out, Y, y_stop, stats, status, t_stop, wall, method, cross_t,
                       cross_y, "generated", used)
    kern, used = loop_kernel.rk_integrate, "general"
    if generated and model in generate.GENERATED_MODELS:
        kern, used = generated_module(model, p).rk_integrate, "generated"
    t0 = time.perf_counter()
    status, t_stop = kern(int(model), p, y0, t_out, A, c, b, E, P, meth, iopt, fopt_v,
                          atol_v, codes, vals, sec_coef, Y, cross_t, cross_y, y_stop, stats)
    wall = time.perf_counter() - t0
    return result(t_out, Y, y_stop, stats, status, t_stop, wall, method, cross_t, cross_y,
                   used, "rk")


# A plain run's entry. The same checks, options and kernel as the general entry's route to
# the small kernel, with what a plain run does not use left out: no tableau arrays, section
# or crossing buffers, and the option vectors memoized. A short run (|M| small, T = 200)
# spends little time in the kernel, and the general entry was a large part of its time
# (bench/limit.py --gap; docs/performance.md).
_PLAIN_FOPT: dict = {}
_PLAIN_ATOL: dict = {}
_NO_CROSSINGS_T = np.empty(0)
_NO_CROSSINGS_T.setflags(write=False)
_NO_CROSSINGS_Y: dict = {}    # state dimension -> a read-only (0, n) array


def _plain_fopt(rtol, control: StepControl) -> np.ndarray:
    """rk.py's packed float options (F_*) of a plain run, memoized (the kernel only reads
    them)."""
    # keyed on the control's identity (its dataclass hash is Python code, slower), the
    # control kept in the entry so that the identity stays its own
    key = (float(rtol), id(control))
    hit = _PLAIN_FOPT.get(key)
    if hit is None or hit[0] is not control:
        if len(_PLAIN_FOPT) > _CACHE_MAX:
            _PLAIN_FOPT.clear()
        hit = _PLAIN_FOPT[key] = (control, np.array(fopt(key[0], control),
                                                     dtype=np.float64))
    return hit[1]


def _plain_atol(atol, n: int) -> np.ndarray:
    """atol as the kernel's vector (the kernel only reads it): a scalar's memoized."""
    if isinstance(atol, float | int):
        key = (float(atol), n)
        hit = _PLAIN_ATOL.get(key)
        if hit is None:
            if len(_PLAIN_ATOL) > _CACHE_MAX:
                _PLAIN_ATOL.clear()
            hit = _PLAIN_ATOL[key] = np.full(n, float(atol))
        return hit
    return np.array(np.broadcast_to(np.asarray(atol, dtype=np.float64), (n,)))


def _inputs(model, p, y0, t_out):
    """The output times, the start and a private float64 copy of p, checked against the
    model's state dimension: (t_out, y0, p, n), for both entries of integrate()."""
    t_out = trusted_or_checked(t_out)
    y0 = f64(y0)
    p = np.array(p, dtype=np.float64)
    n = y0.size
    if n != L.STATE_DIM[model]:
        raise ValueError(f"model {model} has a state of dimension {L.STATE_DIM[model]}")
    return t_out, y0, p, n


# A plain run's plan: what the kernel needs besides the run's own arrays, memoized on the
# request's values (model, tableau, parameter bytes, rtol, a scalar atol and the step
# control's identity): the kernel, its option vectors, the state dimension and the empty
# crossings. One dictionary lookup in place of four (the kernel, fopt, atol, the empty
# crossings), a visible part of a short run's entry (bench/limit.py --gap).
_PLANS: dict = {}


def _plain_plan(model, p, method, rtol, atol, control) -> tuple:
    n = L.STATE_DIM[model]
    cross_y = _NO_CROSSINGS_Y.get(n)
    if cross_y is None:
        cross_y = _NO_CROSSINGS_Y[n] = np.empty((0, n))
        cross_y.setflags(write=False)
    p = f64(p)     # the plan's private copy
    return (control, small_module(model, p, method).run, _plain_fopt(rtol, control),
            _plain_atol(atol, n), n, cross_y, p)


def _integrate_small(model, p, y0, t_out, method, rtol, atol, max_steps, compensated,
                     control) -> IntegrationResult:
    hit = TRUSTED_TIMES.get(id(t_out))
    if hit is not None and hit[0] is t_out:
        t_out, private = hit[1], False      # the shared twin: copied for the result
    else:
        t_out, private = checked_times(t_out), True     # a fresh array of this call
    y0 = f64(y0)
    n = y0.size
    if type(atol) is float or type(atol) is int:
        # keyed on p's values as float64 bytes: a float64 array's own bytes, with no copy
        # (the plan holds its private copy, which the kernel only reads)
        pb = (p.tobytes() if type(p) is np.ndarray and p.dtype is _F64
              else np.array(p, dtype=np.float64).tobytes())
        key = (model, method, pb, rtol, atol, id(control))
        plan = _PLANS.get(key)
        if plan is None or plan[0] is not control:
            if len(_PLANS) > _CACHE_MAX:
                _PLANS.clear()
            plan = _PLANS[key] = _plain_plan(model, p, method, rtol, atol, control)
    else:       # a vector atol: the plan is not memoized (_plain_atol copies the vector)
        plan = _plain_plan(model, p, method, rtol, atol, control)
    _, run, fopt, atol_v, n_model, cross_y, p = plan
    if n != n_model:
        raise ValueError(f"model {model} has a state of dimension {n_model}")
    N = t_out.shape[0]
    Y = np.empty((N, n))
    y_stop = np.empty(n)
    stats = np.empty(5, dtype=np.int64)     # the kernel zeroes its counters first
    t0 = time.perf_counter()
    status, t_stop = run(p, y0, t_out, int(max_steps), bool(compensated), fopt, atol_v, Y,
                         y_stop, stats)
    wall = time.perf_counter() - t0
    accepted, rejected, calls, m, _ = stats.tolist()   # rk.py's S_* order (_S_ORDER)
    if status == L.OK and m == N:       # every sample reached: the result as it stands
        return IntegrationResult(t_out if private else t_out.copy(), Y, 0, OK_TEXT,
                                 float(t_stop), y_stop, accepted, rejected, calls, wall,
                                 method, _NO_CROSSINGS_T, cross_y, "generated", "small")
    return result(t_out, Y, y_stop, stats, status, t_stop, wall, method, _NO_CROSSINGS_T,
                   cross_y, "generated", "small", copy_crossings=False)


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
        rhs_calls=int(stats[gauss.G_RHS]), wall_s=wall, method=method, kernel="gauss")
