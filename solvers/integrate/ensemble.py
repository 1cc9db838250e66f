"""Many initial states in one compiled call.

`integrate_ensemble(model, p, Y0, t_out, **options)` validates once, packs the options once
and runs `solvers.kernels.ensemble.rk_ensemble`: `rk_integrate` for every row of Y0 in a
compiled parallel loop over the trajectories. It returns one `IntegrationResult` per row,
with the numbers `integrate(model, p, Y0[i], t_out, **options)` gives (bit for bit: the
same kernel on the same inputs, tests/test_ensemble.py), statuses per trajectory.

Beyond `integrate`'s options, for callers whose trajectories differ in more than the start
(the Poincare maps, solvers/maps/poincare.py):
  * t_out may be a table (n_traj, N): row i the output times of trajectory i, of which
    the first n_out[i] are used (rows may be ragged: pad them with anything);
  * max_steps, max_crossings and h_max may be one number or one per trajectory;
  * project_values may be one row per trajectory (default: each start's own values).

Threads: numba's parallel loop runs on its threading layer. If none was chosen (the
NUMBA_THREADING_LAYER variable), `workqueue` is taken: it survives a fork, but it is not
thread-safe, so launches are serialised by a lock (two Python threads calling at once run
one after the other, each on all its workers, and both get their own correct results).
`workers` sets numba's thread count for the call (default: every core this process may
use, at most NUMBA_NUM_THREADS).
"""

from __future__ import annotations

import os
import threading
import time
from concurrent.futures import ThreadPoolExecutor

import numba
import numpy as np

from solvers.integrate import collocation, tableaux
from solvers.integrate.integrator import (
    SMALL_REFUSED,
    SMALL_SECTIONS,
    IntegrationResult,
    Section,
    StepControl,
    initial_integrals,
    is_plain,
    method_arrays,
    small_fits,
    small_module,
    status_message,
)
from solvers.integrate.options import Projection, RunOptions
from solvers.integrate.result import result
from solvers.kernels import ensemble as kernels
from solvers.kernels import field_modules, generate, loop_kernel, module_cache, rk
from solvers.kernels import layout as L

_LAUNCH = threading.Lock()
_CONTROL = StepControl()


def default_workers() -> int:
    cores = (len(os.sched_getaffinity(0)) if hasattr(os, "sched_getaffinity")
             else (os.cpu_count() or 1))
    return max(1, min(cores, numba.config.NUMBA_NUM_THREADS))


def threading_layer() -> str:
    """The layer the ensembles run on (chosen at the first launch)."""
    _choose_layer()
    try:
        return numba.threading_layer()
    except ValueError:      # not launched yet
        return numba.config.THREADING_LAYER


def _choose_layer():
    if numba.config.THREADING_LAYER == "default":
        numba.config.THREADING_LAYER = "workqueue"


def _small_ensemble(model, p, Y0, T, counts, steps, compensated, FOPT, atol_v, method,
                    workers, sec=None, cross=None) -> list[IntegrationResult]:
    """integrate()'s route for a plain run (generated=None): the small kernel of the
    structure (solvers/kernels/small.py) per trajectory, on a pool of threads (the kernel
    is nogil): the same bits as integrate(model, p, Y0[i], ...) one by one. sec (a
    Section) and cross (the crossings per trajectory): the small kernel with sections
    (a Poincare map's runs), as integrate() runs them."""
    run = small_module(model, p, method, sections=sec is not None).run
    n = Y0.shape[1]
    empty_t, empty_y = np.empty(0), np.empty((0, n))
    if sec is not None:
        A, c, b, _, _, meth = method_arrays(method)
        code, direction, coef = sec.code, int(np.sign(sec.direction)), sec.packed(n)

    def one(i):
        t_out = np.ascontiguousarray(T[i, :counts[i]])
        Y = np.empty((t_out.size, n))
        y_stop = np.empty(n)
        stats = np.zeros(5, dtype=np.int64)
        fopt = np.ascontiguousarray(FOPT[i])
        t0 = time.perf_counter()
        if sec is None:
            status, t_stop = run(p, np.ascontiguousarray(Y0[i]), t_out, int(steps[i]),
                                 bool(compensated), fopt, atol_v, Y, y_stop, stats)
            cross_t, cross_y, kind = empty_t, empty_y, "small"
        else:
            cross_t, cross_y = np.empty(int(cross[i])), np.empty((int(cross[i]), n))
            status, t_stop = run(p, np.ascontiguousarray(Y0[i]), t_out, int(steps[i]),
                                 bool(compensated), fopt, atol_v, Y, y_stop, stats, model,
                                 code, direction, int(cross[i]), coef, A, c, b, meth,
                                 cross_t, cross_y)
            kind = SMALL_SECTIONS
        wall = time.perf_counter() - t0
        return result(t_out, Y, y_stop, stats, status, t_stop, wall, method, cross_t,
                       cross_y, "generated", kind)

    idx = range(Y0.shape[0])
    if workers == 1 or Y0.shape[0] == 1:
        return [one(i) for i in idx]
    with ThreadPoolExecutor(max_workers=workers) as pool:
        return list(pool.map(one, idx))


