"""Batches of initial conditions on both cores: solvers/integrate/batch.py (the compiled
ensemble, solvers/integrate/ensemble.py, on numba's threads) from 1 to 2 workers, for a
Poincare-map batch and a sweep (bench/ensemble.py sets it against a Python thread pool).

    .venv/bin/python bench/batch_scaling.py      (or: rolling bench batch)

Batch 1: 32 initial states of the Chaplygin ball on a sphere, 300 crossings of g3 = 0
each or up to t = 5000 (a Poincare map); batch 2: 32 states of the Chaplygin ball on the plane over
T = 2000 with 201 samples (a sweep). Each batch runs with 1 worker, then 2, alternately,
best of 3; the results must be bit-identical. The machine is shared: the load average
is printed beside the times. Writes bench/results/batch_scaling.txt.
"""

from __future__ import annotations

import os
import sys
import time
from pathlib import Path

import numpy as np

from solvers.integrate.batch import integrate_batch
from solvers.integrate.integrator import Section
from solvers.models.cases import build, registry

OUT = Path(__file__).with_name("results") / "batch_scaling.txt"
N = 32


def states(case_id, n, seed):
    c = registry()[case_id]
    rng = np.random.default_rng(seed)
    base = np.array(c.state)
    out = []
    for _ in range(n):
        y = base.copy()
        y[:3] += 0.2 * rng.standard_normal(3)
        g = y[3:] + 0.2 * rng.standard_normal(3)
        y[3:] = g / np.linalg.norm(g)
        out.append(y)
    return np.array(out)


def timed(fn, workers):
    t0 = time.perf_counter()
    res = fn(workers)
    return time.perf_counter() - t0, res


def main():
    lines = []

    def say(s=""):
        print(s, flush=True)
        lines.append(s)

    sphere = build("sphere/chaplygin-ball", registry()["sphere/chaplygin-ball"].example)
    plane = build("plane/chaplygin-ball", registry()["plane/chaplygin-ball"].example)
    Ys, Yp = states("sphere/chaplygin-ball", N, 1), states("plane/chaplygin-ball", N, 2)
    sec = Section(coef=(0, 0, 0, 0, 0, 1.0))
    batches = {
        f"Poincare map: {N} states x up to 300 crossings (sphere/chaplygin-ball)":
            lambda w: integrate_batch(sphere.model, sphere.p, Ys, [0.0, 5000.0], workers=w,
                                      section=sec, max_crossings=300),
        f"sweep: {N} states, T = 2000, 201 samples (plane/chaplygin-ball)":
            lambda w: integrate_batch(plane.model, plane.p, Yp, np.linspace(0, 2000, 201),
                                      workers=w),
    }
    say(f"cores available: {len(os.sched_getaffinity(0))}; the compiled ensemble on numba "
        "threads")
    for name, fn in batches.items():
        fn(1)                               # warm
        best = {1: np.inf, 2: np.inf}
        res = {}
        for _ in range(3):
            for w in (1, 2):
                t, r = timed(fn, w)
                best[w] = min(best[w], t)
                res[w] = r
        same = all(np.array_equal(a.y, b.y) and np.array_equal(a.crossings_y, b.crossings_y)
                   for a, b in zip(res[1], res[2], strict=True))
        load = os.getloadavg()[0]
        say(f"{name}\n  1 worker {best[1]:.3f} s   2 workers {best[2]:.3f} s   speed-up "
            f"{best[1] / best[2]:.2f}x (efficiency {best[1] / best[2] / 2:.0%})   identical "
            f"results: {same}   load average {load:.2f}")
    OUT.parent.mkdir(exist_ok=True)
    OUT.write_text("\n".join(lines) + "\n")
    return 0


if __name__ == "__main__":
    if {"-h", "--help"} & set(sys.argv[1:]):     # what it does, without running it
        print(__doc__)
        sys.exit(0)
    sys.exit(main())
