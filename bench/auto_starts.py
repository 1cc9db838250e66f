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
time interpolated log-log on that start's Pareto front, at_error below; none
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
import itertools
import json
import math
import os
import sys
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))


OUT = Path(__file__).with_name("results")
SAMPLES = 101
LEVELS = (1e-6, 1e-8, 1e-10, 1e-12)
RK_TOLS = tuple(10.0 ** (-k / 2) for k in range(10, 29))       # 1e-5 ... 1e-14
TAYLOR_TOLS = tuple(10.0 ** (-k / 2) for k in range(12, 30))   # 1e-6 ... 10^-14.5
METHODS = ("dop853", "vern9", "taylor")
SEED = 19
REPEATS = 3


# ---- the tables and the choice data, from the raw figures

REF_MARGIN = 10.0     # a start is judged at level E where the reference's bound <= E / 10
DATA = Path(__file__).resolve().parents[1] / "solvers" / "integrate" / "data" / "auto_choice.json"
CHOICE_LEVELS = tuple(10.0 ** (-k / 2) for k in range(8, 29))     # 1e-4 ... 1e-14
TARGETS = {"wall_median": 1.3, "wall_worst": 2.0, "cpu_median": 1.8, "heyoka_median": 1.2}


def _q(xs, f):
    xs = [x for x in xs if x is not None and math.isfinite(x)]
    return float(f(xs)) if xs else math.nan


def _judged(rows, E):
    return [r for r in rows if r["ref_bound"] <= E / REF_MARGIN]


def _auto(row, E):
    return next(r for r in row["runs"] if r["kind"] == "auto" and r["tol"] == E)


def level_summary(rows, E) -> dict:
    judged = _judged(rows, E)
    ach, est, wall, cpu, rhs, hey, returned = [], [], [], [], [], [], {}
    met_missed = none_reach = 0
    for row in judged:
        a = _auto(row, E)
        ach.append(a["error"] / E)
        returned[a["returned"]] = returned.get(a["returned"], 0) + 1
        if a["met"] and a["error"] > E:
            met_missed += 1
        if a["estimate"] is not None and a["error"] > 0:
            est.append(a["estimate"] / a["error"])
        m = a.get("matched")
        if not m:
            continue
        w = [m[k]["wall_s"] for k in METHODS if m[k]["wall_s"] is not None]
        c = [m[k]["cpu_s"] for k in METHODS if m[k]["cpu_s"] is not None]
        h = [m[k]["rhs_calls"] for k in ("dop853", "vern9") if m[k]["rhs_calls"] is not None]
        if not w:
            none_reach += 1
            continue
        wall.append(a["wall_s"] / min(w))
        cpu.append(a["cpu_s"] / min(c))
        if h:
            rhs.append(a["rhs_calls"] / min(h))
        if m["taylor"]["wall_s"] is not None:
            hey.append(a["wall_s"] / m["taylor"]["wall_s"])
    n = len(judged)
    return {"judged": n, "not_judged": len(rows) - n,
            "covered": sum(x <= 1.0 for x in ach), "met_but_missed": met_missed,
            "achieved_median": _q(ach, np.median), "achieved_worst": _q(ach, max),
            "est_median": _q(est, np.median), "est_min": _q(est, min), "est_max": _q(est, max),
            "wall_median": _q(wall, np.median), "wall_worst": _q(wall, max),
            "cpu_median": _q(cpu, np.median), "cpu_worst": _q(cpu, max),
            "rhs_median": _q(rhs, np.median), "heyoka_median": _q(hey, np.median),
            "none_reach": none_reach, "returned": returned}


