"""method="auto" against heyoka on lean equations at matched error, the six work-precision
cases (the target: "at 1e-12 the auto choice is no slower than heyoka on any of the
six work-precision cases").

Competitors, each traced as a work-precision front on the case, T and initial state of
bench/work_precision.py (so the front auto reads is measured on the same problem):
  auto         simulate(method="auto", rtol=E) for target errors E: the method and tolerance
               solvers/integrate/auto.py picks from the committed front. Timed twice: the
               integration alone (stats wall_s, what heyoka's figure also is) and the whole
               simulate() call (validation, the invariants along the run, the stats).
  heyoka-lean  heyoka's taylor_adaptive in double on the case's generated lean equations
               with the parameters folded as constants (generate.heyoka_system(fold=True),
               the way a heyoka user writes them), full (unrolled) LLVM code,
               propagate_grid over the same 101 output times; compile excluded.
Errors: max over the output grid of |y - y_ref|_inf / max(1, max|y_ref|_inf), the reference
heyoka in long double at tol 1e-19 (work_precision.py's). Timings interleaved (auto point,
heyoka point, auto point, ...) in one process, best of REPEATS; time at the matched error
interpolated log-log on each front's Pareto points (None: the front does not reach it).

    PYTHONPATH=$PWD .venv/bin/python bench/auto_front.py [--quick]
        -> bench/results/auto_front.txt (--quick: auto_front_quick.txt, not kept)
"""

from __future__ import annotations

import argparse
import itertools
import math
import os
import sys
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))

from work_precision import CASES, SAMPLES

from solvers.integrate.taylor import Taylor
from solvers.kernels.generate import heyoka_system
from solvers.models.cases import build, initial_state, registry
from solvers.simulate import simulate

OUT = Path(__file__).with_name("results")
MATCH = 1e-12
TARGETS = (1e-10, 1e-11, 1e-12, 1e-13, 1e-14)
HEYOKA_TOLS = (1e-11, 1e-12, 1e-13, 1e-14, 1e-15, 1e-16)


def error(Y, Yref):
    if len(Y) != len(Yref):
        return math.inf
    return float(np.max(np.abs(Y - Yref)) / max(1.0, float(np.max(np.abs(Yref)))))


def pareto(points):
    """[(error, wall)] not beaten in both, by increasing error."""
    out, best = [], math.inf
    for e, w in sorted(points, key=lambda x: (x[1], x[0])):
        if e < best:
            out.append((e, w))
            best = e
    return sorted(out)


def at_error(points, target):
    """log-log interpolation of the wall time at `target` error on the Pareto front;
    the cheapest point if every point is below the target; None if none reaches it."""
    pts = pareto([p for p in points if math.isfinite(p[0]) and p[0] > 0])
    below = [w for e, w in pts if e <= target]
    if not below:
        return None
    for (e1, w1), (e2, w2) in itertools.pairwise(pts):
        if e1 <= target <= e2 and e1 < e2:
            s = (math.log(target) - math.log(e1)) / (math.log(e2) - math.log(e1))
            return math.exp(math.log(w1) + s * (math.log(w2) - math.log(w1)))
    return min(below)


