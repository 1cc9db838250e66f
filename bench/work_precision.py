"""Work-precision: every method the project offers against scipy and heyoka, one process.

For six marble cases (Chaplygin ball, unbalanced ball with gravity, disk, ellipsoid, a ball
on a sphere, a flat base on a sphere), the rubber Chaplygin ball on a plane and inside a
sphere (scipy's NumPy field: solvers/models/rubber_lagrange.py's, as in simulate) and
tolerances 1e-4 ... 1e-16 (rtol = atol; scipy from 1e-4 to 1e-14):

  ours      dop853, vern9 (compiled kernels, compensated summation), each also with
            projection onto the case's integrals after every step ("+proj"); gauss8,
            the symmetric 4-stage Gauss collocation method with constant steps STEPS
            (its knob is the step h, not a tolerance: recorded as tol = h, knob "h")
  scipy     solve_ivp DOP853 on the independent NumPy field (solvers/models/reference.py, what
            `--method scipy-dop853` runs) and on our compiled field (scipy's own overhead
            only); LSODA and Radau on the compiled field
  heyoka    adaptive Taylor in float64 on the expression system of solvers/integrate/taylor.py
            (compiled once per tolerance, compilation excluded and reported)
  taylor    the project's Taylor backend (method "taylor": heyoka on the lean generated
            field, solvers/integrate/taylor_backend.py) in double at every tolerance and in
            long double at TAYLOR_EXTENDED; one of ours, a candidate of method "auto"

Error: max over 101 output times of |y - y_ref|_inf / max(1, max|y_ref|_inf); the
reference is heyoka in 80-bit long double at tol 1e-19, checked against heyoka in real128
(quadruple) at tol 1e-24 (the difference is printed as the reference's own error bound).
Cost: wall time (ours and heyoka: best of REPEATS, in this process, same load) and
right-hand-side calls (heyoka: Taylor steps and order instead). scipy (which clips
rtol to 2.2e-14 for its Runge-Kutta methods) runs are bounded: once a run of a method
takes more than BUDGET_S / 3, its tighter tolerances are skipped and marked so. No
absolute time is asserted anywhere: the ratios are read side by side.

    .venv/bin/python bench/work_precision.py [--quick]       (or: rolling bench work-precision)
    .venv/bin/python bench/work_precision.py --only-taylor    (re-measure auto's
        candidates dop853, vern9 and taylor together, interleaved, and merge them into the
        committed JSON, the other methods' runs kept)
    .venv/bin/python bench/work_precision.py --cases ID[,ID]    (measure only these cases,
        every method as the full run does, and merge them into the committed JSON: their
        entries and runs replaced or added, the other cases' kept)
    .venv/bin/python bench/work_precision.py --table    (the table of the committed JSON)

Writes solvers/integrate/data/work_precision.json (every run; package data the explorer serves)
and bench/results/work_precision.txt (the table; --quick: work_precision_quick.{txt,json} in
bench/results/, not kept; --only-taylor: bench/results/work_precision_taylor.txt; --cases:
bench/results/work_precision_cases_<ids>.txt, the named cases' runs and then the table of
every case in the merged JSON). The data
file names its format and this command ("format", "generator"): workprecision.FORMAT;
solvers/integrate/workprecision.py summarises them for the explorer (GET /api/work-precision).
"""

from __future__ import annotations

import argparse
import json
import platform
import sys
import time
import warnings
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from solvers.integrate import workprecision as wp
from solvers.integrate.integrator import integrate
from solvers.integrate.reference import solve_ivp_reference
from solvers.integrate.taylor import Taylor
from solvers.kernels.fields import rhs
from solvers.models.cases import build, initial_state, registry
from solvers.models.reference import field as ref_field

