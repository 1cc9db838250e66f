"""method="auto" over many starts: its cost against the cheapest single run at matched
achieved error, its coverage of the request, and the per-case choice data auto reads.

For each of the six work-precision cases (bench/work_precision.py: parameters and T) and
the 20 random starts of the many-start benchmark (bench/limit.py random_starts, seed 19,
one generator across the cases in their order, as bench/auto_coverage.py and
limit.py's many-start mode draw them), in one process, per case in two phases:

  1 singles  simulate(method=m, rtol=atol=tol) for m = dop853 and vern9 at tolerances
             10^-5 ... 10^-14 (half decades) and m = taylor (heyoka on the lean generated
             field, solvers/integrate/taylor_backend.py, double) at 10^-6 ... 10^-14.5:
             each start's work-precision front of every method. With --write-data the
             case's choice data is written from them (below), and auto reads it from then on
  2 auto     simulate(method="auto", rtol=atol=E) for E = 1e-6, 1e-8, 1e-10, 1e-12, and
             beside it (interleaved) the singles whose errors bracket auto's achieved
             error, timed again: the timings the comparison at matched error reads

Every call is timed whole (wall: perf_counter; CPU: process_time, all threads), best of
REPEATS, the calls interleaved (each repeat runs every job once), its rhs calls counted (a
Taylor run counts its steps; auto: every run it made). The error of a run: max over the 101
output times of |y - y_ref|_inf / max(1, max |y_ref|_inf) (auto.error_between), the
reference heyoka in long double at tol 1e-19 on the general expression system; its own
error is bounded by a second long double run at 1e-18, and a start is judged at level E
only where that bound is <= E / 10 (bench/auto_coverage.py's rule); the others are counted.

Per case and level, over the judgeable starts: coverage (achieved <= E), and auto's cost
against the cheapest single run of any method at auto's own achieved error (each method's
time interpolated log-log on that start's Pareto front, bench/auto_front.py at_error; none
where no single run reaches it): wall and CPU ratios (median, worst), rhs calls over the
cheapest Runge-Kutta single's at the same error, and wall over the taylor single's
(heyoka-lean). Then the measured exponents of the error's growth with tol (what auto's
estimate assumes) and auto's first choice per level (the crossover where taylor begins).
Speed is measured here, never asserted in a test.

The choice data (--write-data, on the benchmark's starts only: 20, seed 19; a run of some
--cases writes those cases' entries): for each case and each level 10^-4 ... 10^-14 (half
decades), each judged start's CPU time at that error on each method's front and the
loosest tolerance of each method that reached it -> solvers/integrate/data/
auto_choice.json; solvers/integrate/auto_choice.py picks the method and tolerance from it.

    nice -n 10 PYTHONPATH=$PWD .venv/bin/python bench/auto_starts.py [--starts N]
        [--repeats R] [--cases a,b] [--write-data] [--seed S]
        -> bench/results/auto_starts.txt (and auto_starts_raw.json, every run's figures;
           a partial run -- --starts, --cases or another seed -- writes *_partial.*)
    PYTHONPATH=$PWD .venv/bin/python bench/auto_starts.py --from-raw FILE [FILE ...]
        the tables again from raw files (their cases merged), nothing run
"""

from __future__ import annotations

import argparse
import json
import math
import os
import sys
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))

from auto_front import at_error
from auto_starts_table import summary_lines, write_choice_case

OUT = Path(__file__).with_name("results")
SAMPLES = 101
LEVELS = (1e-6, 1e-8, 1e-10, 1e-12)
RK_TOLS = tuple(10.0 ** (-k / 2) for k in range(10, 29))       # 1e-5 ... 1e-14
TAYLOR_TOLS = tuple(10.0 ** (-k / 2) for k in range(12, 30))   # 1e-6 ... 10^-14.5
METHODS = ("dop853", "vern9", "taylor")
REF_TOL, REF_CHECK_TOL = 1e-19, 1e-18
SEED = 19
REPEATS = 3


def _call(fn):
    t0, c0 = time.perf_counter(), time.process_time()
    r = fn()
    return r, time.perf_counter() - t0, time.process_time() - c0


