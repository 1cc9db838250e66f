"""No request pays a compile inside its deadline (issue 19).

A route with a deadline first names the kernels its job needs (a key) and, the first time
this server sees that key while they may not be compiled, runs a prepare job in the pool
WITHOUT a deadline: the job's own kernels on a tiny run (app.services.jobs.prepare_*,
app.services.poincare_jobs.prepare), which compiles them into the on-disk caches or loads
them. Then the request's job starts and its deadline counts. Keys:

  ("small", model, structure, method)   a plain run's small kernel (solvers/kernels/small.py)
  ("general", model, method, project, fixed)   the general rk.py kernel of a simulation
  ("map", case, method)                 a Poincare map's compiled ensemble (sections)
  ("scene", case)                       a scene's run (the scene model, general field)
  ("scene-check", scene id)             a teaching scene's checks

What the warm-up compiles (solvers/warmup.py: the general kernels, the ensembles on the
general field, the small dop853 kernels of every case's example structure) needs no
prepare once it is done, or when the caches are known to be warm (Settings.kernels_warm:
the tests, after `./dev test`'s warm-up). Anything else is prepared once per server:
cheap when it is already in a cache (a tiny run in a worker, milliseconds).
"""

from __future__ import annotations

import time

import anyio
import numpy as np

from app.services.kernel_warmup import KernelWarmup

_PREPARED: set = set()     # keys prepared by this server process (their kernels are cached)
_WARMED: set = set()
_INFLIGHT: dict = {}       # key -> Event: a second request of a key waits for the first


def structure(model) -> tuple:
    """(model code, nonzero parameter slots): solvers.kernels.generate.structure without
    importing numba into the server's process."""
    return (model.model, tuple(np.flatnonzero(np.asarray(model.p) != 0.0).tolist()))


def _warmed() -> set:
    """("small", model, structure, method) of the small kernels the warm-up compiles."""
    if not _WARMED:
        from solvers.models.cases import build
        from solvers.warmup import WARM_SMALL, _targets

        _WARMED.update(("small", *structure(build(cid, params)), method)
                       for cid, params in _targets() for method in WARM_SMALL)
    return _WARMED


def simulate_keys(resolved: dict) -> list[tuple]:
    """The kernels a simulate request runs (integrator.is_plain decides small or general;
    method "auto" may take dop853 or vern9)."""
    from solvers.integrate.integrator import SMALL_METHODS

    model = resolved["_model"]
    method, project = resolved["method"], bool(resolved["project"])
    fixed = resolved.get("step") is not None
    methods = SMALL_METHODS if method == "auto" else (method,)
    plain = resolved.get("field", "auto") != "general" and not project and not fixed
    keys = []
    for m in methods:
        if plain and m in SMALL_METHODS and _has_generated(model.model):
            keys.append(("small", *structure(model), m))
        else:
            keys.append(("general", model.model, m, project, fixed))
    return keys


def _has_generated(model_code: int) -> bool:
    from solvers.kernels import generate

    return model_code in generate.GENERATED_MODELS


def needed(kernels: KernelWarmup, assumed_warm: bool, keys: list[tuple]) -> bool:
    """Whether a prepare job must run before a job needing `keys`."""
    todo = [k for k in keys if k not in _PREPARED]
    if not todo:
        return False
    if kernels.state == "done" or (kernels.state == "off" and assumed_warm):
        # the warm-up compiled everything but the small kernels of other structures
        return any(k[0] == "small" and k not in _warmed() for k in todo)
    return True


async def prepare(pool, kernels: KernelWarmup, assumed_warm: bool, keys: list[tuple],
                  fn, *args) -> float | None:
    """Run fn(*args) in the pool without a deadline when `needed`; the seconds it took
    (None when nothing was prepared). A concurrent request of the same keys waits for
    the first one's job instead of compiling the same kernels again. The routes do not
    cancel it when their client leaves: the compile serves the next request."""
    key = tuple(keys)
    while (other := _INFLIGHT.get(key)) is not None:
        await other.wait()
    if not needed(kernels, assumed_warm, keys):
        return None
    _INFLIGHT[key] = done = anyio.Event()
    t0 = time.perf_counter()
    try:
        await pool.run(fn, *args)          # no deadline: this is the compile
    finally:
        del _INFLIGHT[key]
        done.set()
    seconds = time.perf_counter() - t0
    _PREPARED.update(keys)
    kernels.prepared.append({"keys": [list(map(str, k)) for k in keys],
                             "seconds": round(seconds, 2)})
    return seconds
