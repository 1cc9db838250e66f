"""Compile time of the small kernels (solvers/kernels/small.py), per structure and tableau.

Each structure compiles in a fresh process on an empty generated-kernel cache
(ROLLING_KERNEL_CACHE in a temporary directory), so nothing is loaded from numba's cache:
the time of the first call is the compile (numba typing, lowering and LLVM) plus the run
of a 0.01 s trajectory. Reported: wall and CPU time of that first call (CPU time is the
process's own: on a loaded machine the wall time also holds the time other processes
took), the source size, and the time of the generated integrator for comparison when
--big is given (the loop kernel on the generated field).

    PYTHONPATH=$PWD .venv/bin/python bench/small_compile.py [--cases a,b] [--big]
        -> bench/results/small_compile.txt
"""

import json
import os
import subprocess
import sys
import tempfile
import time
from pathlib import Path

OUT = Path(__file__).with_name("results")

CHILD = r"""
import json, sys, time
import numpy as np
c0, w0 = time.process_time(), time.perf_counter()
from solvers.integrate import integrator as I
from solvers.kernels.integrals import ENERGY
from solvers.models.cases import build, registry
case, method, big = sys.argv[1], sys.argv[2], sys.argv[3] == "1"
c = registry()[case]
m = build(case, c.example)
imp = (time.process_time() - c0, time.perf_counter() - w0)
c1, w1 = time.process_time(), time.perf_counter()
if big:
    r = I.integrate(m.model, m.p, c.state, [0.0, 0.01], method=method, generated=True,
                    project_codes=(ENERGY,))
    src = I.generated_module(m.model, np.asarray(m.p))
else:
    r = I.integrate(m.model, m.p, c.state, [0.0, 0.01], method=method)
    src = I.small_module(m.model, m.p, method)
lines = open(src.__file__).read().count("\n")
print(json.dumps({"cpu": time.process_time() - c1, "wall": time.perf_counter() - w1,
                  "import_cpu": imp[0], "import_wall": imp[1], "kernel": r.kernel,
                  "lines": lines}))
"""


def one(case, method, big):
    with tempfile.TemporaryDirectory() as d:
        env = {**os.environ, "ROLLING_KERNEL_CACHE": d}
        out = subprocess.run([sys.executable, "-c", CHILD, case, method, "1" if big else "0"],
                             env=env, capture_output=True, text=True, check=True)
    return json.loads(out.stdout.strip().splitlines()[-1])


def main():
    from solvers.integrate.integrator import SMALL_METHODS
    from solvers.kernels import generate
    from solvers.models.cases import build, registry

    args = sys.argv[1:]
    big = "--big" in args
    chosen = None
    if "--cases" in args:
        chosen = args[args.index("--cases") + 1].split(",")
    seen, cases = set(), []
    for cid, c in registry().items():
        m = build(cid, c.example)
        if m.model not in generate.GENERATED_MODELS:
            continue
        key = generate.structure(m.model, m.p)
        if key in seen or (chosen and cid not in chosen):
            continue
        seen.add(key)
        cases.append(cid)
    load0 = os.getloadavg()
    lines = ["bench/small_compile.py: first call of a small kernel in a fresh process on an "
             "empty kernel cache (compile + a 0.01 s run); CPU = the process's own",
             f"load average at the start: {load0[0]:.2f} {load0[1]:.2f} {load0[2]:.2f} "
             f"({os.cpu_count()} cores)", ""]
    rows = []
    t0 = time.perf_counter()
    for cid in cases:
        for method in SMALL_METHODS:
            r = one(cid, method, False)
            rows.append({"case": cid, "method": method, **r})
            line = (f"{cid:30s} {method:7s} small: {r['cpu']:5.1f} s CPU {r['wall']:6.1f} s "
                    f"wall, {r['lines']} lines")
            print(line, flush=True)
            lines.append(line)
        if big:
            r = one(cid, "dop853", True)
            rows.append({"case": cid, "method": "generated integrator", **r})
            line = (f"{cid:30s} generated integrator (loop kernel):           {r['cpu']:5.1f} "
                    f"s CPU {r['wall']:6.1f} s wall")
            print(line, flush=True)
            lines.append(line)
    small = [r["cpu"] for r in rows if r["method"] in SMALL_METHODS]
    load1 = os.getloadavg()
    lines += ["", f"small kernels: {len(small)}, CPU per kernel median "
              f"{sorted(small)[len(small) // 2]:.1f} s, max {max(small):.1f} s, sum "
              f"{sum(small):.1f} s; whole run {time.perf_counter() - t0:.0f} s wall",
              f"load average at the end: {load1[0]:.2f} {load1[1]:.2f} {load1[2]:.2f}"]
    text = "\n".join(lines) + "\n"
    print(text)
    OUT.mkdir(exist_ok=True)
    (OUT / "small_compile.txt").write_text(text)


if __name__ == "__main__":
    if {"-h", "--help"} & set(sys.argv[1:]):     # what it does, without running it
        print(__doc__)
        sys.exit(0)
    main()
