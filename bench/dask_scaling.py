"""Scaling of a map sweep on dask.distributed from 1 to 2 workers (this 2-core machine).

    python bench/dask_scaling.py      (output: bench/results/dask_scaling.txt)

The sweep: the unbalanced ball's offset a3 over 12 values, each task one map at E0 = 1
with 4 trajectories x 1500 points (seeded starts). Run in this process without dask, then
on a LocalCluster of 1 and of 2 worker processes (one thread each); the results of the
three runs must be identical (fixed seed). The machine is shared: the load average is
printed with the times.
"""

from __future__ import annotations

import json
import os
import time
from pathlib import Path

from solvers.maps.sweeps import DaskSettings, parameter_tasks, run_task, seeded, sweep

BASE = {"I1": 1.0, "I2": 2.0, "I3": 3.0, "m": 1.0, "R": 1.0, "a1": -0.24, "a2": -0.09}
VALUES = [-0.6 + 0.1 * i for i in range(12)]
SEED = 7


def tasks():
    return parameter_tasks("plane/unbalanced-ball", BASE, "a3", VALUES, 1.0,
                           trajectories=4, points=1500)


def strip(results):
    return json.dumps([{k: v for k, v in r.items() if k != "wall_s"} for r in results],
                      sort_keys=True)


def main():
    lines = ["dask.distributed scaling: unbalanced-ball offset sweep, 12 tasks x 4 "
             "trajectories x 1500 points (seed 7)"]
    t0 = time.perf_counter()
    serial = [run_task(t) for t in seeded(tasks(), SEED)]
    t_serial = time.perf_counter() - t0
    lines.append(f"  serial in-process (no dask):   {t_serial:7.2f} s   load "
                 f"{os.getloadavg()[0]:.2f}")
    runs = {}
    for w in (1, 2):
        t0 = time.perf_counter()
        res = sweep(tasks(), seed=SEED, settings=DaskSettings(workers=w, processes=True))
        total = time.perf_counter() - t0
        runs[w] = res
        busy = sum(r["wall_s"] for r in res.results)
        lines.append(f"  LocalCluster {w} worker(s):      {res.wall_s:7.2f} s compute "
                     f"(+ {res.extra['warm_s']:.2f} s loading the kernels in the workers, "
                     f"{total - res.wall_s:.2f} s in all outside the compute)   load "
                     f"{os.getloadavg()[0]:.2f}")
        lines.append(f"      sum of the task times {busy:.2f} s = {busy / res.wall_s:.2f} x the "
                     "wall time (tasks running at once; each slower when cores are shared)")
    speed = runs[1].wall_s / runs[2].wall_s
    lines.append(f"  speed-up 1 -> 2 workers: {speed:.2f}x  (efficiency {speed / 2:.0%})")
    same = strip(serial) == strip(runs[1].results) == strip(runs[2].results)
    lines.append(f"  identical results serial / 1 worker / 2 workers: {same}")
    text = "\n".join(lines)
    print(text)
    (Path(__file__).parent / "results" / "dask_scaling.txt").write_text(text + "\n")


if __name__ == "__main__":
    main()
