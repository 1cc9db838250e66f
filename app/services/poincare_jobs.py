"""Worker-process side of POST /api/poincare: a slice of the map's trajectories per job,
run as one compiled ensemble per round (solvers.maps.poincare.trace_checked_all) on one
thread: the route runs `workers` such jobs at once, one per worker process, so the
processes already fill the cores."""

from __future__ import annotations

import time

import numpy as np


def trajectories(job: dict, starts: list[list[float]]) -> list[dict]:
    # lazy: the Poincare maps (solvers.maps), not at the server's start, which imports this
    # module for the jobs' names
    from solvers.maps.poincare import MapSpec, integral_spread, map_model, trace_checked_all

    model = map_model(job["case"], job["params"], allow_any_inertia=job["allow_any_inertia"])
    trs = trace_checked_all(model, [np.asarray(y0, dtype=float) for y0 in starts],
                            MapSpec(**job["spec"]), workers=1)
    return [{**tr.to_json(), "spread": integral_spread(model, tr)} for tr in trs]


def trajectory(job: dict, y0: list[float]) -> dict:
    return trajectories(job, [y0])[0]


def seconds_per_point(job: dict, y0: list[float], points: int) -> float:
    """The estimate before a map starts: the wall time of one crossing of this start,
    timed on `points` crossings after a first short run that pays the imports and the
    kernel compilation (which a cold worker would otherwise put into the estimate)."""
    warm = {**job, "spec": {**job["spec"], "points": 1}}
    trajectories(warm, [y0])
    timed = {**job, "spec": {**job["spec"], "points": points}}
    t0 = time.perf_counter()
    trajectories(timed, [y0])
    return (time.perf_counter() - t0) / points


def prepare(job: dict, y0: list[float]) -> int:
    """Compile (or load) a map's kernels without a deadline before the map's jobs run
    (app/services/kernel_prepare.py): one crossing of the first start, its step budget
    cut to a few hundred steps (the compile is the cost, not the run)."""
    tiny = {**job, "spec": {**job["spec"], "points": 1,
                            "max_steps": min(job["spec"]["max_steps"], 500)}}
    try:
        trajectories(tiny, [y0])
    except Exception:   # the map itself reports it
        return 0
    return 1
