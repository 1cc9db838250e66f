"""Batches of initial conditions (Poincare maps, parameter sweeps) on every core.

`integrate_batch` runs the explicit Runge-Kutta methods as one compiled parallel loop over
the trajectories (solvers/integrate/ensemble.py: one validation, one call, no Python per
trajectory); the Gauss collocation methods, which the loop does not hold, on a pool of
threads, one `integrate` per thread (the kernels are `nogil`, solvers/kernels/jit.py, so
the threads run truly in parallel). Either way each item is
`solvers.integrate.integrator.integrate` with its own initial state (same model, parameters
and options), and the results come back in the order of the inputs.

    res = integrate_batch(model.model, model.p, Y0, t_out, workers=2, method="dop853",
                          section=Section(coef=(0, 0, 0, 0, 0, 1)), max_crossings=200)
"""

from __future__ import annotations

from concurrent.futures import ThreadPoolExecutor

import numpy as np

from solvers.integrate import collocation
from solvers.integrate.ensemble import default_workers, integrate_ensemble
from solvers.integrate.integrator import IntegrationResult, integrate

__all__ = ["default_workers", "integrate_batch", "integrate_threads"]


def integrate_batch(model: int, p, Y0, t_out, *, workers: int | None = None,
                    **options) -> list[IntegrationResult]:
    """`integrate(model, p, y0, t_out, **options)` for every row y0 of Y0, on `workers`
    threads (default: one per core available to this process)."""
    if options.get("method", "dop853") in collocation.METHODS:
        return integrate_threads(model, p, Y0, t_out, workers=workers, **options)
    return integrate_ensemble(model, p, Y0, t_out, workers=workers, **options)


def integrate_threads(model: int, p, Y0, t_out, *, workers: int | None = None,
                      **options) -> list[IntegrationResult]:
    """The same on a Python thread pool, one `integrate` call per trajectory (the Gauss
    methods' path, and the ensemble's competitor in bench/ensemble.py)."""
    Y0 = np.atleast_2d(np.asarray(Y0, dtype=np.float64))
    workers = default_workers() if workers is None else max(1, int(workers))
    p = np.array(p, dtype=np.float64)
    t_out = np.array(t_out, dtype=np.float64)

    def one(y0):
        return integrate(model, p, y0, t_out, **options)

    if workers == 1 or len(Y0) == 1:
        return [one(y0) for y0 in Y0]
    with ThreadPoolExecutor(max_workers=workers) as pool:
        return list(pool.map(one, Y0))