def summary_lines(raw) -> list[str]:
    levels = raw["levels"]
    out = ["", "auto / the cheapest single run of any method at auto's achieved error "
           "(wall, CPU: median and worst start), rhs calls / the cheapest Runge-Kutta "
           "single's, wall / heyoka-lean's (taylor single, double); coverage = achieved <= E "
           "over the judged starts; estimate / achieved (median [min, max]); 'met but "
           "missed' = stats.auto.met with achieved > E"]
    tot = {E: [0, 0, 0, 0] for E in levels}     # covered, judged, not judged, met-but-missed
    fails = []
    for cid, case in raw["cases"].items():
        out.append(f"\n== {cid}  T = {case['T']:g}")
        for E in levels:
            s = level_summary(case["rows"], E)
            t = tot[E]
            t[0] += s["covered"]
            t[1] += s["judged"]
            t[2] += s["not_judged"]
            t[3] += s["met_but_missed"]
            out.append(
                f"  E {E:.0e}: covered {s['covered']}/{s['judged']}"
                f" (not judged {s['not_judged']}), met but missed {s['met_but_missed']};"
                f" achieved/E median {s['achieved_median']:.2g} worst {s['achieved_worst']:.2g};"
                f" estimate/achieved {s['est_median']:.2g} [{s['est_min']:.2g}, "
                f"{s['est_max']:.2g}] | wall {s['wall_median']:.2f} worst {s['wall_worst']:.2f},"
                f" CPU {s['cpu_median']:.2f} worst {s['cpu_worst']:.2f}, rhs calls "
                f"{s['rhs_median']:.2f}, / heyoka-lean {s['heyoka_median']:.2f}"
                + (f"; no single reaches auto's error on {s['none_reach']}"
                   if s["none_reach"] else "")
                + f" | returned {s['returned']}")
            for k, lim in TARGETS.items():
                if not s[k] <= lim:
                    fails.append(f"{cid} {E:.0e} {k} {s[k]:.2f} > {lim}")
    out.append("")
    for E, (k, n, nj, mm) in tot.items():
        out.append(f"all cases, E {E:.0e}: auto within the request on {k}/{n} = "
                   f"{k / max(n, 1):.0%} of the judged runs ({nj} not judged); met but "
                   f"missed {mm}")
    out.append(f"targets ({', '.join(f'{k} <= {v}' for k, v in TARGETS.items())}) missed on "
               f"{len(fails)} of {len(raw['cases']) * len(levels) * len(TARGETS)} "
               "(case, level, target)" + (":" if fails else ""))
    out += [f"  {f}" for f in fails]
    out += alpha_lines(raw) + crossover_lines(raw)
    if "total_s" in raw:
        le = raw["load_end"]
        out.append(f"total {raw['total_s']:.0f} s; load average at the end {le[0]:.2f}")
    return out


def _sig(x):
    return None if x is None or not math.isfinite(x) else float(f"{x:.4g}")


def choice_table(rows) -> list[dict]:
    """Per level of CHOICE_LEVELS: each judged start's time at that error on each method's
    front (interpolated, None where it does not reach it) and the loosest tolerance of the
    method whose error is <= the level (None: no tolerance of the grid)."""
    out = []
    for L in CHOICE_LEVELS:
        judged = _judged(rows, L)
        cost = {m: [] for m in METHODS}
        loosest = {m: [] for m in METHODS}
        for row in judged:
            for m in METHODS:
                runs = [r for r in row["runs"] if r["kind"] == "single" and r["method"] == m
                        and r["ok"] and math.isfinite(r["error"]) and r["error"] > 0]
                cost[m].append(_sig(at_error([(r["error"], r["cpu_s"]) for r in runs], L)))
                good = [r["tol"] for r in runs if r["error"] <= L]
                loosest[m].append(_sig(max(good)) if good else None)
        out.append({"level": _sig(L), "judged": len(judged), "cpu_s": cost,
                    "loosest_tol": loosest})
    return out


def write_choice_case(case_id, T, rows) -> str:
    """Write one case's choice data into DATA (the other cases' entries kept) and make
    auto read it from now on."""
    from solvers.integrate import auto_choice

    data = {"format": 1, "generator": "python bench/auto_starts.py --write-data",
            "seed": 19, "starts": len(rows), "methods": list(METHODS),
            "note": "per case and level: each judged start's CPU time (s) at that error on "
                    "each method's front (interpolated) and the loosest tolerance reaching "
                    "it (taylor: heyoka on the lean generated field in double)",
            "cases": {}}
    if DATA.exists():
        old = json.loads(DATA.read_text())
        if old.get("format") == 1 and old.get("seed") == 19:
            data["cases"] = old["cases"]
    data["cases"][case_id] = {"T": T, "levels": choice_table(rows)}
    DATA.write_text(json.dumps(data, separators=(",", ":")) + "\n")
    auto_choice.reload()
    return str(DATA)


