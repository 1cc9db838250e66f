"""The tables of bench/auto_starts.py and the choice data it writes, from its raw figures
(one job: reading the raw runs; auto_starts.py runs them)."""

from __future__ import annotations

import json
import math
from pathlib import Path

import numpy as np
from auto_front import at_error

REF_MARGIN = 10.0     # a start is judged at level E where the reference's bound <= E / 10
DATA = Path(__file__).resolve().parents[1] / "solvers" / "integrate" / "data" / "auto_choice.json"
CHOICE_LEVELS = tuple(10.0 ** (-k / 2) for k in range(8, 29))     # 1e-4 ... 1e-14
METHODS = ("dop853", "vern9", "taylor")
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
