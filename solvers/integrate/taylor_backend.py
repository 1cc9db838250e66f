"""`method="taylor"`: heyoka's adaptive Taylor integrator as a runtime backend of simulate().

The system is the case's lean generated field (solvers/kernels/generate.py,
`heyoka_field.heyoka_system(fold=False)`): the same sympy equations as the generated numba field
((1.1)-(1.3), (3.16)-(3.17)), zero terms dropped, the nonzero parameters heyoka runtime
parameters `par[slot]`, so one compiled integrator serves every parameter value of a case
*structure*. heyoka compiles it with LLVM (seconds a case, `bench/taylor_compile.py`); heyoka
itself keeps nothing across processes, so the compiled integrator is kept process-wide per
(structure, precision, tol) in a small LRU (`MAX_CACHED`) and on disk (`disk_dir()`: the
integrator pickled by heyoka's own serialization, which carries the compiled object code,
loaded in a small fraction of a compile's time): a run pays the compile once per machine, and the
explorer's prepare job (app/services/kernel_prepare.py) compiles in any worker what the
request's worker then loads (no compile inside a request's deadline).

Tolerance: heyoka takes one `tol`; it picks the Taylor order ~ -ln(tol)/2 and a step
that keeps the last terms of the series below tol * max(1, |y|_inf) (Jorba & Zou): an
absolute error for states of norm below 1, relative above. So tol = rtol, and atol has no
separate role: the effective absolute tolerance is rtol (`stats["atol_effective"]`).
The tol is compiled into the integrator (it fixes the order), so it is part of the key;
to keep the number of compiles small it is snapped down to a quarter decade
(`snap_tol`: 1e-10 stays 1e-10, 3e-10 becomes 1.78e-10), never looser than asked.

LLVM code: unrolled for double (the fastest steps, several times compact mode's, for a
compile of seconds); compact mode for long double and quad, where unrolled code compiles
far longer and runs no faster (bench/taylor_compile.py; docs/performance.md).

Precision: "double" (float64), "long double" (x87 80-bit where numpy's longdouble has a
64-bit mantissa) and "quad" (real128, in software, where heyoka was built with it);
`precisions()` lists what this build offers. `choose_precision` picks the cheapest one
able to deliver rtol over the run (rule in its docstring). The states come back as float64.

Singularities are heyoka terminal events (scaled, see EVENT_SCALE) on the generated
field's own checks: det(E - k J)
reaching 0 (the body stops fitting the sphere, (1.3); only inside a cavity, k > 0) and
g1^2 + g2^2 reaching FLAT_DISK^2 (the disk falls flat); heyoka's non-finite outcome is the
third (det I_Q cannot reach 0: I_Q >= I). Each stops the run with the kernels' status
code and message (layout.STATUS_TEXT): status "singular", the samples before the stop,
never NaN. The step budget is heyoka's max_steps (status "budget"). The request deadline
is the worker pool's (the worker running the job is killed, as for every method);
`run(..., wall_limit=s)` also stops it from a step callback, for callers outside the pool.

heyoka is the optional extra `taylor` (`pip install rolling-hierarchy[taylor]`, included
in `dev`); without it `method="taylor"` is an InputError saying so.
"""

from __future__ import annotations

import contextlib
import hashlib
import math
import os
import pickle
import threading
import time
from collections import OrderedDict
from dataclasses import dataclass
from functools import lru_cache
from pathlib import Path

import llvmlite.binding as ll
import numpy as np

from solvers.errors import InputError
from solvers.integrate.result import status_message
from solvers.kernels import layout as L
from solvers.kernels import rk
from solvers.kernels.generate import GENERATED_MODELS, structure
from solvers.kernels.heyoka_field import heyoka_system
from solvers.kernels.module_cache import cache_dir, sources_hash
from solvers.kernels.support import FLAT_DISK

MISSING = "method 'taylor' needs heyoka: pip install rolling-hierarchy[taylor]"
PRECISIONS = ("double", "long double", "quad")
EPS = {"double": float(np.finfo(np.float64).eps), "long double": 2.0 ** -63,
       "quad": 2.0 ** -112}
MAX_CACHED = 8
# heyoka's step-size control reads the event functions' Taylor coefficients with the
# state's, on purpose (bluescarni/heyoka PR #124, "Don't ignore the event equations when
# determining the timestep"). An event function much larger than the state (a t_event on
# v0 - 1e10; det I_Q, of size ten) takes over the step-size control: far fewer or other steps
# than the state alone asks for, and a larger error or a wrong state. Scaled by 1e-30 the
# events keep their zeros and leave the control to the state alone (the same steps as a
# run without events).
EVENT_SCALE = 1e-30
# the precision rule (choose_precision): a tol below FLOOR * eps * sqrt(max(1, t_end)) asks
# for less than the round-off a run of that length accumulates in that precision
FLOOR = 1.0


