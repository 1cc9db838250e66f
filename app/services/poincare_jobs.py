"""Worker-process side of POST /api/poincare: a slice of the map's trajectories per job,
run as one compiled ensemble per round (solvers.maps.poincare.trace_checked_all) on one
thread: the route runs `workers` such jobs at once, one per worker process, so the
processes already fill the cores."""

from __future__ import annotations


def trajectories(job: dict, starts: list[list[float]]) -> list[dict]:
    import numpy as np

    from solvers.maps.poincare import MapSpec, integral_spread, map_model, trace_checked_all

    model = map_model(job["case"], job["params"], allow_any_inertia=job["allow_any_inertia"])
    trs = trace_checked_all(model, [np.asarray(y0, dtype=float) for y0 in starts],
                            MapSpec(**job["spec"]), workers=1)
    return [{**tr.to_json(), "spread": integral_spread(model, tr)} for tr in trs]


def trajectory(job: dict, y0: list[float]) -> dict:
    return trajectories(job, [y0])[0]