def timed_jobs(case_id, prm, T, y0, Yref, jobs, repeats, warm=False):
    """The calls of one start, interleaved (each repeat runs every job once), best of
    `repeats` in wall and CPU; warm: one untimed pass first (compiles, disk loads)."""
    from solvers.integrate.auto import error_between
    from solvers.simulate import simulate

    def call(kind, m, tol):
        if kind == "auto":
            return simulate(case_id, prm, list(y0), T, method="auto", rtol=tol, atol=tol,
                            samples=SAMPLES)
        kw = {"precision": "double"} if m == "taylor" else {}
        return simulate(case_id, prm, list(y0), T, method=m, rtol=tol, atol=tol,
                        samples=SAMPLES, **kw)

    for job in jobs if warm else ():
        call(*job)
    best = {}
    for _ in range(repeats):
        for job in jobs:
            r, wall, cpu = _call(lambda job=job: call(*job))
            b = best.get(job)
            if b is None:
                kind, m, tol = job
                ok = r.ok and len(r.state) == len(Yref)
                b = best[job] = {
                    "kind": kind, "method": m, "tol": tol, "ok": ok,
                    "error": error_between(r.state, Yref) if ok else math.inf,
                    "rhs_calls": int(r.stats["rhs_calls"]), "wall_s": wall, "cpu_s": cpu}
                if kind == "auto":
                    a = r.stats["auto"]
                    b.update({"returned": r.stats["method"], "returned_tol": r.stats["rtol"],
                              "precision": r.stats.get("precision"), "met": a["met"],
                              "estimate": r.stats["error_estimate"], "runs": a["runs"],
                              "rhs_calls": int(a["rhs_calls_total"]),
                              "choice": {k: a[k] for k in ("method", "tol")}})
            b["wall_s"], b["cpu_s"] = min(b["wall_s"], wall), min(b["cpu_s"], cpu)
    return best


def matched_costs(runs, achieved):
    """At error `achieved`: each method's wall, CPU and rhs calls interpolated on its
    front (None where its front does not reach it)."""
    out = {}
    for m in METHODS:
        pts = [(r["error"], r) for r in runs if r["kind"] == "single" and r["method"] == m
               and r["ok"] and math.isfinite(r["error"]) and r["error"] > 0]
        out[m] = {k: at_error([(e, r[k]) for e, r in pts], achieved)
                  for k in ("wall_s", "cpu_s", "rhs_calls")}
    return out


def bracket(singles, achieved):
    """Per method the two single runs whose errors bracket `achieved` (the ones the
    interpolation at that error reads)."""
    out = []
    for m in METHODS:
        ok = sorted((r for r in singles.values() if r["method"] == m and r["ok"]
                     and math.isfinite(r["error"])), key=lambda r: r["tol"])
        below = [r for r in ok if r["error"] <= achieved]
        above = [r for r in ok if r["error"] > achieved]
        if below:
            out.append(("single", m, max(below, key=lambda r: r["tol"])["tol"]))
        if above:
            out.append(("single", m, min(above, key=lambda r: r["tol"])["tol"]))
    return out


