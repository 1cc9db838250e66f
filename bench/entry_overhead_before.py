"""The entry overhead before the thin entry (commit e343ac4: general field, no memos), for
bench/results/entry_overhead.txt to be read against. Run it on that commit's tree:

    git archive e343ac4 | (mkdir -p /tmp/before && tar -x -C /tmp/before)
    PYTHONPATH=/tmp/before python bench/entry_overhead_before.py \
        > bench/results/entry_overhead_before.txt

Same method as bench/entry_overhead.py (a tiny run, interleaved, best of 60 batches of
50), with the general rk_integrate as the bare kernel (the only one that tree runs).
"""

import os
import time

import numpy as np

from solvers.integrate import integrator as I
from solvers.kernels import rk
from solvers.models.cases import build, registry
from solvers.simulate import simulate


def case_row(cid):
    c = registry()[cid]
    m = build(cid, c.example)
    p, y0 = np.array(m.p), np.array(c.state)
    t = np.linspace(0, 0.01, 3)
    n = y0.size
    A, cc, b, E, P, meth = I.method_arrays("dop853")
    ctl = I.StepControl()
    args = (int(m.model), p, y0, t, A, cc, b, E, P, meth,
            np.array([10_000_000, 0, 1, 0, 0, 1, 0], dtype=np.int64),
            np.array([1e-10, ctl.h0, ctl.h_max, ctl.safety, ctl.fac_min, ctl.fac_max,
                      ctl.beta]),
            np.full(n, 1e-12), np.zeros(0, dtype=np.int64), np.zeros(0), np.zeros(n + 1),
            np.empty((3, n)), np.empty(1), np.empty((1, n)), np.empty(n),
            np.zeros(5, dtype=np.int64))
    fns = {"kernel": lambda: rk.rk_integrate(*args),
           "integrate": lambda: I.integrate(m.model, m.p, c.state, t),
           "simulate": lambda: simulate(cid, c.example, c.state, 0.01, samples=3)}
    for f in fns.values():
        f()
    best = dict.fromkeys(fns, 1e9)
    for _ in range(60):
        for k, f in fns.items():
            t0 = time.perf_counter()
            for _ in range(50):
                f()
            best[k] = min(best[k], (time.perf_counter() - t0) / 50)
    k, i, s = (best[x] * 1e6 for x in ("kernel", "integrate", "simulate"))
    return (f"{cid:26s} kernel {k:6.1f} integrate {i:6.1f} (+{i - k:.1f}) simulate {s:6.1f} "
            f"(+{s - k:.1f}) load {os.getloadavg()[0]:.2f}")


if __name__ == "__main__":
    for cid in ("plane/chaplygin-ball", "plane/round-disk", "sphere/flat-base"):
        print(case_row(cid))