def heyoka():
    """The heyoka module, or an InputError naming the extra that installs it."""
    try:
        import heyoka as hy  # lazy: heyoka, an optional extra slow to import, only when it runs
    except ImportError as e:
        raise InputError(MISSING) from e
    return hy


def precisions() -> tuple[str, ...]:
    """The precisions this platform and heyoka build offer (double always)."""
    hy = heyoka()
    out = ["double"]
    if np.finfo(np.longdouble).nmant >= 63:
        out.append("long double")
    if getattr(hy, "_with_real128", False):
        out.append("quad")
    return tuple(out)


def check_precision(precision: str | None) -> None:
    if precision is not None and precision not in PRECISIONS:
        raise InputError(f"precision = {precision!r}: choose one of {', '.join(PRECISIONS)}")
    if precision is not None and precision not in precisions():
        raise InputError(f"precision = {precision!r}: this platform's heyoka offers "
                         f"{', '.join(precisions())}")


def check_taylor_options(method: str, precision: str | None, project: bool, step) -> None:
    """InputError for what the Taylor backend does not take (checked before any run)."""
    if precision is not None and method != "taylor":
        raise InputError(f"precision = {precision!r}: only method 'taylor' runs in another "
                         f"precision; {method} runs in double")
    if method != "taylor":
        return
    heyoka()
    check_precision(precision)
    if project:
        raise InputError("project = true: method 'taylor' does not project (its integrals "
                         "hold to about rtol without it)")
    if step is not None:
        raise InputError(f"step = {step!r}: method 'taylor' chooses its own steps from rtol")


def floor(precision: str, t_end: float) -> float:
    """The smallest rtol a run of length t_end can deliver in `precision` (module doc)."""
    return FLOOR * EPS[precision] * float(np.sqrt(max(1.0, t_end)))


def choose_precision(rtol: float, t_end: float) -> str:
    """The cheapest precision whose floor(precision, t_end) <= rtol, else the widest.

    Round-off of a run grows like a random walk over its steps, about sqrt(t_end) steps
    for these O(1)-time-scale systems. Calibrated on bench/results/work_precision_taylor.txt
    (T = 1000, double): below tol ~ eps sqrt(T) = 7e-15 a tighter tol stops buying accuracy
    in double (Chaplygin ball: tol 1e-14 -> error 2.3e-13, 1e-16 -> 5.1e-14; disk: 1e-14
    -> 5.9e-13, 1e-16 -> 1.6e-12), while long double keeps going (1e-16 -> 2.7e-15 and
    4.1e-16), at 10-30 times the cost: so double down to 7e-15 at T = 1000 (2.2e-16 at
    T <= 1), long double below, quad below its own floor."""
    offered = precisions()
    for prec in offered:
        if floor(prec, t_end) <= rtol:
            return prec
    return offered[-1]


def _fp(hy, precision: str):
    return {"double": float, "long double": np.longdouble}.get(precision) or hy.real128


def _cast(fp, values) -> np.ndarray:
    if fp is float or fp is np.longdouble:
        return np.asarray(values, dtype=fp)
    return np.array([fp(float(v)) for v in np.ravel(values)], dtype=fp)


@dataclass
class Compiled:
    """One compiled integrator: reused under its lock (it carries the state)."""

    ta: object
    fp: object
    n_par: int
    events: tuple[int, ...]      # layout status code of each terminal event
    compile_s: float
    lock: threading.Lock
    load_s: float = 0.0          # read from the disk cache in this many seconds (0: compiled)


_cache: OrderedDict = OrderedDict()
_cache_lock = threading.Lock()
COMPILES = [0]      # compiles done in this process (tests count them)
LOADS = [0]         # integrators loaded from the disk cache in this process


def snap_tol(rtol: float) -> float:
    """The largest 10^(j/4) <= rtol (j integer): the tol the integrator is compiled for."""
    j = math.floor(4.0 * math.log10(rtol) + 1e-9)
    return 10.0 ** (j / 4.0)


def cache_key(model: int, p, precision: str, tol: float) -> tuple:
    # the sign of k decides whether the fit event exists (_compile)
    return (structure(model, p, fold=False), float(np.asarray(p)[L.CURV]) > 0, precision,
            float(tol))


def disk_dir() -> Path:
    """Where compiled integrators are kept between processes: beside the generated numba
    kernels (ROLLING_KERNEL_CACHE, else ~/.cache/rolling-hierarchy/kernels), in taylor/."""
    d = cache_dir() / "taylor"
    with contextlib.suppress(OSError):    # not writable: compiled integrators stay in memory
        d.mkdir(parents=True, exist_ok=True)
    return d