def generated_ensemble(model: int, p):
    """The ensemble loop (solvers/kernels/ensemble.py) bound to the case's generated
    `rk_integrate` (field_modules.generated_integrator; module_cache.bound_module: the same code,
    another callee). Its name follows the integrator module's, which already hashes the
    structure and every kernel source."""
    rk_mod = field_modules.generated_integrator(model, p)
    name = f"ens_{rk_mod.__name__}"
    return module_cache.bound_module(name, kernels, {"rk_integrate": rk_mod.rk_integrate},
                                 f"solvers/kernels/ensemble.py's loop on {rk_mod.__name__}")


def _per_traj(value, n_traj, name, dtype):
    a = np.asarray(value, dtype=dtype)
    if a.ndim == 0:
        return np.full(n_traj, a, dtype=dtype)
    if a.shape != (n_traj,):
        raise ValueError(f"{name}: one number, or one per trajectory ({n_traj}); "
                         f"got shape {a.shape}")
    return a.copy()


def _times(t_out, n_traj, n_out):
    """(T_out table (n_traj, N), n_out per row), every used prefix checked."""
    T = np.array(t_out, dtype=np.float64)
    if T.ndim <= 1:
        # a writable C-ordered copy, never the broadcast view: a read-only table, or the
        # F-ordered copy numpy makes of a view with a zero stride, is another numba
        # specialization of rk_ensemble than a Poincare map's table, and its rows another
        # of the loop kernel than integrate()'s t_out
        T = np.array(np.broadcast_to(T.ravel(), (n_traj, T.size)), order="C")
    elif T.ndim != 2 or T.shape[0] != n_traj:
        raise ValueError(f"t_out: one row of output times, or one per trajectory "
                         f"({n_traj} rows); got shape {T.shape}")
    N = T.shape[1]
    counts = (np.full(n_traj, N, dtype=np.int64) if n_out is None else
              _per_traj(n_out, n_traj, "n_out", np.int64))
    if N == 0 or np.any(counts < 1) or np.any(counts > N):
        raise ValueError("t_out must hold at least one time per trajectory (t_out[0] is t0)")
    for i in range(n_traj):
        row = T[i, :counts[i]]
        if np.any(np.diff(row) <= 0) or not np.all(np.isfinite(row)):
            raise ValueError(f"t_out (trajectory {i}) must be finite and strictly "
                             "increasing; t_out[0] is t0")
    return T, counts