OUT = Path(__file__).with_name("results")
TOLS = (1e-4, 1e-6, 1e-8, 1e-10, 1e-12, 1e-14, 1e-15, 1e-16)
STEPS = (0.4, 0.2, 0.1, 0.05, 0.025, 0.0125)     # gauss8
SCIPY_MIN_TOL = 1e-14    # scipy clips rtol to 2.2e-14: tighter runs would repeat that one
SAMPLES = 101
REPEATS = 5
TAYLOR_EXTENDED = (1e-14, 1e-15, 1e-16)   # the taylor backend also in long double here
# --only-taylor also measures auto's candidates half a decade apart from 10^-8.5 to
# 10^-10.5 and a quarter decade apart from 10^-11.25 to 10^-13.75, the grid the taylor
# backend compiles for (taylor_backend.snap_tol): a Taylor method's error is not a smooth
# power of tol (its order steps with it), so auto runs only measured tolerances, and
# where the fronts cross (1e-11 ... 1e-14) the grid is the backend's own
HALF_DECADES = (*(10.0 ** -(k + 0.5) for k in range(8, 11)),
                *(10.0 ** -(k + q) for k in range(11, 14) for q in (0.25, 0.5, 0.75)))
BUDGET_S = 60.0


@dataclass(frozen=True)
class WPCase:
    id: str
    overrides: dict = field(default_factory=dict)
    t_end: float = 1000.0
    note: str = ""


CASES = (
    WPCase("plane/chaplygin-ball", note="integrable (Chaplygin)"),
    WPCase("plane/unbalanced-ball", {"g": 1.0}, 100.0,
           note="with gravity, sensitive to initial data: errors grow ~1e4 per 1000 time "
                "units, so T = 100"),
    WPCase("plane/round-disk", note="integrable (Chaplygin disk), gravity on"),
    WPCase("plane/ellipsoid"),
    WPCase("sphere/chaplygin-ball", note="k = 0.3"),
    WPCase("sphere/flat-base", note="k = -0.5, z = 0.3"),
    WPCase("rubber-plane/chaplygin-ball",
           note="rubber (no spin about the normal); scipy on the Lagrange-d'Alembert field"),
    WPCase("rubber-sphere/ball-inside",
           note="rubber, inside a fixed sphere; scipy on the Lagrange-d'Alembert field"),
)


def _record(case, method, tol, Y, Yref, wall, rhs_calls, steps, ok, msg="", **extra):
    err = None
    if ok and Y is not None and len(Y) == len(Yref):
        err = float(np.max(np.abs(Y - Yref)) / max(1.0, float(np.max(np.abs(Yref)))))
        if not np.isfinite(err):       # a "successful" run that returned garbage
            err, ok, msg = None, False, f"non-finite output ({msg})"
    return {"case": case.id, "method": method, "tol": tol, "error": err, "wall_s": wall,
            "rhs_calls": rhs_calls, "steps": steps, "ok": bool(ok), "message": msg,
            "knob": "tol", **extra}


def run_ours(model, y0, t, method, tol, project):
    best = None
    for _ in range(REPEATS):
        r = integrate(model.model, model.p, y0, t, method=method, rtol=tol, atol=tol,
                      compensated=True, project_codes=model.integral_codes if project else ())
        if best is None or r.wall_s < best.wall_s:
            best = r
    return best


def scipy_fun(model, compiled):
    if compiled:
        d = np.empty(model.dim)

        def f(t, y):
            rhs(model.model, t, y, model.p, d)
            return d.copy()
        return f
    if model.case.constraint == "rubber":   # what simulate's scipy methods run
        from solvers.models import rubber_lagrange
        from solvers.models.rubber_bodies import from_vector

        body = from_vector(model.p)
        return lambda t, y: rubber_lagrange.field(body, y)
    return lambda t, y: ref_field(model.model, model.p, y)


def taylor_plan(tols):
    """(tol, precision) of the taylor runs: double down to 1e-14 (below, double stalls:
    taylor_backend.choose_precision), long double at TAYLOR_EXTENDED."""
    from solvers.integrate import taylor_backend as tb

    plan = [(tol, "double") for tol in tols if tol >= 1e-14]
    if "long double" in tb.precisions():
        plan += [(tol, "long double") for tol in TAYLOR_EXTENDED]
    return plan


def run_taylor(case, model, y0, t, Yref, tols) -> list[dict]:
    """The Taylor backend as simulate() runs it; the compile (first run) excluded."""
    from solvers.integrate import taylor_backend as tb

    runs = []
    for tol, prec in taylor_plan(tols):
        first = tb.run(model.model, model.p, y0, t, rtol=tol, precision=prec)
        best = min((tb.run(model.model, model.p, y0, t, rtol=tol, precision=prec)
                    for _ in range(REPEATS)), key=lambda r: r.wall_s)
        runs.append(_taylor_record(case, tol, prec, best, first, Yref))
    return runs