@lru_cache(maxsize=1)
def _build_stamp() -> str:
    """What a stored integrator depends on besides its key: the sources of the expressions
    (solvers/kernels, via the generator's stamp) and of this module (the events), heyoka's
    and numpy's versions, and the host CPU (LLVM compiles for it)."""
    import heyoka as hy  # lazy: heyoka, an optional extra slow to import, only when it runs

    h = hashlib.sha256()
    for part in (sources_hash(), Path(__file__).read_bytes(), hy.__version__,
                 np.__version__, ll.get_host_cpu_name(), ll.get_host_cpu_features().flatten()):
        h.update(part if isinstance(part, bytes) else str(part).encode())
    return h.hexdigest()[:16]


def _disk_path(key: tuple) -> Path:
    name = hashlib.sha256(repr((key, _build_stamp())).encode()).hexdigest()[:24]
    return disk_dir() / f"{name}.pkl"


def ready(model: int, p, precision: str, tol: float) -> bool:
    """Whether the integrator is compiled: in this process or in the disk cache."""
    key = cache_key(model, p, precision, tol)
    with _cache_lock:
        if key in _cache:
            return True
    return _disk_path(key).is_file()


def _load(key: tuple) -> Compiled | None:
    """The integrator stored by an earlier process, or None (absent, or unreadable: a
    partial or foreign file is recompiled and replaced)."""
    path = _disk_path(key)
    try:
        t0 = time.perf_counter()
        with open(path, "rb") as f:
            ta, n_par, events, compile_s = pickle.load(f)
        load_s = time.perf_counter() - t0
    except FileNotFoundError:
        return None
    except Exception:       # any damage means: compile again
        return None
    LOADS[0] += 1
    return Compiled(ta, _fp(heyoka(), key[2]), n_par,
                    tuple(events), compile_s, threading.Lock(), load_s)


def _store(key: tuple, entry: Compiled) -> None:
    """Write the integrator for later processes (atomically: a reader never sees half a
    file). A cache that cannot be written only costs the next process a compile."""
    path = _disk_path(key)
    tmp = path.with_name(f"{path.name}.{os.getpid()}.tmp")
    try:
        with open(tmp, "wb") as f:
            pickle.dump((entry.ta, entry.n_par, entry.events, entry.compile_s), f,
                        protocol=pickle.HIGHEST_PROTOCOL)
        os.replace(tmp, path)
    except OSError:
        with contextlib.suppress(OSError):
            tmp.unlink(missing_ok=True)


def compiled(model: int, p, precision: str, tol: float) -> tuple[Compiled, str | None]:
    """(the compiled integrator of the case structure, where it came from: "memory" (this
    process), "disk" (an earlier process compiled it) or None (compiled now))."""
    key = cache_key(model, p, precision, tol)
    with _cache_lock:
        if key in _cache:
            _cache.move_to_end(key)
            return _cache[key], "memory"
    entry, source = _load(key), "disk"
    if entry is None:
        entry, source = _compile(model, p, precision, tol), None
        _store(key, entry)
    with _cache_lock:
        _cache[key] = entry
        _cache.move_to_end(key)
        while len(_cache) > MAX_CACHED:
            _cache.popitem(last=False)
    return entry, source


def clear_cache(disk: bool = False) -> None:
    """Forget the integrators of this process (disk: and the stored ones)."""
    with _cache_lock:
        _cache.clear()
    if disk:
        for f in disk_dir().glob("*.pkl"):
            f.unlink(missing_ok=True)


def _compile(model: int, p, precision: str, tol: float) -> Compiled:
    hy = heyoka()
    fp = _fp(hy, precision)
    hvars, rhs, pars, checks = heyoka_system(model, p, fold=False, with_checks=True)
    neg = hy.event_direction.negative
    exprs, codes = [], []
    if "edge" in checks:   # g1^2 + g2^2 reaches FLAT_DISK^2: the disk lies flat (2.15)
        exprs.append(hvars[3] * hvars[3] + hvars[4] * hvars[4] - FLAT_DISK ** 2)
        codes.append(L.SING_EDGE)
    # det(E - k J) reaches 0 (1.3): only inside a cavity (k > 0); outside a ball (k < 0)
    # E - k J >= E, as J = Hess h is positive semidefinite for a convex body
    # A ball (support c |gamma| + (a, gamma)) has the constant radius of curvature c, and a
    # ball that does not fit is refused before any run: no event (it doubled the cost of
    # a step of the Chaplygin ball in a cavity)
    pv = np.asarray(p, dtype=float)
    ball = not any(pv[s] != 0.0 for s in (L.B11, L.B22, L.B33, L.B12, L.B13, L.B23, L.DISK_D))
    if "fit" in checks and pv[L.CURV] > 0 and not ball:
        exprs.append(checks["fit"])
        codes.append(L.SING_FIT)
    # det I_Q needs no event: I_Q = I + m (|r|^2 E - r r^T) >= I, positive definite for the
    # positive moments the cases accept (1.6); every event costs time in every step
    events = [hy.t_event(EVENT_SCALE * e, direction=neg, fp_type=fp) for e in exprs]
    t0 = time.perf_counter()
    ta = hy.taylor_adaptive(list(zip(hvars, rhs, strict=True)), _cast(fp, [0.0] * len(hvars)),
                            tol=fp(tol), fp_type=fp, pars=_cast(fp, pars), t_events=events,
                            compact_mode=precision != "double")
    COMPILES[0] += 1
    return Compiled(ta, fp, len(pars), tuple(codes), time.perf_counter() - t0,
                    threading.Lock())