def integrate_ensemble(model, p, Y0, t_out, *, method="dop853", rtol=1e-10, atol=1e-12,
                       max_steps=10_000_000, compensated=False, project_codes=(),
                       project_values=None, project_every=1, section=None,
                       max_crossings=100_000, h_fixed=None, dense_output=True,
                       control=_CONTROL, generated=None, n_out=None, h_max=None,
                       workers=None, kernel=None) -> list[IntegrationResult]:
    """`integrate(model, p, Y0[i], t_out, **options)` for every row of Y0 in one compiled
    parallel call (module docstring); generated=None: integrate()'s default (a plain run:
    the small kernel per trajectory on threads; any other: the general field); kernel=
    "small": a run with a section too runs the small kernel with sections, per trajectory
    on threads (integrate's kernel="small"). Bad input
    raises ValueError before anything runs. wall_s of each result is its share of the call
    (the call's wall time / the number of trajectories)."""
    model = int(model)
    if not 0 <= model < len(L.STATE_DIM):
        raise ValueError(f"unknown model code {model!r}")
    n = L.STATE_DIM[model]
    Y0 = np.array(Y0, dtype=np.float64)
    if Y0.ndim == 1 and Y0.size == n:
        Y0 = Y0[None, :]
    if Y0.ndim != 2 or Y0.shape[1] != n:
        raise ValueError(f"Y0: one initial state of dimension {n} per row (model {model}); "
                         f"got shape {Y0.shape}")
    n_traj = Y0.shape[0]
    p = np.array(p, dtype=np.float64)
    if method in collocation.METHODS:
        raise ValueError(f"{method} is a fixed-step collocation method: the ensemble runs "
                         f"the explicit pairs {', '.join(tableaux.METHODS)}; use integrate() "
                         "per trajectory")
    if method not in tableaux.METHODS:
        raise ValueError(f"unknown method {method!r}; one of {', '.join(tableaux.METHODS)}")
    T, counts = _times(t_out, n_traj, n_out)
    codes = np.asarray(project_codes, dtype=np.int64).ravel()
    if project_every < 1:
        raise ValueError("project_every must be >= 1")
    if project_values is None:
        vals = np.array([initial_integrals(model, p, y0, codes) for y0 in Y0],
                        dtype=np.float64).reshape(n_traj, codes.size)
    else:
        v = np.array(project_values, dtype=np.float64)
        if v.ndim <= 1 and v.size == codes.size:
            vals = np.array(np.broadcast_to(v.ravel(), (n_traj, codes.size)))
        elif v.shape == (n_traj, codes.size):
            vals = np.ascontiguousarray(v)
        else:
            raise ValueError("project_values: one value per code, or one row of them per "
                             "trajectory")
    fixed = h_fixed is not None
    if fixed and not h_fixed > 0:
        raise ValueError("h_fixed must be positive")
    steps = _per_traj(max_steps, n_traj, "max_steps", np.int64)
    hmax = _per_traj(control.h_max if h_max is None else h_max, n_traj, "h_max", np.float64)
    if np.any(steps < 0) or np.any(~(hmax > 0)):
        raise ValueError("max_steps must be >= 0 and h_max > 0")
    atol_v = np.array(atol, dtype=np.float64).ravel()
    if atol_v.size == 1:
        atol_v = np.full(n, atol_v[0])
    elif atol_v.size != n:
        raise ValueError(f"atol: one number or one per state component ({n})")
    if not (np.isfinite(rtol) and rtol > 0) or not np.all(np.isfinite(atol_v)) or \
            np.any(atol_v < 0):
        raise ValueError("rtol must be a finite positive number and atol finite, >= 0")
    workers = default_workers() if workers is None else int(workers)
    if workers < 1:
        raise ValueError(f"workers = {workers}: must be >= 1")
    # integrate()'s rule (is_plain): a plain run with generated=None runs the small kernel,
    # any other the general field unless generated=True (then the generated twin); the
    # route depends on the request only, never on what is compiled
    if generated is None and kernel is None and not module_cache.disk_cache_ok():
        generated = False   # no kernel cache to write: the general kernels
    plain = generated is not False and is_plain(
        model, method, project=bool(codes.size), section=section, compensated=compensated,
        fixed=fixed, dense_output=dense_output)
    use_gen = bool(generated)
    small_sec = kernel == "small" and section is not None
    if kernel not in (None, "small"):
        raise ValueError(f"kernel = {kernel!r}: None or 'small'")
    if kernel == "small" and (generated is False or codes.size or not small_fits(
            model, method, fixed=fixed, dense_output=dense_output)):
        raise ValueError(f"{SMALL_REFUSED}; the ensemble's: a section, no projection")
    A, c, b, E, Pd, meth = method_arrays(method)
    if not dense_output:
        Pd = np.zeros((0, 1))
    sec = section if section is not None else Section(coef=(0.0,) * n, code=rk.SECTION_NONE)
    cross = (np.maximum(1, _per_traj(max_crossings, n_traj, "max_crossings", np.int64))
             if section is not None else np.ones(n_traj, dtype=np.int64))
    n_cross = int(cross.max(initial=1))
    # the options every trajectory shares, packed once (options.py); then the columns
    # that differ per trajectory: the budget, the crossings and h_max
    opts = RunOptions(method=method, rtol=rtol, atol=atol, control=control,
                      h_fixed=h_fixed, dense_output=dense_output, compensated=compensated,
                      section=section, projection=Projection(
                          tuple(codes.tolist()), every=int(project_every)) if codes.size
                      else None)
    ipack, fpack = opts.packed()
    IOPT = np.empty((n_traj, len(ipack)), dtype=np.int64)
    IOPT[:] = ipack
    IOPT[:, rk.I_MAX_STEPS] = steps
    IOPT[:, rk.I_MAX_CROSS] = cross
    FOPT = np.empty((n_traj, len(fpack)), dtype=np.float64)
    FOPT[:] = fpack
    FOPT[:, rk.F_HMAX] = hmax
    N = T.shape[1]
    Y = np.empty((n_traj, N, n))
    cross_t = np.empty((n_traj, n_cross))
    cross_y = np.empty((n_traj, n_cross, n))
    y_stop = np.empty((n_traj, n))
    stats = np.zeros((n_traj, 5), dtype=np.int64)
    status = np.zeros(n_traj, dtype=np.int64)
    t_stop = np.zeros(n_traj)
    if n_traj == 0:
        return []
    if plain or small_sec:
        return _small_ensemble(model, p, Y0, T, counts, steps, compensated, FOPT, atol_v,
                               method, workers, section if small_sec else None, cross)
    gen = use_gen and model in generate.GENERATED_MODELS
    w = min(workers, numba.config.NUMBA_NUM_THREADS)
    t0 = time.perf_counter()
    if w == 1 or n_traj == 1:
        # one thread: the serial kernel row by row, which is what the parallel loop runs
        # per trajectory (the same bits), without compiling that loop: the explorer's maps
        # run so (one trajectory slice per worker process, app/services/poincare_jobs.py)
        serial = (field_modules.generated_integrator(model, p)
                  if gen else loop_kernel).rk_integrate
        packed = sec.packed(n)
        for i in range(n_traj):
            status[i], t_stop[i] = serial(
                model, p, Y0[i], T[i, :counts[i]], A, c, b, E, Pd, meth, IOPT[i], FOPT[i],
                atol_v, codes, vals[i], packed, Y[i], cross_t[i], cross_y[i], y_stop[i],
                stats[i])
    else:
        kern = generated_ensemble(model, p).rk_ensemble if gen else kernels.rk_ensemble
        with _LAUNCH:
            _choose_layer()
            before = numba.get_num_threads()
            numba.set_num_threads(w)
            try:
                kern(model, p, Y0, T, counts, A, c, b, E, Pd, meth, IOPT, FOPT, atol_v,
                     codes, vals, sec.packed(n), Y, cross_t, cross_y, y_stop, stats, status,
                     t_stop, w, np.zeros(1, dtype=np.int64))
            finally:
                numba.set_num_threads(before)
    wall = (time.perf_counter() - t0) / n_traj
    out = []
    for i in range(n_traj):
        m, k, st = stats[i, rk.S_SAMPLES], stats[i, rk.S_CROSSINGS], int(status[i])
        message = status_message(st)
        if st != L.OK:
            message += f" (stopped at t = {t_stop[i]:.17g})"
        out.append(IntegrationResult(
            t=T[i, :m].copy(), y=Y[i, :m], status=st, message=message,
            t_stop=float(t_stop[i]), y_stop=y_stop[i], steps=int(stats[i, rk.S_ACCEPTED]),
            rejected=int(stats[i, rk.S_REJECTED]), rhs_calls=int(stats[i, rk.S_RHS]),
            wall_s=wall, method=method, crossings_t=cross_t[i, :k].copy(),
            crossings_y=cross_y[i, :k].copy()))
    return out