def _taylor_record(case, tol, prec, best, first, Yref):
    return _record(case, wp.TAYLOR, tol, best.y, Yref, best.wall_s, None, best.steps,
                   best.success, best.message, precision=prec,
                   order=best.extra["taylor_order"], compile_s=first.extra["compile_s"])


def run_auto_candidates(case, model, y0, t, Yref, tols) -> list[dict]:
    """method "auto"'s candidates (dop853, vern9, taylor) re-measured together, each
    tolerance's runs interleaved (dop853, vern9, taylor, dop853, ...), best of REPEATS:
    the same load for all three."""
    from solvers.integrate import taylor_backend as tb

    plan = taylor_plan(tols)
    firsts = {(tol, prec): tb.run(model.model, model.p, y0, t, rtol=tol, precision=prec)
              for tol, prec in plan}              # the compiles, excluded
    for method in wp.PLAIN:
        integrate(model.model, model.p, y0, t[:3], method=method, compensated=True)
    runs = []
    for tol in sorted({x for x in tols} | {tol for tol, _ in plan}, reverse=True):
        best = {}
        for _ in range(REPEATS):
            for method in wp.PLAIN:
                if tol not in tols:
                    continue
                r = integrate(model.model, model.p, y0, t, method=method, rtol=tol,
                              atol=tol, compensated=True)
                if method not in best or r.wall_s < best[method].wall_s:
                    best[method] = r
            for ptol, prec in plan:
                if ptol == tol:
                    r = tb.run(model.model, model.p, y0, t, rtol=tol, precision=prec)
                    if prec not in best or r.wall_s < best[prec].wall_s:
                        best[prec] = r
        for key, r in best.items():
            if key in wp.PLAIN:
                runs.append(_record(case, key, tol, r.y, Yref, r.wall_s, r.rhs_calls,
                                    r.steps, r.success, r.message, field=r.vector_field))
            else:
                runs.append(_taylor_record(case, tol, key, r, firsts[(tol, key)], Yref))
    return runs


