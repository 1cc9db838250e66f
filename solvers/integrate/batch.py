"""Batches of initial conditions (Poincare maps, parameter sweeps) on every core.

The compiled kernels are `nogil` (solvers/kernels/jit.py), so a pool of threads runs one
`rk_integrate` per thread truly in parallel, with no process start-up, no pickling and
no second copy of the numba cache in memory. Each item is one call of
`solvers.integrate.integrator.integrate` with its own initial state (same model, parameters and
options); the results come back in the order of the inputs.

    res = integrate_batch(model.model, model.p, Y0, t_out, workers=2, method="dop853",
                          section=Section(coef=(0, 0, 0, 0, 0, 1)), max_crossings=200)
"""

from __future__ import annotations

import os
from concurrent.futures import ThreadPoolExecutor

import numpy as np

from solvers.integrate.integrator import IntegrationResult, integrate


def default_workers() -> int:
    return max(1, len(os.sched_getaffinity(0)) if hasattr(os, "sched_getaffinity")
               else (os.cpu_count() or 1))


def integrate_batch(model: int, p, Y0, t_out, *, workers: int | None = None,
                    **options) -> list[IntegrationResult]:
    """`integrate(model, p, y0, t_out, **options)` for every row y0 of Y0, on `workers`
    threads (default: one per core available to this process)."""
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
