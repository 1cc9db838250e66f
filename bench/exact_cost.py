"""Cost of the exact certificates (solvers/verify/exact), side by side in one process.

    PYTHONPATH=$PWD .venv/bin/python bench/exact_cost.py

1. The rational type: python-flint's fmpq against the standard library's Fraction on the
   exact layer's typical work (3x3 Gaussian elimination and products of 64-bit-grid
   rationals whose size grows as in the field evaluation), best of 3.
2. `verify()` over the whole catalogue in one process, with the exact hook off and on
   (run.exact_for replaced by a function returning None), once each, in CPU seconds of
   this process (time.process_time: the machine is shared, often at a load of 10-20 on 2
   cores, and wall time would measure the neighbours). Writes bench/results/exact_cost.txt.
"""

import os
import random
import sys
import time
from fractions import Fraction
from pathlib import Path

from flint import fmpq

OUT = Path(__file__).with_name("results") / "exact_cost.txt"


def workload(Q, seed=0, reps=40):
    rnd = random.Random(seed)

    def q():
        return Q(rnd.randrange(2 ** 64), 2 ** 64) + Q(1)
    acc = Q(0)
    for _ in range(reps):
        A = [[q() for _ in range(3)] for _ in range(3)]
        b = [q() for _ in range(3)]
        for c in range(3):                     # elimination, as linalg.solve
            for i in range(c + 1, 3):
                f = A[i][c] / A[c][c]
                A[i] = [A[i][j] - f * A[c][j] for j in range(3)]
                b[i] = b[i] - f * b[c]
        x = [Q(0)] * 3
        for i in (2, 1, 0):
            s = b[i] - sum((A[i][j] * x[j] for j in range(i + 1, 3)), Q(0))
            x[i] = s / A[i][i]
        acc = acc + x[0] * x[1] - x[2]
    return acc


def best(fn, n=3):
    out = []
    for _ in range(n):
        t = time.process_time()
        fn()
        out.append(time.process_time() - t)
    return min(out)


def main():
    lines = [f"load average {os.getloadavg()}"]
    tf = best(lambda: workload(fmpq))
    tF = best(lambda: workload(Fraction))
    a, b = workload(fmpq), workload(Fraction)
    assert (int(a.p), int(a.q)) == (b.numerator, b.denominator)     # the same exact result
    lines.append(f"rational workload: fmpq {tf * 1e3:.1f} ms, Fraction {tF * 1e3:.1f} ms, "
                 f"Fraction/fmpq = {tF / tf:.1f}")

    from solvers.verify import run
    hook = run.exact_for
    times = {"off": [], "on": []}
    run.verify(claim="plane/chaplygin-ball/integral/energy")      # imports, numba cache
    for mode in ("off", "on"):
        run.exact_for = hook if mode == "on" else (lambda *a, **k: None)
        t = time.process_time()
        recs = run.verify()
        times[mode].append(time.process_time() - t)
    run.exact_for = hook
    off, on = min(times["off"]), min(times["on"])
    n_cert = sum(1 for r in recs if r["exact"] and r["exact"]["holds"] and r["verdict"] ==
                 "verified")
    lines.append(f"verify() whole catalogue, one process, CPU: exact off {off:.1f} s, "
                 f"on {on:.1f} s,"
                 f" ratio {on / off:.2f} (+{on - off:.1f} s); {n_cert} verified records "
                 "certified")
    lines.append(f"load average {os.getloadavg()}")
    OUT.write_text("\n".join(lines) + "\n")
    print("\n".join(lines))


if __name__ == "__main__":
    if {"-h", "--help"} & set(sys.argv[1:]):     # what it does, without running it
        print(__doc__)
        sys.exit(0)
    main()
