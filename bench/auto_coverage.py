"""Does method="auto" keep its promise? Coverage of the requested error over random starts.

For each of the six work-precision cases (bench/work_precision.py: its parameters and T),
random starts from bench/limit.py's generator (random_starts: M in a random direction with
|M| log-uniform over two decades, 0.1x ... 10x the example's; gamma uniform on the sphere),
and requested errors E = 1e-6, 1e-10, 1e-12:

  auto      simulate(method="auto", rtol=E, atol=E, samples=101): the returned run, its
            error_estimate (solvers/integrate/auto.py: an upper estimate by extrapolation
            from a check run of the same method 10^2.5 times looser, run beside it on a
            second thread; tightened until the estimate is <= E, at most MAX_ROUNDS runs)
  first     auto's first choice alone (auto.choose(): the method and tolerance auto
            runs before its estimate), run as auto runs it

Achieved error: max over the 101 output times of |y - y_ref|_inf / max(1, max |y_ref|_inf)
(work_precision.py's measure, the one auto reads rtol as), the reference heyoka's Taylor
integrator in 80-bit long double at tol 1e-19 on the general expression system
(solvers/integrate/taylor.py: not the generated field auto's kernels run). Its own error is
bounded by its difference from a second long double run at tol 1e-18 (printed per case):
a start counts at level E only where that bound is <= E / 10; the others (chaotic over T, or
long double too short for E) are reported as "not measurable", with whether auto's own
estimate said it missed E there.

Printed per case and level: coverage (the fraction of runs with achieved <= requested),
median and worst achieved/requested, the same for the first choice alone, the estimate's own
ratio estimated/achieved (median, min, max), and auto's cost against the first choice alone:
its total rhs calls over all its runs / the first choice's (a Taylor run counts its steps, so
this ratio means little where auto moved to the Taylor backend) and its total integration
time (every run's, compile excluded) / the first choice's. No time is asserted.

    nice -n 10 .venv/bin/python bench/auto_coverage.py [--quick] [--levels 1e-6,1e-8]
        [--only CASE ...] [--seed S] [--extended-below E] [--tag T]
        -> bench/results/auto_coverage<T>.txt (--quick: auto_coverage_quick.txt, not kept;
           a run of --only cases writes a file only with --tag)
--quick: 3 starts per case, T at most 100, levels 1e-6 and 1e-10 (a smoke run, seconds once
the kernels are compiled). --only: those cases, each with the starts of a whole run.
--extended-below E: requests at or below E may run in long double (auto.EXTENDED_BELOW,
1e-14 by default): the option of long double where double's floor is above the request,
measured beside the default. Per level it also counts the runs that said met with the
achieved error above the request, the runs that did not say met but reached it, and auto's
integration time over the judged runs.
"""

from __future__ import annotations

import argparse
import math
import os
import sys
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))

from limit import random_starts
from work_precision import CASES

from solvers.integrate import auto as auto_mod
from solvers.integrate.integrator import integrate
from solvers.integrate.taylor import Taylor
from solvers.models.cases import build, registry
from solvers.simulate import simulate

OUT = Path(__file__).with_name("results")
SAMPLES = 101
LEVELS = (1e-6, 1e-10, 1e-12)
REF_TOL, REF_CHECK_TOL = 1e-19, 1e-18
REF_MARGIN = 10.0   # a run counts at level E only where the reference's bound is <= E / 10
SEED = 19


def error(Y, Yref) -> float:
    if len(Y) != len(Yref):
        return math.inf
    return auto_mod.error_between(Y, Yref)


def first_choice(model, y0, t, choice):
    """The front's choice run alone, as auto runs it (its achieved error: today's auto)."""
    if choice["method"] == "taylor":
        from solvers.integrate import taylor_backend

        r = taylor_backend.run(model.model, model.p, y0, t, rtol=choice["tol"],
                               precision=choice["precision"])
    else:
        r = integrate(model.model, model.p, y0, t, method=choice["method"],
                      rtol=choice["tol"], atol=choice["tol"], compensated=choice["compensated"])
    return r.y[:len(r.t)], r.rhs_calls, r.wall_s, r.success