def slopes(raw, method, check_max_tol=1e-5, run_max_error=1e-6) -> list[float]:
    """The measured growth exponent of each start's error with tol between a run and the
    run auto would check it with (solvers/integrate/auto.py: CHECK_LOOSER looser for the
    pairs, two orders lower for Taylor; tols by auto.effective_tol), where both errors are
    above ten times the reference's bound, the check's tol is <= check_max_tol and the
    run's error <= run_max_error (the runs auto returns for requests of 1e-6 and below;
    looser runs of the chaotic cases reach errors of order one, where no power law holds)."""
    from solvers.integrate import auto

    out = []
    for case in raw["cases"].values():
        for row in case["rows"]:
            runs = {r["tol"]: r for r in row["runs"]
                    if r["kind"] == "single" and r["method"] == method and r["ok"]}
            for tol, r in runs.items():
                rung = {"method": method, "tol": tol, "precision": "double"}
                chk = auto._looser(rung, 1000.0)
                c = next((x for t, x in runs.items() if math.isclose(t, chk["tol"],
                                                                     rel_tol=1e-6)), None)
                e_r, e_c = auto.effective_tol(rung), auto.effective_tol(chk)
                if (c is None or e_c <= e_r or e_c > check_max_tol
                        or r["error"] > run_max_error
                        or min(r["error"], c["error"]) <= 10 * row["ref_bound"]):
                    continue
                out.append(math.log(c["error"] / r["error"]) / math.log(e_c / e_r))
    return out


def alpha_lines(raw) -> list[str]:
    from solvers.integrate import auto

    if not hasattr(auto, "effective_tol"):     # an auto without the looser check
        return []
    out = ["", "the error's growth exponent with tol between a run and auto's check of it "
           "(looser; both errors above 10x the reference bound, the run's error <= 1e-6): "
           "quantiles over every start and tol; auto.ALPHA is the exponent auto assumes (an "
           "estimate is above the error where the exponent is >= ALPHA)"]
    for m in METHODS:
        s = sorted(slopes(raw, m))
        if not s:
            continue
        qs = [s[int(f * (len(s) - 1))] for f in (0.01, 0.05, 0.1, 0.5)]
        below = sum(x < auto.ALPHA[m] for x in s)
        out.append(f"  {m:7s} n {len(s)}: 1% {qs[0]:.2f}, 5% {qs[1]:.2f}, 10% {qs[2]:.2f}, "
                   f"median {qs[3]:.2f}; below ALPHA {auto.ALPHA[m]}: {below} "
                   f"({below / len(s):.0%})")
    return out


def crossover_lines(raw) -> list[str]:
    """Per case, the method auto's first choice takes at each level of the choice data
    (auto_choice.first_choice on the data file as it stands), and where taylor begins."""
    try:
        from solvers.integrate import auto, auto_choice
    except ImportError:
        return []
    if auto_choice.load() is None:
        return []
    out = ["", "auto's first choice per level of the choice data (requests at twice the "
           "level: auto aims at half), and the crossover: the loosest level taylor is chosen"]
    for cid in raw["cases"]:
        picks = []
        for L in CHOICE_LEVELS:
            p = auto_choice.first_choice(cid, 2 * L, auto.CANDIDATES)
            picks.append((L, p["method"] if p else None, p["tol"] if p else None))
        first_taylor = next((L for L, m, _ in picks if m == "taylor"), None)
        out.append(f"  {cid}: " + ", ".join(f"{L:.0e} {m or '-'}" + (f" {t:.0e}" if t else "")
                                           for L, m, t in picks)
                   + f" | taylor from {first_taylor:.0e}" if first_taylor else
                   f"  {cid}: " + ", ".join(f"{L:.0e} {m or '-'}" for L, m, _ in picks)
                   + " | taylor never chosen")
    return out


# ---- the time at a given error on a start's front

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


# ---- the runs


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
    from auto_coverage import case_setup, reference

    setup = case_setup(case, n_starts, rng)
    prm, T, starts = setup["params"], setup["T"], setup["starts"]
    singles_jobs = [("single", m, tol) for m in METHODS
                    for tol in (TAYLOR_TOLS if m == "taylor" else RK_TOLS)]
    rows, refs = [], []
    for i, y0 in enumerate(starts):
        Yref, ok, bound = reference(setup, y0)
        bound = bound if ok else math.inf
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
                from auto_coverage import draw_only

                draw_only(case, args.starts, rng)
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