def run_case(case: WPCase, tols, quick: bool, say, only_taylor=False) -> list[dict]:
    spec = registry()[case.id]
    model = build(case.id, {**spec.example, **case.overrides})
    y0 = initial_state(model, spec.state)
    t = np.linspace(0.0, case.t_end, SAMPLES)
    say(f"\n== {case.id}  T = {case.t_end:g}  {case.note}")

    t0 = time.perf_counter()
    ref = Taylor(model.model, model.p, y0, tol=1e-19, fp="longdouble", compact_mode=True)
    Yref, _, ref_wall, ref_steps, ok = ref.run(y0, t)
    assert ok, "reference failed"
    info = {"reference": "heyoka long double, tol 1e-19", "reference_wall_s": ref_wall,
            "reference_steps": ref_steps, "reference_order": ref.order}
    if not quick:
        q = Taylor(model.model, model.p, y0, tol=1e-24, fp="real128", compact_mode=True)
        Yq, _, q_wall, _, _ = q.run(y0, t)
        info["reference_check"] = ("heyoka real128, tol 1e-24: max difference "
                                   f"{np.max(np.abs(Yq - Yref)):.1e} ({q_wall:.1f} s)")
        info["reference_error_bound"] = float(np.max(np.abs(Yq - Yref)))
    say(f"reference: {info['reference']} ({time.perf_counter() - t0:.1f} s); "
        + info.get("reference_check", "real128 check skipped (--quick)"))

    if only_taylor:
        return run_auto_candidates(case, model, y0, t, Yref, tols), info
    runs = []
    # warm every path once (numba specializations, heyoka's JIT, scipy's first calls)
    integrate(model.model, model.p, y0, t[:3], method="vern9", compensated=True,
              project_codes=model.integral_codes)
    integrate(model.model, model.p, y0, t[:3], method="dop853", compensated=True)
    for compiled in (True, False):
        scipy_fun(model, compiled)(0.0, y0)
    # ours
    for method in ("dop853", "vern9"):
        for project in (False, True):
            name = method + ("+proj" if project else "")
            for tol in tols:
                r = run_ours(model, y0, t, method, tol, project)
                runs.append(_record(case, name, tol, r.y, Yref, r.wall_s, r.rhs_calls, r.steps,
                                    r.success, r.message, field=r.vector_field))
    # the symmetric method, constant steps
    integrate(model.model, model.p, y0, t[:3], method="gauss8", h_fixed=0.01)
    for h in (STEPS[:3] if quick else STEPS):
        r = min((integrate(model.model, model.p, y0, t, method="gauss8", h_fixed=h)
                 for _ in range(REPEATS)), key=lambda r: r.wall_s)
        runs.append(_record(case, "gauss8", h, r.y, Yref, r.wall_s, r.rhs_calls, r.steps,
                            r.success, r.message, knob="h"))
    # heyoka, float64
    compile_s = 0.0
    for tol in tols:
        h = Taylor(model.model, model.p, y0, tol=tol)
        compile_s += h.compile_s
        best = min((h.run(y0, t) for _ in range(REPEATS)), key=lambda x: x[2])
        Y, _, wall, steps, ok = best
        runs.append(_record(case, wp.HEYOKA, tol, Y, Yref, wall, None, steps, ok,
                            order=h.order))
    info["heyoka_compile_s"] = compile_s
    runs += run_taylor(case, model, y0, t, Yref, tols)
    # scipy
    for name, method, compiled in ((wp.SCIPY_NUMPY, "DOP853", False),
                                   (wp.SCIPY_COMPILED, "DOP853", True),
                                   ("scipy-LSODA/numba", "LSODA", True),
                                   ("scipy-Radau/numba", "Radau", True)):
        if quick and not compiled:
            continue
        skip = False
        for tol in (x for x in tols if x >= SCIPY_MIN_TOL):
            if skip:
                runs.append(_record(case, name, tol, None, Yref, None, None, None, False,
                                    "skipped: the previous tolerance took > BUDGET_S/3"))
                continue
            with np.errstate(all="ignore"), warnings.catch_warnings():
                warnings.simplefilter("ignore")   # scipy clips rtol < 2.2e-14 (said above)
                r = solve_ivp_reference(model.model, model.p, y0, t, method=method, rtol=tol,
                                        atol=tol, fun=scipy_fun(model, compiled))
            runs.append(_record(case, name, tol, r.y, Yref, r.wall_s, r.rhs_calls, None,
                                r.success and len(r.t) == len(t), r.message))
            skip = r.wall_s > BUDGET_S / 3
    return runs, info


