"""Cost of one right-hand-side call per model, against the planar Kepler field as yardstick.

The full field used to allocate ~15 small arrays per call; the kernels now run on scalars
(solvers/kernels/fields.py). Absolute nanoseconds depend on the machine's load (it is
shared), so each model's cost is also given as a multiple of the Kepler field's, measured
in the same process a moment apart.

    .venv/bin/python bench/field_cost.py [--label NAME]

Run it on a checkout of an older commit (PYTHONPATH=that checkout) to compare before and
after; bench/results/field_cost.txt keeps both runs.
"""

from __future__ import annotations

import argparse
import time

import numba
import numpy as np

from solvers.kernels import layout as L
from solvers.kernels.fields import rhs
from solvers.models.cases import build, registry

N = 200_000
CASES = ("plane/chaplygin-ball", "plane/unbalanced-ball", "plane/round-disk",
         "plane/ellipsoid", "sphere/chaplygin-ball", "sphere/flat-base")


@numba.njit
def _loop(model, y, p, d, n):
    acc = 0.0
    for _ in range(n):
        y[0] += 1e-12
        rhs(model, 0.0, y, p, d)
        acc += d[0]
    return acc


def cost(model, y, p) -> float:
    y = np.array(y, dtype=float)
    d = np.empty_like(y)
    p = np.array(p, dtype=float)
    _loop(model, y, p, d, 10)
    best = np.inf
    for _ in range(5):
        t0 = time.perf_counter()
        _loop(model, y, p, d, N)
        best = min(best, time.perf_counter() - t0)
    return best / N * 1e9


def main(argv=None):
    ap = argparse.ArgumentParser()
    ap.add_argument("--label", default="current")
    args = ap.parse_args(argv)
    kepler = cost(L.MODEL_TEST_KEPLER, [1.0, 0.0, 0.0, 1.0], np.zeros(L.N_PARAMS))
    print(f"[{args.label}] Kepler yardstick {kepler:.1f} ns/call")
    for cid in CASES:
        c = registry()[cid]
        m = build(cid, c.example)
        ns = cost(m.model, c.state, m.p)
        print(f"[{args.label}] {cid:24s} {ns:7.1f} ns/call  = {ns / kepler:5.1f} x Kepler")


if __name__ == "__main__":
    main()
