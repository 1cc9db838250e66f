"""Compiled ensembles: many trajectories in one compiled parallel call
(solvers/integrate/ensemble.py) against a Python thread pool of `integrate` calls and a
plain Python loop of them, and a Poincare map of 20 trajectories x 500 points.

    PYTHONPATH=$PWD .venv/bin/python bench/ensemble.py [--quick]

Batches: 100 starts (the case's example state, M perturbed by 10%), T = 200, 201 samples,
dop853, rtol 1e-10, atol 1e-12, on 2 workers (the compiled loop's numba threads, or the
pool's threads); every competitor runs the same kernel with the case's generated field
(and the compiled loop also with the general field), so the ratios are the Python per
trajectory and the parallel loop. The competitors run interleaved (A B C A B C ...), best
of `repeats`; all give identical numbers (checked). cpu/wall: the process's CPU time over
the wall time of that best run (2 = both cores busy with it all along; on a loaded
machine the threads wait for a core and it drops). The map: plane/chaplygin-ball at
E0 = 1, 20 seeded starts, 500 crossings each with the missed-crossing check, warm, in
process (solvers.maps.poincare.poincare), best of `repeats`, on 2 threads and on 1.
Targets: at most 0.25 ms per trajectory; the map in at most 0.5 s. The load
average is printed beside every figure: the machine is shared, read the ratios.
Writes bench/results/ensemble.txt.
"""

from __future__ import annotations

import argparse
import os
import sys
import time
from pathlib import Path

import numpy as np

from solvers.integrate.batch import integrate_threads
from solvers.integrate.ensemble import integrate_ensemble, threading_layer
from solvers.integrate.integrator import integrate
from solvers.maps.poincare import MapSpec, poincare
from solvers.models.cases import build, registry

OUT = Path(__file__).with_name("results") / "ensemble.txt"
CASES = ("plane/chaplygin-ball", "sphere/chaplygin-ball", "plane/round-disk",
         "plane/ellipsoid", "sphere/flat-base")
N, T_END, RTOL, ATOL, WORKERS = 100, 200.0, 1e-10, 1e-12, 2


def starts(case_id, n, seed):
    c = registry()[case_id]
    rng = np.random.default_rng(seed)
    Y = np.tile(np.array(c.state, dtype=float), (n, 1))
    Y[:, :3] *= 1.0 + 0.1 * rng.standard_normal((n, 3))
    return Y


def competitors(m, Y0, t_out):
    opts = {"rtol": RTOL, "atol": ATOL}
    return {
        "compiled loop (generated field)": lambda: integrate_ensemble(
            m.model, m.p, Y0, t_out, workers=WORKERS, generated=True, **opts),
        "compiled loop, 1 thread": lambda: integrate_ensemble(
            m.model, m.p, Y0, t_out, workers=1, generated=True, **opts),
        "compiled loop (general field)": lambda: integrate_ensemble(
            m.model, m.p, Y0, t_out, workers=WORKERS, generated=False, **opts),
        "Python thread pool": lambda: integrate_threads(
            m.model, m.p, Y0, t_out, workers=WORKERS, generated=True, **opts),
        "plain Python loop": lambda: [integrate(m.model, m.p, y0, t_out, generated=True,
                                                **opts) for y0 in Y0],
    }


def same(a, b):
    return all(np.array_equal(x.y, y.y) and x.steps == y.steps
               for x, y in zip(a, b, strict=True))


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--quick", action="store_true", help="2 cases, 3 repeats")
    args = ap.parse_args(argv)
    repeats = 3 if args.quick else 5
    cases = CASES[:2] if args.quick else CASES
    lines = []

    def say(s=""):
        print(s, flush=True)
        lines.append(s)

    say(f"cores available: {len(os.sched_getaffinity(0))}; numba threading layer "
        f"{threading_layer()}; {WORKERS} workers; best of {repeats}, interleaved")
    say(f"batches: {N} trajectories, T = {T_END:g}, 201 samples, dop853, rtol {RTOL:g}, "
        f"atol {ATOL:g}; ms per trajectory (target <= 0.25)")
    t_out = np.linspace(0.0, T_END, 201)
    for case_id in cases:
        m = build(case_id, registry()[case_id].example)
        Y0 = starts(case_id, N, 1)
        comp = competitors(m, Y0, t_out)
        ref = {k: fn() for k, fn in comp.items()}        # warm (compiles if needed)
        gen_ok = same(ref["compiled loop (generated field)"], ref["Python thread pool"]) and \
            same(ref["compiled loop (generated field)"], ref["plain Python loop"])
        best = dict.fromkeys(comp, np.inf)
        cpu = dict.fromkeys(comp, 0.0)
        loads = []
        for _ in range(repeats):
            for k, fn in comp.items():
                c0, t0 = time.process_time(), time.perf_counter()
                fn()
                wall = time.perf_counter() - t0
                if wall < best[k]:
                    best[k], cpu[k] = wall, (time.process_time() - c0) / wall
            loads.append(os.getloadavg()[0])
        steps = np.mean([r.steps for r in ref["compiled loop (generated field)"]])
        loop = best["compiled loop (generated field)"]
        say(f"{case_id} (mean {steps:.0f} steps per trajectory; identical results: "
            f"{gen_ok}; load average {min(loads):.2f}-{max(loads):.2f})")
        for k, t in best.items():
            say(f"  {k:34s} {1e3 * t / N:8.3f} ms/traj   {t / loop:6.2f}x the compiled loop"
                f"   cpu/wall {cpu[k]:4.2f}")
    # the map
    say()
    c = registry()["plane/chaplygin-ball"]
    say("Poincare map: plane/chaplygin-ball, E0 = 1, 20 trajectories x 500 points, "
        "dop853 rtol 1e-10, with the missed-crossing check (target <= 0.5 s warm)")
    for gen in (True, False):
        spec = MapSpec(energy=1.0, points=500, generated=gen)
        poincare("plane/chaplygin-ball", c.example, spec, trajectories=20, workers=WORKERS)
        best = {WORKERS: np.inf, 1: np.inf}
        loads = []
        for _ in range(repeats):
            for w in best:
                t0 = time.perf_counter()
                res = poincare("plane/chaplygin-ball", c.example, spec, trajectories=20,
                               workers=w)
                best[w] = min(best[w], time.perf_counter() - t0)
            loads.append(os.getloadavg()[0])
        pts = sum(len(tr.t) for tr in res.trajectories)
        steps = sum(tr.steps for tr in res.trajectories)
        say(f"  {'generated' if gen else 'general'} field: {best[WORKERS]:.3f} s on "
            f"{WORKERS} threads, {best[1]:.3f} s on 1 ({pts} points, {steps} steps; load "
            f"average {min(loads):.2f}-{max(loads):.2f})")
    OUT.parent.mkdir(exist_ok=True)
    # a --quick smoke run goes beside the kept table, not over it
    (OUT.with_name("ensemble_quick.txt") if args.quick else OUT).write_text(
        "\n".join(lines) + "\n")
    return 0


if __name__ == "__main__":
    sys.exit(main())