def table(data) -> list[str]:
    summ = wp.summarise(data)
    lines = []
    refs = [wp.SCIPY_NUMPY, wp.SCIPY_COMPILED, "scipy-LSODA/numba", "scipy-Radau/numba",
            wp.HEYOKA]
    for case in data["cases"]:
        s = summ[case["id"]]
        lines.append(f"\n{case['id']}  (T = {case['t_end']:g}; default method from the "
                     f"front: {s['default_method']})")
        lines.append(f"{'error <=':>9s} {'ours: method':>18s} {'tol':>6s} {'wall ms':>8s} | "
                     + " ".join(f"{r.split('/')[0] + ('/np' if 'numpy' in r else ''):>13s}"
                                for r in refs))
        for row in s["table"]:
            o = row["ours"]
            knob = (f"{o['tol']:6.0e}" if o.get("knob", "tol") == "tol"
                    else f"h={o['tol']:.3g}".rjust(6)) if o else ""
            head = (f"{row['level']:9.0e} {o['method']:>18s} {knob} "
                    f"{o['wall_s'] * 1e3:8.2f} | ") if o else f"{row['level']:9.0e} {'-':>18s} " \
                f"{'':6s} {'':8s} | "
            cells = []
            for r in refs:
                ratio = row.get(f"ratio_{r}")
                ref = row.get(r)
                if r not in row:
                    cells.append(f"{'not run':>13s}")
                else:
                    cells.append(f"{ratio:12.1f}x" if ratio else
                                 (f"{'(no ours)':>13s}" if ref else f"{'not reached':>13s}"))
            lines.append(head + " ".join(cells))
    lines.append("\nratio = (reference's least wall time reaching the error) / (ours'); "
                 "'not reached': no run of that reference reached the error level")
    return lines


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--quick", action="store_true",
                    help="three tolerances, no NumPy-field scipy, no real128 check")
    ap.add_argument("--case", action="append", help="only these case ids")
    ap.add_argument("--only-taylor", action="store_true",
                    help="re-measure dop853, vern9 and taylor (auto's candidates) "
                         "interleaved and merge them into the committed JSON (the other "
                         "methods' runs are kept)")
    ap.add_argument("--cases", help="ID[,ID]: measure only these cases (every method), "
                                     "merged into the committed JSON, the others' runs kept")
    ap.add_argument("--table", action="store_true",
                    help="print the table of the committed JSON (nothing is run)")
    args = ap.parse_args(argv)
    if args.table:
        print("\n".join(table(wp.load_results())))
        return 0
    if args.only_taylor:
        return merge_taylor(args)
    if args.cases:
        return merge_cases(args)
    tols = (1e-6, 1e-10, 1e-14) if args.quick else TOLS
    cases = [c for c in CASES if not args.case or c.id in args.case]
    lines = []

    def say(s=""):
        print(s, flush=True)
        lines.append(s)

    t0 = time.perf_counter()
    warm = build("plane/chaplygin-ball", registry()["plane/chaplygin-ball"].example)
    integrate(warm.model, warm.p, np.array(registry()["plane/chaplygin-ball"].state), [0, 1])
    say(f"first call (numba cache load or compile): {time.perf_counter() - t0:.2f} s; "
        f"python {platform.python_version()}, {platform.machine()}")
    # the data file names its format and the command that wrote it (workprecision.FORMAT)
    data = {"format": wp.FORMAT, "generator": wp.GENERATOR + (" --quick" if args.quick else ""),
            "tolerances": list(tols), "samples": SAMPLES, "repeats": REPEATS, "cases": [],
            "runs": [], "quick": args.quick,
            "error": "max over the output grid of ‖y − y*‖∞ / max(1, max ‖y*‖∞), "
                     "y* the reference solution"}
    for case in cases:
        runs, info = run_case(case, tols, args.quick, say)
        data["cases"].append({"id": case.id, "overrides": case.overrides, "t_end": case.t_end,
                              "note": case.note, **info})
        data["runs"].extend(runs)
        for r in runs:
            say(run_line(r))
    lines_table = table(data)
    for s in lines_table:
        say(s)
    say(f"\ntotal {time.perf_counter() - t0:.0f} s")
    OUT.mkdir(exist_ok=True)
    suffix = "_quick" if args.quick else ""
    # the full run is what the explorer serves: package data next to its reader
    # (solvers.integrate.workprecision.RESULTS), so that an installed wheel carries it
    json_out = OUT / "work_precision_quick.json" if args.quick else wp.RESULTS
    json_out.write_text(json.dumps(data, indent=1, ensure_ascii=False) + "\n")
    (OUT / f"work_precision{suffix}.txt").write_text("\n".join(lines) + "\n")
    return 0


def merged(data: dict, case: WPCase, info: dict, runs: list[dict]) -> dict:
    """`data` with `case`'s entry and runs replaced (or added); the others' kept as they were."""
    entry = {"id": case.id, "overrides": case.overrides, "t_end": case.t_end,
             "note": case.note, **info}
    ids = [c["id"] for c in data["cases"]]
    cases = ([entry if c["id"] == case.id else c for c in data["cases"]]
             if case.id in ids else [*data["cases"], entry])
    return {**data, "cases": cases,
            "runs": [r for r in data["runs"] if r["case"] != case.id] + runs}


def pick_cases(ids: str) -> list[WPCase]:
    """The WPCases named in "ID[,ID]"; an unknown id is an error before anything runs."""
    known = {c.id: c for c in CASES}
    want = [x.strip() for x in ids.split(",") if x.strip()]
    bad = [x for x in want if x not in known]
    if bad or not want:
        raise SystemExit(f"--cases: unknown case id(s) {bad or ids!r}; the benchmark's "
                         f"cases: {', '.join(known)}")
    return [known[x] for x in want]


