"""A small kernel before and after a change of solvers/kernels/small.py, side by side in one
process: the same bits, and the time per run.

The "before" kernel is written by small.py as it stands at a git revision (default HEAD),
loaded from `git show REV:solvers/kernels/small.py`; the "after" kernel by the checkout's.
Both run the same case, start and output times, alternately (best of --repeat runs each),
so a loaded machine slows both alike. Reported per case: whether the samples, the stop
state and the counters are bit-identical, the time per run of each and their ratio
(after / before: below 1 is faster), and the time per rhs call.

    PYTHONPATH=$PWD python bench/small_side.py [--before REV] [--method dop853]
        [--cases a,b] [--T 200] [--repeat 7]
"""

import importlib.util
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
CASES = ("plane/chaplygin-ball", "sphere/routh-ball", "plane/rattleback")


def before_module(rev: str):
    text = subprocess.run(["git", "show", f"{rev}:solvers/kernels/small.py"], cwd=ROOT,
                          capture_output=True, text=True, check=True).stdout
    path = Path(tempfile.mkdtemp()) / "small_before.py"
    path.write_text(text)
    spec = importlib.util.spec_from_file_location("small_before", path)
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    return mod


def kernel(small, model, p, method, tag):
    import hashlib

    from solvers.kernels import baked, generate

    tab = baked.baked_tableaux((method,))[method]
    text = small.kernel_source(model, p, method, tab)
    name = f"side_{tag}_{hashlib.sha256(text.encode()).hexdigest()[:16]}"
    return generate.cached_module(name, lambda: text).run


def main():
    import solvers.integrate.integrator  # noqa: F401 (provides the tableaux to baked.py)
    from solvers.kernels import rk
    from solvers.kernels import small as after
    from solvers.models.cases import build, registry

    args = sys.argv[1:]

    def opt(name, default):
        return args[args.index(name) + 1] if name in args else default

    rev, method = opt("--before", "HEAD"), opt("--method", "dop853")
    cases = opt("--cases", ",".join(CASES)).split(",")
    T, repeat = float(opt("--T", "200")), int(opt("--repeat", "7"))
    before = before_module(rev)
    print(f"small kernel, {method}: before = {rev}'s small.py, after = the checkout's; "
          f"T = {T}, best of {repeat}")
    for cid in cases:
        c = registry()[cid]
        m = build(cid, c.example)
        p = np.asarray(m.p, dtype=np.float64)
        runs = {tag: kernel(mod, m.model, p, method, tag)
                for tag, mod in (("before", before), ("after", after))}
        t_out = np.linspace(0.0, T, 401)
        out, best = {}, {"before": np.inf, "after": np.inf}
        for k in range(repeat + 1):
            for tag, run in runs.items():
                fopt, atol = _options(m.model)
                Y = np.zeros((t_out.size, len(c.state)))
                y_stop = np.zeros(len(c.state))
                stats = np.zeros(5, dtype=np.int64)
                t0 = time.perf_counter()
                status, t_stop = run(p, np.asarray(c.state, float), t_out, 10_000_000, False,
                                     fopt, atol, Y, y_stop, stats)
                dt = time.perf_counter() - t0
                if k:          # the first round compiles (or loads) both
                    best[tag] = min(best[tag], dt)
                out[tag] = (status, t_stop, Y.tobytes(), y_stop.tobytes(), stats.tobytes(),
                            int(stats[rk.S_RHS]))
        same = out["before"][:5] == out["after"][:5]
        rhs = out["after"][5]
        print(f"{cid:26s} bit-identical: {same}; per run {best['before'] * 1e3:8.2f} ms -> "
              f"{best['after'] * 1e3:8.2f} ms, ratio {best['after'] / best['before']:.3f}; "
              f"{best['after'] / rhs * 1e9:.1f} ns per rhs call ({rhs} calls)", flush=True)


def _options(model):
    """rk.py's packed options of a plain run at rtol 1e-10, atol 1e-12, the default step
    control (integrator.StepControl)."""
    from solvers.integrate.integrator import StepControl
    from solvers.kernels import layout as L
    from solvers.kernels import rk

    sc = StepControl()
    fopt = np.zeros(7)
    fopt[[rk.F_RTOL, rk.F_H, rk.F_HMAX, rk.F_SAFETY, rk.F_FACMIN, rk.F_FACMAX, rk.F_BETA]] = \
        (1e-10, sc.h0, sc.h_max, sc.safety, sc.fac_min, sc.fac_max, sc.beta)
    return fopt, np.full(L.STATE_DIM[model], 1e-12)


if __name__ == "__main__":
    main()
