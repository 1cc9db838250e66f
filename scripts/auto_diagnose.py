"""Where method="auto"'s time goes against the cheapest single run at the same achieved
error, on a few starts: the four parts of the question, each measured apart.

On a few random starts of some work-precision cases (auto_coverage.case_setup: the
many-start benchmark's starts for seed 19, other starts for another seed) and requested
errors E, in one process, every timing the best of REPEATS with the calls interleaved:

  (a) the method choice: at auto's achieved error, the CPU time of each method's front
      (the start's singles over the benchmark's tolerance grids, log-log interpolated:
      auto_starts.at_error) -- is the method auto returned the cheapest there?
  (b) the check: the returned run alone and the check run alone (simulate at their
      method and tolerance), CPU time and rhs calls: the check's share of one run
  (c) the thread: the returned run and its check by auto's own pairing (auto._pair on the
      integrator, no simulate around them) three ways: as auto pairs them (the check
      thread joins once the run has gone on auto.CHECK_DEFER_S), both at once, one after
      the other: the pair's wall over the longer run alone
  (d) fixed overheads: simulate(method="auto")'s CPU time less its runs' kernel time,
      against the same for a single simulate call

    ROLLING_KERNEL_CACHE=... PYTHONPATH=$PWD .venv/bin/python scripts/auto_diagnose.py
        [--cases a,b] [--starts N] [--seed S] [--levels 1e-6,1e-8] [--repeats R]
        -> stdout (and bench/results/auto_diagnose<tag>.txt with --tag)
The load average is printed at the start and the end: wall figures mean little above
about one busy process per core. Nothing here is asserted.
"""

from __future__ import annotations

import argparse
import math
import os
import sys
import time
from pathlib import Path

import numpy as np

BENCH = Path(__file__).resolve().parents[1] / "bench"   # the auto benches it reuses
sys.path.insert(0, str(BENCH))

from auto_coverage import case_setup, draw_only, reference  # noqa: E402  (after the path to bench/)
from auto_starts import METHODS, RK_TOLS, TAYLOR_TOLS, at_error  # noqa: E402  (after the path to bench/)
from work_precision import CASES  # noqa: E402  (after the path to bench/)

from solvers.integrate import auto  # noqa: E402  (after the path to bench/)
from solvers.simulate import _integrate, _model, simulate  # noqa: E402  (after the path to bench/)

OUT = BENCH / "results"
REPEATS = 5
# the pair's three ways (auto._pair's defer): auto's (the check thread joins once the run
# has gone on CHECK_DEFER_S), both at once, one after the other on this thread
PAIRINGS = {"deferred": None, "at_once": 0.0, "serial": -1.0}


def _cpu_wall(fn, repeats):
    """(result, best wall, best CPU over all threads) of fn() over `repeats` calls; the
    result returned is the one of the best wall (its own kernel timings go with it)."""
    best_w = best_c = math.inf
    r = None
    for _ in range(repeats):
        t0, c0 = time.perf_counter(), time.process_time()
        x = fn()
        w = time.perf_counter() - t0
        best_c = min(best_c, time.process_time() - c0)
        if w < best_w:
            best_w, r = w, x
    return r, best_w, best_c


def _single(case_id, prm, y0, T, samples, m, tol):
    kw = {"precision": "double"} if m == "taylor" else {}
    return simulate(case_id, prm, list(y0), T, method=m, rtol=tol, atol=tol,
                    samples=samples, **kw)


def front(case_id, prm, y0, T, samples, Yref, repeats):
    """{method: [(error, cpu_s, rhs_calls)]} over the benchmark's tolerance grids."""
    out = {}
    for m in METHODS:
        pts = []
        for tol in TAYLOR_TOLS if m == "taylor" else RK_TOLS:
            r, _, cpu = _cpu_wall(lambda m=m, tol=tol: _single(case_id, prm, y0, T, samples,
                                                               m, tol), repeats)
            if r.ok and len(r.state) == len(Yref):
                e = auto.error_between(r.state, Yref)
                if e > 0:
                    pts.append((e, cpu, r.stats["rhs_calls"]))
        out[m] = pts
    return out