def run_case(case, targets, tols, repeats, say):
    import heyoka as hy

    spec = registry()[case.id]
    params = {**spec.example, **case.overrides}
    model = build(case.id, params)
    y0 = initial_state(model, spec.state)
    t = np.linspace(0.0, case.t_end, SAMPLES)
    ref = Taylor(model.model, model.p, y0, tol=1e-19, fp="longdouble", compact_mode=True)
    Yref = ref.run(y0, t)[0]

    def auto(E):
        return simulate(case.id, params, spec.state, case.t_end, method="auto", rtol=E,
                        atol=E, samples=SAMPLES)

    hvars, rhs, _ = heyoka_system(model.model, model.p, fold=True)
    tas, compile_s = {}, {}
    for tol in tols:
        t0 = time.perf_counter()
        tas[tol] = hy.taylor_adaptive(list(zip(hvars, rhs, strict=True)), y0, tol=tol)
        compile_s[tol] = time.perf_counter() - t0

    def heyoka(tol):
        ta = tas[tol]
        ta.time = 0.0
        ta.state[:] = y0
        t0 = time.perf_counter()
        out = ta.propagate_grid(t)
        return out[-1], time.perf_counter() - t0

    choice = {}
    for E in targets:          # first runs: the Taylor backend's compiles, numba's loads
        r = auto(E)
        choice[E] = {"method": r.stats["method"], "tol": r.stats["rtol"],
                     "precision": r.stats.get("precision"), "reason": r.stats["auto"]["reason"],
                     "compile_s": r.stats.get("compile_s", 0.0)}
    best = {("auto", E): [math.inf, math.inf, None] for E in targets}
    best.update({("heyoka", tol): [math.inf, None] for tol in tols})
    for _ in range(repeats):       # interleaved: auto, heyoka, auto, heyoka, ...
        for E, tol in itertools.zip_longest(targets, tols):
            if E is not None:
                t0 = time.perf_counter()
                r = auto(E)
                call = time.perf_counter() - t0
                b = best[("auto", E)]
                if r.stats["wall_s"] < b[0]:
                    b[0], b[2] = r.stats["wall_s"], error(r.state, Yref)
                b[1] = min(b[1], call)
            if tol is not None:
                Y, wall = heyoka(tol)
                b = best[("heyoka", tol)]
                if wall < b[0]:
                    b[0], b[1] = wall, error(Y, Yref)
    autos = [{"target": E, **choice[E], "wall_s": best[("auto", E)][0],
              "call_s": best[("auto", E)][1], "error": best[("auto", E)][2]} for E in targets]
    heys = [{"tol": tol, "wall_s": best[("heyoka", tol)][0],
             "error": best[("heyoka", tol)][1], "compile_s": compile_s[tol]} for tol in tols]
    a_kernel = at_error([(a["error"], a["wall_s"]) for a in autos], MATCH)
    a_call = at_error([(a["error"], a["call_s"]) for a in autos], MATCH)
    h = at_error([(x["error"], x["wall_s"]) for x in heys], MATCH)
    say(f"\n== {case.id}  T = {case.t_end:g}")
    for a in autos:
        say(f"  auto   target {a['target']:.0e} -> {a['method']:7s} tol {a['tol']:.1e} "
            f"{a['precision'] or '':11s} error {a['error']:.1e}  integration "
            f"{a['wall_s'] * 1e3:8.2f} ms  simulate() {a['call_s'] * 1e3:8.2f} ms")
    for x in heys:
        say(f"  heyoka tol {x['tol']:.0e}  error {x['error']:.1e}  wall {x['wall_s'] * 1e3:8.2f}"
            f" ms  (compile {x['compile_s']:.1f} s)")

    def ms(v):
        return f"{v * 1e3:.2f} ms" if v is not None else "not reached"
    ratio = (a_kernel / h) if a_kernel and h else None
    ratio_call = (a_call / h) if a_call and h else None
    say(f"  at error {MATCH:.0e}: auto {ms(a_kernel)} (simulate() {ms(a_call)}), heyoka-lean "
        f"{ms(h)}; auto / heyoka = "
        + (f"{ratio:.2f} (simulate(): {ratio_call:.2f})" if ratio else "n/a"))
    return {"case": case.id, "t_end": case.t_end, "auto": autos, "heyoka_lean": heys,
            "at_match": {"error": MATCH, "auto_s": a_kernel, "auto_call_s": a_call,
                         "heyoka_lean_s": h, "ratio": ratio, "ratio_call": ratio_call}}


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--quick", action="store_true",
                    help="three targets, four heyoka tolerances, 3 repeats")
    ap.add_argument("--case", action="append", help="only these case ids")
    args = ap.parse_args(argv)
    targets = (1e-11, 1e-12, 1e-13) if args.quick else TARGETS
    tols = (1e-12, 1e-13, 1e-14, 1e-15) if args.quick else HEYOKA_TOLS
    repeats = 3 if args.quick else 7
    lines = []

    def say(s=""):
        print(s, flush=True)
        lines.append(s)

    load0 = os.getloadavg()
    say(f"bench/auto_front.py{' --quick' if args.quick else ''}: auto vs heyoka on lean "
        f"equations at matched error {MATCH:.0e}; load average {load0[0]:.1f} "
        f"{load0[1]:.1f} {load0[2]:.1f} at the start ({os.cpu_count()} cores)")
    t0 = time.perf_counter()
    out = [run_case(c, targets, tols, repeats, say) for c in CASES
           if not args.case or c.id in args.case]
    load1 = os.getloadavg()
    say("\nsummary at error 1e-12: (auto integration time) / (heyoka-lean time), and with "
        "the whole simulate() call")
    for r in out:
        m = r["at_match"]
        f = (f"{m['ratio']:.2f}  (simulate(): {m['ratio_call']:.2f})" if m["ratio"]
             else "n/a (a front does not reach 1e-12)")
        say(f"  {r['case']:24s} {f}")
    ok = [r["at_match"]["ratio"] is not None and r["at_match"]["ratio"] <= 1.0 for r in out]
    say(f"auto no slower than heyoka-lean (integration time) on {sum(ok)} of {len(out)} cases")
    say(f"load average {load1[0]:.1f} {load1[1]:.1f} {load1[2]:.1f} at the end; total "
        f"{time.perf_counter() - t0:.0f} s")
    OUT.mkdir(exist_ok=True)
    suffix = "_quick" if args.quick else ""
    (OUT / f"auto_front{suffix}.txt").write_text("\n".join(lines) + "\n")
    return 0


if __name__ == "__main__":
    sys.exit(main())