def merge_cases(args) -> int:
    """--cases: the named cases measured as the full run does (every method, every
    tolerance), merged into the committed JSON; the table is of the merged data."""
    import os

    cases = pick_cases(args.cases)
    data = json.loads(wp.RESULTS.read_text())
    wp.check_format(data, str(wp.RESULTS))
    tols = tuple(data["tolerances"])
    rerun = f"{wp.GENERATOR} --cases {','.join(c.id for c in cases)}"
    generator = data.get("generator", wp.GENERATOR)
    lines = []

    def say(s=""):
        print(s, flush=True)
        lines.append(s)

    t0 = time.perf_counter()
    for case in cases:
        load = round(os.getloadavg()[0], 1)
        runs, info = run_case(case, tols, False, say)
        for r in runs:
            r["load"] = load
        data = merged(data, case, {**info, "load": load}, runs)
        for r in runs:
            say(run_line(r))
    data = {**data, "format": wp.FORMAT, "generator": f"{generator}, then {rerun}"}
    for s in table(data):
        say(s)
    say(f"\ntotal {time.perf_counter() - t0:.0f} s (the cases above; load average at the "
        "start of each case in its entry's 'load')")
    wp.RESULTS.write_text(json.dumps(data, indent=1, ensure_ascii=False) + "\n")
    OUT.mkdir(exist_ok=True)
    (OUT / cases_log_name(cases)).write_text("\n".join(lines) + "\n")
    return 0


def cases_log_name(cases) -> str:
    """The log of a --cases run: one file per set of cases, kept by runs of others."""
    return "work_precision_cases_" + "+".join(c.id.replace("/", "-") for c in cases) + ".txt"


def run_line(r: dict) -> str:
    e = f"{r['error']:.1e}" if r["error"] is not None else "-"
    w = f"{r['wall_s'] * 1e3:.2f}" if r["wall_s"] is not None else "-"
    k = f"tol {r['tol']:.0e}" if r["knob"] == "tol" else f"h {r['tol']:>7.4g}"
    return (f"  {r['method']:20s} {k}  error {e:>8s}  wall {w:>9s} ms  "
            f"rhs {r['rhs_calls'] or '-'}  steps {r['steps'] or '-'}"
            + ("" if r["ok"] else f"  [{r['message'][:70]}]"))


def merge_taylor(args) -> int:
    import os

    data = json.loads(wp.RESULTS.read_text())
    wp.check_format(data, str(wp.RESULTS))
    rerun = f"{wp.GENERATOR} --only-taylor" + "".join(f" --case {c}" for c in args.case or ())
    generator = data.get("generator", wp.GENERATOR)
    data = {**data, "format": wp.FORMAT,
            "generator": generator if generator.endswith(rerun) else f"{generator}, then {rerun}"}
    tols = tuple(sorted({*data["tolerances"], *HALF_DECADES}, reverse=True))
    cases = [c for c in CASES if not args.case or c.id in args.case]
    renew = {wp.TAYLOR, *wp.PLAIN}
    load0 = os.getloadavg()[0]
    for case in cases:
        runs, _ = run_case(case, tols, True, print, only_taylor=True)
        data["runs"] = [r for r in data["runs"]
                        if not (r["case"] == case.id and r["method"] in renew)] + runs
        for r in runs:
            r["load"] = round(load0, 1)
    # the table of every case's re-measured runs (the cases not re-run keep theirs)
    lines = ["dop853, vern9 and the taylor backend, interleaved per case, merged into "
             f"{wp.RESULTS.name}; load average at the start of each case's measurement "
             "in brackets"]
    for c in data["cases"]:
        for r in (x for x in data["runs"] if x["case"] == c["id"] and x["method"] in renew):
            e = f"{r['error']:.1e}" if r["error"] is not None else "-"
            what = (f"taylor {r['precision']:11s}" if r["method"] == wp.TAYLOR
                    else f"{r['method']:18s}")
            extra = (f" order {r['order']:2d} compile {r['compile_s']:.1f} s"
                     if r["method"] == wp.TAYLOR
                     else f" rhs {r['rhs_calls']} {r.get('field', '')} field")
            lines.append(f"{c['id']:24s} {what} tol {r['tol']:.1e} error {e:>8s}"
                         f" wall {r['wall_s'] * 1e3:8.2f} ms" + extra
                         + (f" [{r['load']}]" if "load" in r else ""))
    wp.RESULTS.write_text(json.dumps(data, indent=1, ensure_ascii=False) + "\n")
    OUT.mkdir(exist_ok=True)
    (OUT / "work_precision_taylor.txt").write_text("\n".join(lines) + "\n")
    print("\n".join(lines))
    return 0


if __name__ == "__main__":
    sys.exit(main())