def diagnose(case_id, prm, y0, T, samples, Yref, E, fr, repeats) -> dict:
    res, w_auto, c_auto = _cpu_wall(
        lambda: simulate(case_id, prm, list(y0), T, method="auto", rtol=E, atol=E,
                         samples=samples), repeats)
    a = res.stats["auto"]
    ret = res.stats["method"], res.stats["rtol"], res.stats.get("precision")
    achieved = auto.error_between(res.state, Yref)
    # (a) each method's CPU at auto's achieved error on this start's front
    at = {m: at_error([(e, c) for e, c, _ in fr[m]], achieved) for m in METHODS}
    reach = {m: v for m, v in at.items() if v is not None}
    cheapest = min(reach, key=reach.get) if reach else None
    # (b) the returned run and its check alone, through simulate
    rung = {"method": ret[0], "tol": ret[1], "precision": ret[2], "compensated": False}
    chk = auto._looser(rung, T) if len(a["rounds"]) <= 1 else None
    r1, w1, c1 = _cpu_wall(lambda: _single(case_id, prm, y0, T, samples, ret[0], ret[1]),
                           repeats)
    out = {"E": E, "achieved": achieved, "met": a["met"], "returned": f"{ret[0]}@{ret[1]:.3g}",
           "runs": a["runs"], "rounds": len(a["rounds"]), "expected_s": a.get("expected_s"),
           "auto_wall": w_auto, "auto_cpu": c_auto, "auto_rhs": a["rhs_calls_total"],
           "auto_kernel_s": a["wall_s_total"], "at": at, "cheapest": cheapest,
           "ret_wall": w1, "ret_cpu": c1, "ret_rhs": r1.stats["rhs_calls"],
           "ret_kernel_s": r1.stats["wall_s"]}
    if chk is not None:
        r2, w2, c2 = _cpu_wall(lambda: _single(case_id, prm, y0, T, samples, chk["method"],
                                               chk["tol"]), repeats)
        out.update({"chk": f"{chk['tol']:.3g}", "chk_wall": w2, "chk_cpu": c2,
                    "chk_rhs": r2.stats["rhs_calls"], "chk_kernel_s": r2.stats["wall_s"]})
        # (c) auto's own pairing on the integrator, side by side and one after the other
        model = _model(case_id, prm, False)[0]
        t_out = np.linspace(0.0, T, samples)
        y = np.asarray(y0, dtype=float)

        def runner(g, budget):
            return _integrate(model, y, t_out, g["method"], g["tol"], g["tol"], False,
                              budget, None, None, g["precision"])

        chk_rung = {**rung, **chk}
        for key, defer in PAIRINGS.items():
            (ra, rb), w, c = _cpu_wall(lambda defer=defer: auto._pair(
                runner, rung, 10**8, chk_rung, 10**8, defer=defer), repeats)
            out[key + "_wall"], out[key + "_cpu"] = w, c
            out[key + "_kernels"] = (ra.wall_s, rb.wall_s)
    return out


