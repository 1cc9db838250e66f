"""The Python cost of an entry call (the target: a repeated `simulate()` of the same
case should cost no more than 20 us beyond the kernel).

A tiny run (t_end = 0.01, 3 samples: a handful of steps) of each case, timed three ways
side by side in one process, interleaved (A B C A B C ...), each the best of many batches:
  kernel     the generated rk_integrate called directly with prebuilt arrays (the limit);
  integrate  solvers.integrate.integrator.integrate(model, p, y0, t_out);
  simulate   solvers.simulate.simulate(case, params, state, t_end, samples=3), which
             adds validation (memoized), the invariants along the run and their drift.
Overhead = entry - kernel, in microseconds and as a ratio.

    PYTHONPATH=$PWD python bench/entry_overhead.py [--quick] [--profile]

writes bench/results/entry_overhead.txt (--profile prints cProfile's top entries of a
repeated simulate() instead).
"""

import argparse
import os
import sys
import time
from pathlib import Path

import numpy as np

OUT = Path(__file__).resolve().parent / "results" / "entry_overhead.txt"
CASES = ("plane/chaplygin-ball", "plane/round-disk", "sphere/flat-base")


def _setup(case_id):
    from solvers import compile_state
    from solvers.integrate import integrator as I
    from solvers.kernels import field_modules
    from solvers.models.cases import build, registry

    c = registry()[case_id]
    model = build(case_id, c.example)
    p = np.array(model.p)
    y0 = np.array(c.state, dtype=float)
    t_out = np.linspace(0.0, 0.01, 3)
    assert compile_state.is_compiled(compile_state.generated_key(model.model, p)), \
        f"{case_id}: run python -m solvers.warmup --generated"
    kern = field_modules.generated_integrator(model.model, p).rk_integrate
    A, cc, b, E, P, meth = I.method_arrays("dop853")
    n = y0.size
    iopt = np.array([10_000_000, 0, 1, 0, 0, 1, 0], dtype=np.int64)
    ctl = I.StepControl()
    fopt = np.array([1e-10, ctl.h0, ctl.h_max, ctl.safety, ctl.fac_min, ctl.fac_max,
                     ctl.beta])
    args = (int(model.model), p, y0, t_out, A, cc, b, E, P, meth, iopt, fopt,
            np.full(n, 1e-12), np.zeros(0, dtype=np.int64), np.zeros(0), np.zeros(n + 1),
            np.empty((3, n)), np.empty(1), np.empty((1, n)), np.empty(n),
            np.zeros(5, dtype=np.int64))

    def kernel():
        kern(*args)

    def integrate():
        I.integrate(model.model, model.p, c.state, t_out)

    def simulate():
        from solvers.simulate import simulate as sim
        sim(case_id, c.example, c.state, 0.01, samples=3)

    r = I.integrate(model.model, model.p, c.state, t_out)
    assert r.vector_field == "generated" and r.success
    return {"kernel": kernel, "integrate": integrate, "simulate": simulate}, r.steps


def measure(fns, rounds, batch):
    best = dict.fromkeys(fns, np.inf)
    for f in fns.values():
        f()
    for _ in range(rounds):
        for name, f in fns.items():
            t0 = time.perf_counter()
            for _ in range(batch):
                f()
            best[name] = min(best[name], (time.perf_counter() - t0) / batch)
    return best


def profile(case_id, n=20000):
    import cProfile
    import pstats

    fns, _ = _setup(case_id)
    fns["simulate"]()
    pr = cProfile.Profile()
    pr.enable()
    for _ in range(n):
        fns["simulate"]()
    pr.disable()
    pstats.Stats(pr).sort_stats("tottime").print_stats(20)


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--quick", action="store_true")
    ap.add_argument("--profile", action="store_true")
    a = ap.parse_args(argv)
    if a.profile:
        profile(CASES[0])
        return
    rounds, batch = (60, 50) if a.quick else (300, 100)
    load0 = os.getloadavg()
    lines = ["Entry overhead: a tiny run (t_end = 0.01, 3 samples, dop853, rtol 1e-10) per case,",
             "the generated kernel called bare vs integrate() vs simulate(), interleaved,",
             f"best of {rounds} batches of {batch} calls each (microseconds per call).",
             "overhead = entry - kernel; target: <= 20 us for a repeated simulate().",
             "", f"{'case':26s} {'steps':>5s} {'kernel':>8s} {'integrate':>10s} "
             f"{'(+us, x)':>14s} {'simulate':>9s} {'(+us, x)':>14s}"]
    worst = 0.0
    for case_id in CASES:
        fns, steps = _setup(case_id)
        best = measure(fns, rounds, batch)
        k, i, s = (best[x] * 1e6 for x in ("kernel", "integrate", "simulate"))
        worst = max(worst, s - k)
        lines.append(f"{case_id:26s} {steps:5d} {k:8.1f} {i:10.1f} "
                     f"{f'(+{i - k:.1f}, {i / k:.2f}x)':>14s} {s:9.1f} "
                     f"{f'(+{s - k:.1f}, {s / k:.2f}x)':>14s}")
    load1 = os.getloadavg()
    lines += ["", f"largest simulate() overhead: {worst:.1f} us "
              f"({'meets' if worst <= 20 else 'misses'} the 20 us target)",
              f"load average before/after: {load0[0]:.2f} / {load1[0]:.2f} (2 cores shared)",
              f"python {sys.version.split()[0]}, numpy {np.__version__}",
              f"command: PYTHONPATH=$PWD python bench/entry_overhead.py{' --quick' * a.quick}"]
    text = "\n".join(lines) + "\n"
    print(text)
    (OUT.with_name("entry_overhead_quick.txt") if a.quick else OUT).write_text(text)


if __name__ == "__main__":
    main()