@dataclass
class TaylorRun:
    """What simulate() needs of a run (the fields of integrator.IntegrationResult)."""

    t: np.ndarray
    y: np.ndarray
    status: int
    message: str
    t_stop: float
    steps: int
    rejected: int
    rhs_calls: int
    wall_s: float
    method: str
    extra: dict

    @property
    def success(self) -> bool:
        return self.status == L.OK

    @property
    def budget_exhausted(self) -> bool:
        return self.status == rk.MAX_STEPS


def run(model: int, p, y0, t_out, *, rtol: float, precision: str | None = None,
        max_steps: int = 50_000_000, wall_limit: float | None = None) -> TaylorRun:
    """Integrate from (t_out[0], y0), states at t_out (float64); see the module doc."""
    hy = heyoka()
    if model not in GENERATED_MODELS:
        raise InputError(f"method 'taylor' runs the generated fields of models "
                         f"{GENERATED_MODELS}; model {model} has none")
    t_out = np.asarray(t_out, dtype=float)
    prec = precision or choose_precision(rtol, float(t_out[-1] - t_out[0]))
    check_precision(prec)
    tol = snap_tol(rtol)
    entry, source = compiled(model, p, prec, tol)
    fp = entry.fp
    p = np.asarray(p, dtype=float)
    cb = None
    if wall_limit is not None:
        stop_at = time.monotonic() + wall_limit

        def cb(ta):
            return time.monotonic() < stop_at
    with entry.lock:
        ta = entry.ta
        ta.time = fp(float(t_out[0]))
        ta.state[:] = _cast(fp, y0)
        ta.pars[:] = _cast(fp, p[:entry.n_par])
        if entry.events:
            ta.reset_cooldowns()
        t0 = time.perf_counter()
        res = ta.propagate_grid(_cast(fp, t_out), max_steps=int(max_steps), callback=cb)
        wall = time.perf_counter() - t0
        t_stop = float(ta.time)
    outcome, nsteps, Y = res[0], int(res[3]), np.asarray(res[-1], dtype=float)
    code = int(outcome.value)
    if outcome == hy.taylor_outcome.time_limit:
        status = L.OK
    elif outcome == hy.taylor_outcome.step_limit:
        status = rk.MAX_STEPS
    elif outcome == hy.taylor_outcome.err_nf_state:
        status = L.SING_NONFINITE
    elif outcome == hy.taylor_outcome.cb_stop:
        status = rk.MAX_STEPS
    elif code < 0:     # terminal event number -code - 1
        status = entry.events[-code - 1]
    else:
        status = L.SING_NONFINITE
    m = len(Y)
    while m and not np.all(np.isfinite(Y[m - 1])):
        m -= 1
    if status == L.OK and m < len(t_out):
        status = L.SING_NONFINITE
    message = "" if status == L.OK else status_message(status)
    if outcome == hy.taylor_outcome.cb_stop:
        message = f"the wall-time limit of {wall_limit:g} s ran out before the last output time"
    if status != L.OK:
        message += f" (stopped at t = {t_stop:.17g})"
    # compiled: whether this run compiled its integrator (compile_s); else it came from
    # this process ("memory") or the disk cache ("disk", read in load_s)
    extra = {"precision": prec, "taylor_order": int(ta.order), "compiled": source is None,
             "compile_s": entry.compile_s if source is None else 0.0,
             "integrator_cache": source,
             "load_s": round(entry.load_s, 4) if source == "disk" else 0.0, "tol": tol,
             "atol_effective": tol}
    # one Taylor jet (the series of every state variable to the order) per step
    return TaylorRun(t=t_out[:m].copy(), y=Y[:m], status=int(status), message=message,
                     t_stop=t_stop, steps=nsteps, rejected=0, rhs_calls=nsteps, wall_s=wall,
                     method="taylor", extra=extra)