def run_case(case, n_starts, rng, repeats, levels, say, on_fronts=None):
    """Phase 1: every start's singles (its fronts); on_fronts(case_id, T, rows) then (the
    choice data auto reads from then on); phase 2: auto at each level on every start, the
    singles that bracket its achieved error timed again beside it."""
    from limit import random_starts

    from solvers.integrate.auto import error_between
    from solvers.integrate.taylor import Taylor
    from solvers.models.cases import build, registry

    spec = registry()[case.id]
    prm = {**spec.example, **case.overrides}
    model = build(case.id, prm)
    T = case.t_end
    t = np.linspace(0.0, T, SAMPLES)
    starts = random_starts(case.id, prm, n_starts, rng)
    ref = Taylor(model.model, model.p, starts[0], tol=REF_TOL, fp="longdouble",
                 compact_mode=True)
    ref_check = Taylor(model.model, model.p, starts[0], tol=REF_CHECK_TOL, fp="longdouble",
                       compact_mode=True)
    singles_jobs = [("single", m, tol) for m in METHODS
                    for tol in (TAYLOR_TOLS if m == "taylor" else RK_TOLS)]
    rows, refs = [], []
    for i, y0 in enumerate(starts):
        Yref, _, _, _, ok = ref.run(y0, t)
        Ychk, _, _, _, ok2 = ref_check.run(y0, t)
        bound = error_between(Ychk, Yref) if ok and ok2 else math.inf
        singles = timed_jobs(case.id, prm, T, y0, Yref, singles_jobs, repeats, warm=i == 0)
        rows.append({"y0": [float(v) for v in y0], "ref_bound": bound,
                     "runs": list(singles.values())})
        refs.append((Yref, singles))
        say(f"  {case.id} start {i + 1}/{len(starts)}: fronts measured, reference bound "
            f"{bound:.1e}")
    if on_fronts is not None:
        on_fronts(case.id, T, rows)
    for i, (y0, row, (Yref, singles)) in enumerate(zip(starts, rows, refs, strict=True)):
        autos = timed_jobs(case.id, prm, T, y0, Yref, [("auto", "auto", E) for E in levels],
                           1, warm=i == 0)
        again = sorted({j for a in autos.values() if a["ok"]
                        for j in bracket(singles, a["error"])})
        jobs = [*autos, *again]
        best = timed_jobs(case.id, prm, T, y0, Yref, jobs, repeats)
        for j in again:      # side by side with auto: these timings replace phase 1's
            singles[j] = best[j]
        runs = list(singles.values())
        for E in levels:
            a = best[("auto", "auto", E)]
            a["matched"] = matched_costs(runs, a["error"]) if a["ok"] else None
        row["runs"] = runs + [best[("auto", "auto", E)] for E in levels]
        say(f"  {case.id} start {i + 1}/{len(starts)}: auto "
            + ", ".join(f"{E:.0e} -> {best[('auto', 'auto', E)]['error']:.1e} "
                        f"({best[('auto', 'auto', E)]['returned']})" for E in levels))
    return {"T": T, "params": prm, "rows": rows}


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--starts", type=int, default=20)
    ap.add_argument("--repeats", type=int, default=REPEATS)
    ap.add_argument("--cases", help="comma-separated case ids (the same starts as a whole run)")
    ap.add_argument("--seed", type=int, default=SEED)
    ap.add_argument("--levels", help="comma-separated requested errors (default "
                    + ", ".join(f"{E:.0e}" for E in LEVELS) + ")")
    ap.add_argument("--write-data", action="store_true",
                    help="write the cases' entries of solvers/integrate/data/auto_choice.json "
                    "(20 starts, seed 19 only)")
    ap.add_argument("--from-raw", nargs="+",
                    help="raw JSONs of earlier runs (their cases merged): tables only")
    ap.add_argument("--tag", default="", help="suffix of the output files")
    args = ap.parse_args(argv)
    whole = args.starts == 20 and not args.cases and args.seed == SEED
    # the many-start benchmark's starts (a case's are the same in a run of some cases)
    data_ok = args.starts == 20 and args.seed == SEED
    stem = ("auto_starts" + ("" if whole else "_partial")) + args.tag
    if args.write_data and not data_ok:
        print("--write-data: only on the many-start benchmark's starts (20, seed 19)")
        return 1
    lines = []

    def say(s=""):
        print(s, flush=True)
        lines.append(s)

    if args.from_raw:
        from work_precision import CASES

        parts = [json.loads(Path(f).read_text()) for f in args.from_raw]
        raw = {**parts[0], "cases": {}}
        got = {cid: c for part in parts for cid, c in part["cases"].items()}
        raw["cases"] = {c.id: got[c.id] for c in CASES if c.id in got}
        raw["head"] = [line for part in parts for line in part["head"]]
        raw["whole"] = whole = len(raw["cases"]) == len(CASES) and all(
            p["starts"] == 20 and p["seed"] == SEED for p in parts)
        if len(parts) > 1:
            raw.pop("total_s", None)
        for line in raw["head"]:
            say(line)
    else:
        from work_precision import CASES

        levels = (tuple(float(x) for x in args.levels.split(",")) if args.levels
                  else LEVELS)
        load0 = os.getloadavg()
        raw = {"whole": whole, "seed": args.seed, "starts": args.starts,
               "repeats": args.repeats, "levels": levels, "cases": {},
               "head": [f"bench/auto_starts.py --starts {args.starts} --repeats "
                        f"{args.repeats} --seed {args.seed}"
                        + (f" --cases {args.cases}" if args.cases else "")
                        + f": load average {load0[0]:.2f} {load0[1]:.2f} {load0[2]:.2f} at the "
                        f"start ({os.cpu_count()} cores)"]}
        say(raw["head"][0])
        only = set(args.cases.split(",")) if args.cases else None
        rng = np.random.default_rng(args.seed)
        t0 = time.perf_counter()
        for case in CASES:
            if only and case.id not in only:
                from limit import random_starts

                from solvers.models.cases import registry

                spec = registry()[case.id]     # draw its starts all the same
                random_starts(case.id, {**spec.example, **case.overrides}, args.starts, rng)
                continue
            raw["cases"][case.id] = run_case(
                case, args.starts, rng, args.repeats, levels, say,
                on_fronts=write_choice_case if args.write_data and data_ok else None)
            OUT.mkdir(exist_ok=True)     # after each case: a stopped run keeps its cases
            (OUT / f"{stem}_raw.json").write_text(json.dumps(raw, default=float))
        raw["total_s"] = time.perf_counter() - t0
        raw["load_end"] = os.getloadavg()
    for line in summary_lines(raw):
        say(line)
    OUT.mkdir(exist_ok=True)
    if not args.from_raw:
        (OUT / f"{stem}_raw.json").write_text(json.dumps(raw, default=float))
    else:
        stem = ("auto_starts" + ("" if whole else "_partial")) + args.tag
    (OUT / f"{stem}.txt").write_text("\n".join(lines) + "\n")
    return 0


if __name__ == "__main__":
    sys.exit(main())