def lines_for(case_id, k, d) -> list[str]:
    base = min(v for v in d["at"].values() if v is not None) if d["cheapest"] else math.nan
    s = [f"  {case_id} start {k} E {d['E']:.0e}: achieved {d['achieved']:.1e} "
         f"(met {d['met']}), returned {d['returned']}, {d['runs']} runs, "
         f"{d['rounds']} rounds; expected_s {d['expected_s'] or math.nan:.2g}",
         "    (a) CPU at the achieved error: " + ", ".join(
             f"{m} {v * 1e3:.3g} ms" if v is not None else f"{m} -" for m, v in d["at"].items())
         + f" -> cheapest {d['cheapest']}; auto CPU / it {d['auto_cpu'] / base:.2f}, "
         f"wall / it {d['auto_wall'] / base:.2f}",
         f"    (b) returned alone: CPU {d['ret_cpu'] * 1e3:.3g} ms ({d['ret_cpu'] / base:.2f} "
         f"of the cheapest), {d['ret_rhs']} rhs calls, kernel {d['ret_kernel_s'] * 1e3:.3g} ms"]
    if "chk" in d:
        s.append(f"        check alone (tol {d['chk']}): CPU {d['chk_cpu'] * 1e3:.3g} ms = "
                 f"{d['chk_cpu'] / d['ret_cpu']:.2f} of the returned run's, {d['chk_rhs']} "
                 f"rhs calls = {d['chk_rhs'] / d['ret_rhs']:.2f}")
        longer = max(d["ret_wall"], d["chk_wall"])
        s.append("    (c) the pair's wall / the longer run alone's (run + check kernels, ms): "
                 + ", ".join(f"{k} {d[k + '_wall'] / longer:.2f} ({d[k + '_kernels'][0] * 1e3:.3g}"
                             f" + {d[k + '_kernels'][1] * 1e3:.3g})" for k in PAIRINGS)
                 + f"; the longer run alone {longer * 1e3:.3g} ms")
        over_auto = d["auto_cpu"] - d["auto_kernel_s"]
        over_one = d["ret_cpu"] - d["ret_kernel_s"]
        s.append(f"    (d) CPU outside the kernels: auto {over_auto * 1e3:.3g} ms, a single "
                 f"call {over_one * 1e3:.3g} ms; auto's CPU {d['auto_cpu'] * 1e3:.3g} ms = "
                 f"returned {d['ret_cpu'] / d['auto_cpu']:.0%} + check "
                 f"{d['chk_cpu'] / d['auto_cpu']:.0%} + the rest")
    return s


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--cases", default="plane/chaplygin-ball,sphere/chaplygin-ball")
    ap.add_argument("--starts", type=int, default=4)
    ap.add_argument("--seed", type=int, default=19)
    ap.add_argument("--levels", default="1e-6,1e-8,1e-10")
    ap.add_argument("--repeats", type=int, default=REPEATS)
    ap.add_argument("--tag", default="")
    args = ap.parse_args(argv)
    levels = [float(x) for x in args.levels.split(",")]
    want = args.cases.split(",")
    rng = np.random.default_rng(args.seed)
    load0 = os.getloadavg()
    text = [f"scripts/auto_diagnose.py --cases {args.cases} --starts {args.starts} --seed "
            f"{args.seed} --levels {args.levels} --repeats {args.repeats}: load average "
            f"{load0[0]:.2f} {load0[1]:.2f} {load0[2]:.2f} at the start "
            f"({os.cpu_count()} cores)"]
    print(text[0], flush=True)
    for case in CASES:
        if case.id not in want:
            draw_only(case, 20, rng)     # the benchmark's draw: the same starts per seed
            continue
        setup = case_setup(case, 20, rng)
        prm, T, samples = setup["params"], setup["T"], len(setup["t"])
        for k, y0 in enumerate(setup["starts"][:args.starts], 1):
            Yref, ok, bound = reference(setup, y0)
            if not ok:
                continue
            fr = front(case.id, prm, y0, T, samples, Yref, max(args.repeats // 2, 1))
            for E in levels:
                if bound > E / 10:
                    continue
                d = diagnose(case.id, prm, y0, T, samples, Yref, E, fr, args.repeats)
                for line in lines_for(case.id, k, d):
                    text.append(line)
                    print(line, flush=True)
    le = os.getloadavg()
    text.append(f"load average at the end {le[0]:.2f} {le[1]:.2f} {le[2]:.2f}")
    print(text[-1])
    if args.tag:
        OUT.mkdir(exist_ok=True)
        (OUT / f"auto_diagnose{args.tag}.txt").write_text("\n".join(text) + "\n")
    return 0


if __name__ == "__main__":
    sys.exit(main())
