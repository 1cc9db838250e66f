"""What a Taylor integrator costs on first use, per case (the target: no compile inside a
request's deadline): heyoka's compile against loading the integrator from the disk cache
(solvers/integrate/taylor_backend.py), for the precisions method "taylor" and "auto" take.

Where compiled Taylor integrators are kept: heyoka 7 keeps the LLVM object code of what it
compiled in memory (llvm_state memcache, per process) and on disk (llvm_state diskcache,
on by default: $XDG_CACHE_HOME/heyoka, else ~/.cache/heyoka); taylor_backend keeps the
integrators in a per-process LRU and pickled in ROLLING_KERNEL_CACHE/taylor.

Per work-precision case (bench/work_precision.py's CASES, their parameters) and per
(precision, tol), taylor_backend.compiled() timed in FRESH interpreters (a new worker
process has nothing in memory), one after another:
  cold        empty heyoka disk cache, empty taylor cache: build the expressions, compile
  heyoka      heyoka's disk cache warm, taylor's empty: build the expressions, Taylor
              decomposition, heyoka finds the object code on disk
  taylor      both warm: taylor_backend unpickles the integrator
  first run   a short propagate after it (cold / taylor), any lazy work left to it
Wall seconds, at the load average printed with them.

    PYTHONPATH=$PWD .venv/bin/python bench/taylor_compile.py [--quick]
        -> bench/results/taylor_compile{,_quick}.txt
"""

from __future__ import annotations

import argparse
import json
import os
import subprocess
import sys
import tempfile
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))

ROOT = Path(__file__).resolve().parents[1]
# (precision, tol): double at a common tolerance (unrolled code), long double where auto
# goes below double's floor (compact mode; auto's first run and its check run at 1e-15)
RUNS = (("double", 1e-10), ("long double", 1e-16), ("long double", 10 ** -17.5))

CHILD = r"""
import json, sys, time
import numpy as np
from solvers.integrate import taylor_backend as tb
from solvers.models.cases import build, initial_state
cid, params, state, prec, tol = json.loads(sys.argv[1])
m = build(cid, params)
y0 = initial_state(m, state)
t0 = time.perf_counter()
import heyoka  # noqa: F401
imp = time.perf_counter() - t0
t0 = time.perf_counter()
entry, source = tb.compiled(m.model, m.p, prec, tol)
got = time.perf_counter() - t0
t0 = time.perf_counter()
r = tb.run(m.model, m.p, y0, np.linspace(0.0, 1.0, 3), rtol=tol, precision=prec)
first = time.perf_counter() - t0
print(json.dumps({"source": source, "get_s": got, "first_s": first, "import_s": imp,
                  "ok": r.status == 0}))
"""


def _child(args, cache: str, xdg: str) -> dict:
    env = {**os.environ, "ROLLING_KERNEL_CACHE": cache, "XDG_CACHE_HOME": xdg,
           "PYTHONPATH": str(ROOT)}
    out = subprocess.run([sys.executable, "-c", CHILD, json.dumps(args)], env=env,
                         capture_output=True, text=True, check=True)
    return json.loads(out.stdout.strip().splitlines()[-1])


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--quick", action="store_true", help="two cases, one precision")
    a = ap.parse_args()
    from work_precision import CASES

    cases = CASES[:2] if a.quick else CASES
    runs = RUNS[:2] if a.quick else RUNS
    lines = [f"load average at start: {os.getloadavg()[0]:.2f} (2 cores here)",
             f"{'case':34s} {'precision':12s} {'tol':>8s} {'cold s':>7s} {'heyoka':>7s} "
             f"{'taylor':>7s} {'first run s':>11s}"]
    print(lines[0], flush=True)
    from solvers.models.cases import registry

    for case in cases:
        spec = registry()[case.id]
        cid, params, state = case.id, {**spec.example, **case.overrides}, list(spec.state)
        for prec, tol in runs:
            args = [cid, params, state, prec, tol]
            with tempfile.TemporaryDirectory() as xdg, tempfile.TemporaryDirectory() as c1, \
                    tempfile.TemporaryDirectory() as c2:
                cold = _child(args, c1, xdg)
                hey = _child(args, c2 + "/fresh", xdg)
                disk = _child(args, c1, xdg)
            assert cold["source"] is None and hey["source"] is None, (cold, hey)
            assert disk["source"] == "disk", disk
            line = (f"{cid:34s} {prec:12s} {tol:8.1e} {cold['get_s']:7.2f} "
                    f"{hey['get_s']:7.3f} {disk['get_s']:7.3f} "
                    f"{cold['first_s']:5.3f}/{disk['first_s']:5.3f}")
            print(line, flush=True)
            lines.append(line)
    lines.append(f"load average at end: {os.getloadavg()[0]:.2f}")
    out = ROOT / "bench" / "results" / f"taylor_compile{'_quick' if a.quick else ''}.txt"
    head = __doc__.split("\n    PYTHONPATH")[0].rstrip()
    out.write_text(f"{head}\n\n" + "\n".join(lines) + "\n")
    print(f"-> {out}")


if __name__ == "__main__":
    main()