def q(xs, f):
    xs = [x for x in xs if x is not None and math.isfinite(x)]
    return f(xs) if xs else math.nan


def case_setup(case, n_starts, rng, t_cap=None) -> dict:
    """One work-precision case as both auto benchmarks measure it: its parameters and
    model, T (the case's, at most t_cap), the SAMPLES output times, n_starts random starts
    drawn from rng (bench/limit.py random_starts) and the two long double Taylor
    references (REF_TOL, and REF_CHECK_TOL for the reference's own error bound: reference
    below)."""
    spec = registry()[case.id]
    prm = {**spec.example, **case.overrides}
    model = build(case.id, prm)
    T = min(case.t_end, t_cap) if t_cap else case.t_end
    starts = random_starts(case.id, prm, n_starts, rng)
    ref, ref_check = (Taylor(model.model, model.p, starts[0], tol=tol, fp="longdouble",
                             compact_mode=True) for tol in (REF_TOL, REF_CHECK_TOL))
    return {"params": prm, "model": model, "T": T, "t": np.linspace(0.0, T, SAMPLES),
            "starts": starts, "ref": ref, "ref_check": ref_check}


def draw_only(case, n_starts, rng) -> None:
    """Draw a case's starts from rng and nothing else: a run of some cases draws the
    skipped cases' starts all the same, so each case's starts are those of a whole run."""
    spec = registry()[case.id]
    random_starts(case.id, {**spec.example, **case.overrides}, n_starts, rng)


def reference(setup, y0):
    """(Y_ref, both reference runs succeeded, the reference's error bound: its difference
    from the REF_CHECK_TOL run) at the case's output times."""
    Yref, _, _, _, ok = setup["ref"].run(y0, setup["t"])
    Ychk, _, _, _, ok2 = setup["ref_check"].run(y0, setup["t"])
    return Yref, bool(ok and ok2), error(Ychk, Yref)


