"""Worker-process side of POST /api/poincare: one trajectory of the map per job (so that
the route can report progress and both workers share the trajectories)."""

from __future__ import annotations


def trajectory(job: dict, y0: list[float]) -> dict:
    import numpy as np

    from solvers.maps.poincare import MapSpec, integral_spread, map_model, trace_checked

    model = map_model(job["case"], job["params"], allow_any_inertia=job["allow_any_inertia"])
    tr = trace_checked(model, np.asarray(y0, dtype=float), MapSpec(**job["spec"]))
    return {**tr.to_json(), "spread": integral_spread(model, tr)}
