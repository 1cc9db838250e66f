"""integrate()'s plain entry at two revisions, side by side in one process (issue 19, item
4: the short runs set the worst starts of bench/limit.py's many-start mode).

For each case, the many-start mode's start of smallest |M| (seed 19, the shortest run), at
rtol = atol 1e-6, T of the work-precision case: integrate() of this tree, integrate() of
solvers/integrate/integrator.py at REV (loaded from `git show` as a module of its own, on
this tree's kernels), and bench/limit.py's scalar limit, each timed alone right after a
heyoka run of the same start (as in the many-start rounds), ROUNDS rounds interleaved;
medians (perf_counter_ns). Both entries must give the same bits.

    PYTHONPATH=$PWD python bench/entry_ab.py [REV]        (default REV: HEAD~1)
        -> bench/results/entry_ab.txt
"""

import importlib.util
import os
import subprocess
import sys
import tempfile
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "bench"))
OUT = ROOT / "bench" / "results" / "entry_ab.txt"
CASES = ("plane/chaplygin-ball", "plane/ellipsoid", "sphere/flat-base")
ROUNDS = 400


def _entry_at(rev: str):
    text = subprocess.run(["git", "show", f"{rev}:solvers/integrate/integrator.py"],
                          cwd=ROOT, check=True, capture_output=True, text=True).stdout
    path = Path(tempfile.mkdtemp()) / "integrator_at_rev.py"
    path.write_text(text)
    spec = importlib.util.spec_from_file_location("integrator_at_rev", path)
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    return mod.integrate


def one_case(case_id, old_integrate):
    import heyoka as hy
    import limit as LB

    from solvers.integrate.integrator import integrate

    wp, prm, model = LB.work_precision_case(case_id)
    p = np.asarray(model.p, dtype=float)
    T, rt = wp.t_end, 1e-6
    starts = LB.random_starts(wp.id, prm, 20, np.random.default_rng(19))
    y0 = min(starts, key=lambda y: float(np.linalg.norm(y[:3])))
    v, f, _ = LB.heyoka_system(model.model, p, fold=True)
    ta = hy.taylor_adaptive(list(zip(v, f, strict=True)), y0, tol=1e-8)
    limit, _ = LB.scalar_limit(wp.id, model, p)

    def hey():
        ta.time = 0.0
        ta.state[:] = y0
        ta.propagate_until(T)

    new = integrate(model.model, p, y0, [0.0, T], rtol=rt, atol=rt)
    old = old_integrate(model.model, p, y0, [0.0, T], rtol=rt, atol=rt)
    assert np.array_equal(new.y, old.y) and np.array_equal(new.t, old.t), case_id
    fns = {"this tree": lambda: integrate(model.model, p, y0, [0.0, T], rtol=rt, atol=rt),
           "REV": lambda: old_integrate(model.model, p, y0, [0.0, T], rtol=rt, atol=rt),
           "limit": lambda: limit(y0, p, T, rt, rt)}
    took = LB.timed_after(fns, hey, ROUNDS)
    med = {k: float(np.median(v)) / 1e3 for k, v in took.items()}
    return (f"{case_id:22s} |M| {np.linalg.norm(y0[:3]):.3f}  this tree {med['this tree']:7.2f} "
            f"us  REV {med['REV']:7.2f} us  limit {med['limit']:7.2f} us  this tree / limit "
            f"{med['this tree'] / med['limit']:.3f}  REV / limit {med['REV'] / med['limit']:.3f}")


def main():
    rev = sys.argv[1] if len(sys.argv) > 1 else "HEAD~1"
    sha = subprocess.run(["git", "rev-parse", "--short", rev], cwd=ROOT, check=True,
                         capture_output=True, text=True).stdout.strip()
    old = _entry_at(rev)
    lines = [f"bench/entry_ab.py {rev} ({sha}): integrate() of this tree against REV's, and the "
             f"limit, rtol 1e-6, the shortest start of each case, each call right after a "
             f"heyoka run, {ROUNDS} rounds, medians; load average at the start "
             f"{' '.join(f'{x:.2f}' for x in os.getloadavg())}"]
    lines += [one_case(c, old) for c in CASES]
    lines.append(f"load average at the end {' '.join(f'{x:.2f}' for x in os.getloadavg())}")
    text = "\n".join(lines) + "\n"
    print(text)
    OUT.write_text(text)


if __name__ == "__main__":
    main()
