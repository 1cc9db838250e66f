"""No request pays a compile inside its deadline.

A route with a deadline first names the kernels its job needs (a key) and, the first time
this server sees that key while they may not be compiled, runs a prepare job in the pool
WITHOUT a deadline: the job's own kernels on a tiny run (app.services.jobs.prepare_*,
app.services.poincare_jobs.prepare), which compiles them into the on-disk caches or loads
them. Then the request's job starts and its deadline counts. A simulate request's keys and
their compile are solvers/compile_state.py's (plan, compile: "small", "generated",
"general", "taylor"); the routes add:

  ("map", case, method)                 a Poincare map's general kernel (sections)
  ("small-sections", case, params, method)   a large map's small kernel with sections
                                        (solvers/maps/poincare.py map_kernel: compiled on
                                        first use, never by the warm-up)
  ("scene", case)                       a scene's run (the scene model, general field)
  ("scene-check", scene id)             a teaching scene's checks

What the warm-up compiles (solvers/warmup.py: the general kernels, a scene and a tiny
Poincare map per model, the ensembles on the general field, the small dop853 kernels of
every case's example structure; tests/test_warm_covers_requests.py checks that the
explorer's default clicks need nothing else) needs no
prepare once it is done, or when the caches are known to be warm (Settings.kernels_warm:
the tests, after `./dev test`'s warm-up). Anything else is prepared once per server:
cheap when it is already in a cache (a tiny run in a worker, milliseconds). The warm-up
compiles no Taylor integrator, so those are always prepared once per server: heyoka keeps
compiled code in the memory of one process only, and the prepare job may run in another
worker than the request; taylor_backend's disk cache carries it across (the request's
worker loads it in a small fraction of the compile's time: bench/taylor_compile.py).
"""

from __future__ import annotations

import time

import anyio
import numpy as np

from app.services.kernel_warmup import KernelWarmup
from solvers.models.cases import build

_PREPARED: set = set()     # keys prepared by this server process (their kernels are cached)
_WARMED: set = set()
_INFLIGHT: dict = {}       # key -> Event: a second request of a key waits for the first


def structure(model) -> tuple:
    """(model code, nonzero parameter slots) of a built model: what its small kernel is
    compiled for (solvers.kernels.generate.structure without the folded values)."""
    return (model.model, tuple(np.flatnonzero(np.asarray(model.p) != 0.0).tolist()))


def _warmed() -> set:
    """("small", model, structure, method) of the small kernels the warm-up compiles."""
    if not _WARMED:
        # lazy: the warm-up's list of targets (solvers.warmup), not at the server's start
        from solvers.warmup import WARM_SMALL, warm_targets

        _WARMED.update(("small", *structure(build(cid, params)), method)
                       for cid, params in warm_targets() for method in WARM_SMALL)
    return _WARMED


def simulate_keys(resolved: dict) -> list[tuple]:
    """The kernels a simulate request runs: solvers/compile_state.py plan(), from the
    request alone. Not on the event loop: planning "auto" reads the measured front and
    imports heyoka."""
    # lazy: solvers.compile_state (with auto's measured front and the Taylor backend), not
    # at the server's start
    from solvers import compile_state

    return compile_state.plan(resolved)


def map_key(job: dict) -> tuple:
    """The key of a Poincare map's job (app/api/routes/poincare.py resolve)."""
    spec = job["spec"]
    if spec["kernel"] == "small":
        return ("small-sections", job["case"], tuple(sorted(job["params"].items())),
                spec["method"])
    return ("map", job["case"], spec["method"])


def needed(kernels: KernelWarmup, assumed_warm: bool, keys: list[tuple]) -> bool:
    """Whether a prepare job must run before a job needing `keys`."""
    todo = [k for k in keys if k not in _PREPARED]
    if not todo:
        return False
    if kernels.state == "done" or (kernels.state == "off" and assumed_warm):
        # the warm-up compiled everything but the small kernels of other structures, the
        # small kernels with sections (large maps) and the Taylor integrators: maps,
        # scenes and their checks included
        # (tests/test_warm_covers_requests.py: their default requests enter no numba
        # specialization the warm-up's tasks do not)
        return any((k[0] == "small" and k not in _warmed())
                   or k[0] in ("taylor", "small-sections", "generated") for k in todo)
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