def run_case(case, n_starts, levels, t_cap, rng, say):
    setup = case_setup(case, n_starts, rng, t_cap)
    prm, model, T, t = setup["params"], setup["model"], setup["T"], setup["t"]
    rows = []
    for y0 in setup["starts"]:
        Yref, ref_ok, bound = reference(setup, y0)
        row = {"y0": [float(v) for v in y0], "M": float(np.linalg.norm(y0[:3])),
               "ref_ok": ref_ok, "ref_error_bound": bound, "levels": {}}
        for E in levels:
            r = simulate(case.id, prm, list(y0), T, method="auto", rtol=E, atol=E,
                         samples=SAMPLES)
            a = r.stats["auto"]
            choice = {k: a[k] for k in ("method", "tol", "precision", "compensated")}
            Y1, calls1, wall1, ok1 = first_choice(model, np.asarray(y0, dtype=float), t, choice)
            row["levels"][f"{E:.0e}"] = {
                "status": r.status, "method": r.stats["method"], "tol": r.stats["rtol"],
                "precision": r.stats.get("precision"), "runs": a["runs"], "met": a["met"],
                "estimate": r.stats["error_estimate"],
                "achieved": error(r.state, Yref) if r.ok else math.inf,
                "first": {**choice, "achieved": error(Y1, Yref) if ok1 else math.inf,
                          "rhs_calls": int(calls1), "wall_s": float(wall1)},
                "rhs_calls_total": a["rhs_calls_total"], "wall_s_total": a["wall_s_total"]}
        rows.append(row)
    lines = [f"\n== {case.id}  T = {T:g}  ({len(rows)} starts, |M| {min(r['M'] for r in rows):.3g}"
             f" ... {max(r['M'] for r in rows):.3g}; reference error bound "
             f"{max(r['ref_error_bound'] for r in rows):.1e}"
             + ("" if all(r["ref_ok"] for r in rows) else "; A REFERENCE RUN FAILED") + ")"]
    summary = {}
    for E in levels:
        key = f"{E:.0e}"
        good = [r["ref_ok"] and r["ref_error_bound"] <= E / REF_MARGIN for r in rows]
        L = [r["levels"][key] for r, g in zip(rows, good, strict=True) if g]
        bad = [r["levels"][key] for r, g in zip(rows, good, strict=True) if not g]
        ach = [x["achieved"] / E for x in L]
        fst = [x["first"]["achieved"] / E for x in L]
        est = [x["estimate"] / x["achieved"] if x["estimate"] is not None and x["achieved"] > 0
               else None for x in L]
        cost = [x["rhs_calls_total"] / x["first"]["rhs_calls"] for x in L
                if x["first"]["rhs_calls"]]
        n = max(len(L), 1)
        wall = [x["wall_s_total"] / x["first"]["wall_s"] for x in L if x["first"]["wall_s"] > 0]
        s = {"coverage": sum(a <= 1.0 for a in ach) / n,
             "median": q(ach, np.median), "worst": q(ach, max),
             "first_coverage": sum(a <= 1.0 for a in fst) / n,
             "first_median": q(fst, np.median), "first_worst": q(fst, max),
             "est_median": q(est, np.median), "est_min": q(est, min), "est_max": q(est, max),
             "not_met": sum(not x["met"] for x in L), "cost_median": q(cost, np.median),
             "met_but_missed": sum(x["met"] and x["achieved"] > E for x in L),
             "unmet_but_within": sum(not x["met"] and x["achieved"] <= E for x in L),
             "time_total": float(sum(x["wall_s_total"] for x in L)),
             "time_median": q([x["wall_s_total"] for x in L], np.median),
             "wall_median": q(wall, np.median), "wall_worst": q(wall, max),
             "methods": sorted({x["method"] for x in L}), "runs": len(L),
             "not_measurable": len(bad), "not_measurable_flagged": sum(not x["met"] for x in bad)}
        summary[key] = s
        lines.append(
            f"  E {key}: auto coverage {s['coverage']:.0%} ({round(s['coverage'] * len(L))}/"
            f"{len(L)})  achieved/E median {s['median']:.2g} worst {s['worst']:.2g}"
            f"  | first choice alone {s['first_coverage']:.0%}, median "
            f"{s['first_median']:.2g} worst {s['first_worst']:.2g}"
            f"  | estimate/achieved median {s['est_median']:.2g} [{s['est_min']:.2g}, "
            f"{s['est_max']:.2g}]  | estimate > E after {auto_mod.MAX_ROUNDS} rounds: "
            f"{s['not_met']} (achieved <= E on {s['unmet_but_within']} of them), met but "
            f"achieved > E: {s['met_but_missed']}"
            f"  | cost / the first choice's: rhs calls median {s['cost_median']:.2g}, "
            f"integration time median {s['wall_median']:.2g} worst {s['wall_worst']:.2g};"
            f" auto's integration time median {s['time_median'] * 1e3:.3g} ms, total "
            f"{s['time_total']:.3g} s"
            f"  ({', '.join(s['methods'])})"
            + (f"  | not measurable (reference bound > E/10): {s['not_measurable']}, auto's "
               f"estimate > E on {s['not_measurable_flagged']} of them" if bad else ""))
    for line in lines:
        say(line)
    return {"T": T, "params": prm, "rows": rows, "summary": summary}


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--quick", action="store_true", help="3 starts, T <= 100, 1e-6 and 1e-10")
    ap.add_argument("--only", nargs="*", help="case ids (each with the starts of a whole run)")
    ap.add_argument("--levels", help="comma-separated requested errors (default "
                    + ", ".join(f"{E:.0e}" for E in LEVELS) + ")")
    ap.add_argument("--seed", type=int, default=SEED)
    ap.add_argument("--extended-below", type=float, default=None,
                    help="auto.EXTENDED_BELOW for this run: requests at or below it may run "
                    "in long double (default auto's own, 1e-14): the option of allowing it")
    ap.add_argument("--tag", default="", help="suffix of the output file")
    args = ap.parse_args()
    n_starts, levels, t_cap = (3, LEVELS[:2], 100.0) if args.quick else (20, LEVELS, None)
    if args.levels:
        levels = tuple(float(x) for x in args.levels.split(","))
    if args.extended_below is not None:
        auto_mod.EXTENDED_BELOW = args.extended_below
    stem = ("auto_coverage_quick" if args.quick else "auto_coverage") + args.tag
    seed = args.seed
    rng = np.random.default_rng(seed)
    load0 = os.getloadavg()
    out = {"quick": args.quick, "starts": n_starts, "levels": levels, "seed": seed,
           "load_start": load0, "cases": {}}
    cmd = " ".join(sys.argv[1:])
    text = [f"bench/auto_coverage.py {cmd}: method='auto' over "
            f"{n_starts} random starts per case (bench/limit.py random_starts, seed {seed}), "
            f"requested errors {', '.join(f'{E:.0e}' for E in levels)}; achieved error = max "
            "over 101 output times of |y - y_ref| / max(1, max|y_ref|), reference heyoka long "
            f"double tol {REF_TOL:g} (general expression system); coverage = fraction of runs "
            "with achieved <= requested (target >= 95%); requests at or below "
            f"{auto_mod.EXTENDED_BELOW:g} may run in long double",
            f"load average at the start: {load0[0]:.2f} {load0[1]:.2f} {load0[2]:.2f} "
            f"({os.cpu_count()} cores)"]
    for line in text:
        print(line, flush=True)

    def say(s):
        text.append(s)
        print(s, flush=True)

    t0 = time.perf_counter()
    for case in CASES:
        if args.only and case.id not in args.only:
            draw_only(case, n_starts, rng)
            continue
        out["cases"][case.id] = run_case(case, n_starts, levels, t_cap, rng, say)
    cov = {}
    for E in levels:
        key = f"{E:.0e}"
        n = sum(c["summary"][key]["runs"] for c in out["cases"].values())
        k = sum(round(c["summary"][key]["coverage"] * c["summary"][key]["runs"])
                for c in out["cases"].values())
        k1 = sum(round(c["summary"][key]["first_coverage"] * c["summary"][key]["runs"])
                 for c in out["cases"].values())
        nm = sum(c["summary"][key]["not_measurable"] for c in out["cases"].values())
        tot = {f: sum(c["summary"][key][f] for c in out["cases"].values())
               for f in ("not_met", "unmet_but_within", "met_but_missed", "time_total")}
        cov[key] = {"covered": k, "runs": n, "first_covered": k1, "not_measurable": nm, **tot}
        met = n - tot["not_met"]
        say(f"\nall cases, E {key}: auto {k}/{n} = {k / n:.0%} within the requested error "
            f"(the first choice alone: {k1}/{n} = {k1 / n:.0%}); {nm} runs not measurable; "
            f"met {met}/{n}, of which achieved > E: {tot['met_but_missed']}; not met "
            f"{tot['not_met']}, of which achieved <= E: {tot['unmet_but_within']}; auto's "
            f"integration time over the judged runs {tot['time_total']:.3g} s")
    out["coverage"] = cov
    say(f"total {time.perf_counter() - t0:.0f} s; load average at the end "
        f"{os.getloadavg()[0]:.2f}")
    if not args.only or args.tag:
        OUT.mkdir(exist_ok=True)
        (OUT / f"{stem}.txt").write_text("\n".join(text) + "\n")


if __name__ == "__main__":
    main()
