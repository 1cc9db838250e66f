"""The loop kernel of this checkout against the loop kernel of another revision, side by side
in one process: the same runs on both, their bytes compared and their times interleaved.

The other revision's kernel is its solvers/kernels/rk.py (where the loop kernel was
written by hand before the step's template, solvers/kernels/step.py), loaded as a module of
its own from `git show REV:solvers/kernels/rk.py`, on this checkout's field, control and
section code. Runs: the general field (generated=False, kernel "rk") from many starts (the
example state of each case, its moment scaled by a random factor in [0.5, 2] and turned),
by dop853, vern9 and rk45, plain, with projection onto the energy and with a section. Each
run is timed on both kernels alternately (A B A B ...), best of `repeats`; the report gives
per case and kind the median over the starts of new / old, and whether every run gave the
same bytes (state, times, counters).

    PYTHONPATH=$PWD python scripts/loop_kernel_ab.py REV [--starts N] [--repeats R]
        [--cases a,b]
"""

from __future__ import annotations

import argparse
import hashlib
import importlib.util
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

from solvers.integrate.integrator import Section, integrate
from solvers.kernels import loop_kernel
from solvers.kernels.integrals import ENERGY
from solvers.models.cases import build, registry

ROOT = Path(__file__).resolve().parent.parent
CASES = ("plane/chaplygin-ball", "plane/unbalanced-ball", "plane/ellipsoid",
         "sphere/flat-base")


def old_kernel(rev: str):
    """rk_integrate of `rev`'s solvers/kernels/rk.py, as a module of its own."""
    text = subprocess.run(["git", "show", f"{rev}:solvers/kernels/rk.py"], cwd=ROOT,
                          capture_output=True, text=True, check=True).stdout
    d = Path(tempfile.mkdtemp(prefix="loop_ab_"))
    path = d / f"rk_{rev[:10]}.py"
    path.write_text(text)
    spec = importlib.util.spec_from_file_location(path.stem, path)
    mod = importlib.util.module_from_spec(spec)
    sys.modules[path.stem] = mod
    spec.loader.exec_module(mod)
    return mod.rk_integrate


def digest(r) -> str:
    h = hashlib.sha256()
    for a in (r.t, r.y, [r.t_stop], r.y_stop, r.crossings_t, r.crossings_y):
        h.update(np.ascontiguousarray(a, dtype=np.float64).tobytes())
    h.update(repr((int(r.status), r.steps, r.rejected, r.rhs_calls)).encode())
    return h.hexdigest()


def starts(case, n, rng):
    y0 = np.asarray(case.state, dtype=float)
    out = [y0]
    for _ in range(n - 1):
        y = y0.copy()
        q, _ = np.linalg.qr(rng.normal(size=(3, 3)))
        y[:3] = rng.uniform(0.5, 2.0) * (q @ y0[:3])
        out.append(y)
    return out


def runs(m, y0, method):
    t = np.linspace(0.0, 20.0, 41)
    n = y0.size
    sec = Section(coef=tuple(1.0 if i == 0 else 0.0 for i in range(n)), offset=float(y0[0]),
                  direction=0)
    return {
        "plain": lambda: integrate(m.model, m.p, y0, t, method=method, generated=False,
                                   kernel="rk"),
        "projected": lambda: integrate(m.model, m.p, y0, t, method=method, generated=False,
                                       project_codes=(ENERGY,)),
        "section": lambda: integrate(m.model, m.p, y0, [0.0, 40.0], method=method,
                                     generated=False, section=sec, max_crossings=20),
    }


def timed(fn, kern):
    """One run of fn on the loop kernel `kern`: (CPU seconds, result)."""
    loop_kernel.rk_integrate = kern
    c0 = time.process_time()
    r = fn()
    return time.process_time() - c0, r


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("rev")
    ap.add_argument("--starts", type=int, default=10)
    ap.add_argument("--repeats", type=int, default=5)
    ap.add_argument("--cases", default=",".join(CASES))
    a = ap.parse_args()
    new = loop_kernel.rk_integrate
    old = old_kernel(a.rev)
    rng = np.random.default_rng(0)
    same = total = 0
    print(f"loop kernel: this checkout / {a.rev}, CPU time, median over {a.starts} starts "
          f"(best of {a.repeats} each), general field")
    print(f"{'case':26s} {'method':7s} {'kind':10s} {'new/old':>8s}  {'same bytes':>10s}")
    ratios_all = []
    for cid in a.cases.split(","):
        case = registry()[cid]
        m = build(cid, case.example)
        for method in ("dop853", "vern9", "rk45"):
            ratios: dict[str, list[float]] = {}
            agree: dict[str, int] = {}
            for y0 in starts(case, a.starts, rng):
                for kind, fn in runs(m, y0, method).items():
                    timed(fn, old)      # compiled (or loaded) before timing
                    timed(fn, new)
                    t_old = t_new = np.inf
                    for _ in range(a.repeats):   # interleaved: A B A B ...
                        to, ro = timed(fn, old)
                        tn, rn = timed(fn, new)
                        t_old, t_new = min(t_old, to), min(t_new, tn)
                    ratios.setdefault(kind, []).append(t_new / t_old)
                    ok = digest(ro) == digest(rn)
                    agree[kind] = agree.get(kind, 0) + ok
                    same += ok
                    total += 1
            for kind, rs in ratios.items():
                med = statistics.median(rs)
                ratios_all.append(med)
                print(f"{cid:26s} {method:7s} {kind:10s} {med:8.3f}  "
                      f"{agree[kind]:4d} of {len(rs):3d}", flush=True)
    loop_kernel.rk_integrate = new
    print(f"same bytes: {same} of {total} runs; median of the medians new/old: "
          f"{statistics.median(ratios_all):.3f}")


if __name__ == "__main__":
    main()
