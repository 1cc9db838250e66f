"""The paper's 3D point maps (Figs ris-*1 .. ris-*4) recomputed and quantified.

    python bench/paper_figures.py     (about two minutes on one core)

Writes bench/results/paper_figures.txt (the numbers) and app/static/data/paper_figures.json
(the points, which the explorer's /poincare page draws as 3D scatter plots). The paper
gives the inertia of Fig ris-*1 only (I = (1, 2, 3)); every other parameter below is our
choice, stated with the figure. All runs: E0 = 1, section g = 0 crossed with g
increasing, DOP853 at rtol 1e-12, atol 1e-14, no projection onto the integrals.
"""

from __future__ import annotations

import json
import sys
import time
from pathlib import Path

import numpy as np

from solvers.maps.map_analysis import correlation_dimension, jacobian, log_det_series
from solvers.maps.poincare import MapSpec, map_model, poincare

ROOT = Path(__file__).resolve().parents[1]
TOL = {"rtol": 1e-12, "atol": 1e-14}
CHAPLYGIN = {"I1": 1.0, "I2": 2.0, "I3": 3.0, "m": 1.0, "R": 1.0}
UNBALANCED = {**CHAPLYGIN, "a1": -0.24, "a2": -0.09, "a3": -0.57}
ELLIPSOID = {"m": 1.0, "b1": 1.0, "b2": 2.0, "b3": 3.0, "mu": 1.0, "lambda": 0.0}
# starts (L/G, H/G, l) on the section; the unbalanced ball's were drawn with seed 6 and
# kept for what they show (see the text of each figure)
UB_ATTRACTED = (-0.7163524877143389, -0.851714459230827, 5.341909778560195)
UB_OTHERS = [(0.07251226779669206, -0.297785347354657, 2.318917858443646),
             (0.3312154679585378, -0.3230694347676293, 4.272048658717694)]
ELL_REGULAR = [(-0.407, -0.848, 2.409), (0.948, 0.29, 1.473), (0.336, -0.834, 3.491),
               (0.34, 0.703, 1.428), (-0.12, -0.564, 2.042), (0.013, 0.012, 1.484)]
ELL_LAYER = (-0.174, -0.864, 0.306)


def near_return(P, k):
    d = P[k:] - P[:-k]
    d[:, 2] = (d[:, 2] + np.pi) % (2 * np.pi) - np.pi
    return np.linalg.norm(d, axis=1)


def run(case, params, points, **kw):
    spec = MapSpec(energy=1.0, points=points, **TOL)
    t0 = time.perf_counter()
    res = poincare(case, params, spec, **kw)
    return res, spec, time.perf_counter() - t0


def describe(res, extra=None):
    rows = []
    for i, (tr, sp) in enumerate(zip(res.trajectories, res.integral_spread(), strict=True)):
        d = {"n": len(tr.points), "status": tr.status, "missed": tr.check.get("missed"),
             "extra": tr.check.get("extra"), **sp}
        if len(tr.points) > 50:
            d["D2"] = correlation_dimension(tr.points, 0.01, 0.1)
        if extra:
            d.update(extra[i])
        rows.append(d)
    return rows


def fmt(rows):
    keys = []
    for r in rows:
        keys += [k for k in r if k not in keys]
    out = ["  " + " ".join(f"{k:>13s}" for k in keys)]
    for r in rows:
        cells = []
        for k in keys:
            v = r.get(k, "")
            cells.append(f"{v:13.3e}" if isinstance(v, float) else f"{v!s:>13s}")
        out.append("  " + " ".join(cells))
    return "\n".join(out)


def mean_log_det(model, spec, P, n):
    ld = log_det_series(model, spec, P[:n])
    return float(np.nanmean(ld))


def fig1(text, data):
    res, spec, wall = run("plane/chaplygin-ball", CHAPLYGIN, 1000, trajectories=8, seed=1)
    model = map_model("plane/chaplygin-ball", CHAPLYGIN)
    extra = [{"mean_logdet": mean_log_det(model, spec, t.points, 100)} if i < 3 else {}
             for i, t in enumerate(res.trajectories)]
    rows = describe(res, extra)
    worst = max(r["H/G"] for r in rows)
    lines = [
        "Fig ris-*1  Chaplygin ball, I = (1, 2, 3), m = 1, R = 1 (D = m R^2 = 1), U = 0; "
        f"8 trajectories (seed 1) x 1000 points, {wall:.1f} s",
        "  claim: every trajectory lies on a joint level of H = (M, gamma) and M^2, so H/G "
        "is constant along it and the points lie on curves",
        fmt(rows),
        f"  largest spread of H/G on one trajectory: {worst:.2e} (absolute; the map "
        "coordinates span [-1, 1]); D2 ~ 1: curves.",
        "  mean log|det DP| over the first 100 returns (a measure exists: -> 0 like 1/n) "
        "is the control for Fig ris-*2/3.", ""]
    text += lines
    data["ris-1"] = pack(res, "Chaplygin ball, I = (1, 2, 3): joint levels of (M, γ) and M²",
                         lines)
    data["ris-1"]["finding"] = {
        "status": "confirmed", "statement": "the points lie on invariant curves",
        "found": f"H/G constant along each trajectory to {worst:.1e}; D2 ~ 1 (curves)"}


def fig23(text, data):
    res, spec, wall = run("plane/unbalanced-ball", UNBALANCED, 3000,
                          initial=[*UB_OTHERS, UB_ATTRACTED])
    model = map_model("plane/unbalanced-ball", UNBALANCED)
    extra = []
    for t in res.trajectories:
        d3 = near_return(t.points, 3)
        extra.append({"mean_logdet": mean_log_det(model, spec, t.points, 200),
                      "d3_first100": float(np.median(d3[:100])),
                      "d3_last100": float(np.median(d3[-100:]))})
    rows = describe(res, extra)
    att = res.trajectories[-1].points
    d3 = near_return(att, 3)
    n = np.arange(len(d3))
    fit = slice(200, len(d3))
    rate = float(np.polyfit(n[fit], np.log(np.maximum(d3[fit], 1e-300)), 1)[0])
    # multipliers of P^3 at the end of the attracted orbit (on the 3-cycle to ~1e-7)
    J = np.eye(3)
    for x in att[-3:]:
        Jx = jacobian(model, spec, x)
        J = Jx @ J
    mult = np.linalg.eigvals(J)
    pair = max(mult, key=lambda x: abs(x.imag))      # the complex pair (one of it)
    unit = min(mult, key=lambda x: abs(x - 1))      # the multiplier across the levels of F
    head = (
        "Figs ris-*2, ris-*3  unbalanced ball, I = (1, 2, 3), m = 1, R = 1, a = (-0.24, "
        f"-0.09, -0.57) (our choice), U = 0; 3 trajectories x 3000 points, {wall:.1f} s")
    lines = [
        head,
        "  claim: the points lie on surfaces F = M^2 - m r^2 (M, omega) = const (eq-d*2) "
        "and condense towards periodic solutions (no invariant measure)",
        fmt(rows),
        "  d3 = |x_{n+3} - x_n| (map coordinates): median over the first and the last 100 "
        "returns.", ""]
    # Fig ris-*2 (the paper's caption: one trajectory on a surface, from the top to three
    # points in its lower part): the last trajectory, the one that condenses
    fig2 = [
        head,
        "  claim (the caption): all points of one trajectory lie on a surface (a level of "
        "the integral F, eq-d*2); it leaves the top and approaches three points in the "
        "lower part (a periodic solution)",
        f"  on a level of F: the relative spread of F along the trajectory is "
        f"{rows[-1]['unbalanced_F']:.1e} over {rows[-1]['n']} returns (round-off of the "
        "integration): confirmed.",
        f"  three points: it approaches a 3-cycle (three points at H/G ~ {att[-1, 1]:.3f}); "
        f"the distance between returns n and n + 3 falls as exp({rate:.5f} n) after n = 200, "
        f"from {d3[0]:.2e} to {d3[-1]:.2e} at n = {len(d3)}: confirmed.",
        "  multipliers of the third iterate of the map at the cycle: "
        f"{pair.real:.6f} ± {abs(pair.imag):.6f}i and {unit.real:.6f} "
        f"(moduli {abs(pair):.6f} and {abs(unit):.6f}); their product "
        f"{np.prod(mult).real:.6f} < 1: volume contracts by that factor every 3 returns, "
        "which a map with an invariant measure cannot do on a 3-cycle (no measure, as the "
        "text says); the multiplier 1 is the direction across the levels of F.",
        f"  contraction per return on the cycle: {np.log(abs(np.prod(mult))) / 3:.5f}; the "
        f"approach rate the multipliers predict, {np.log(abs(pair)) / 3:.5f}, agrees with "
        f"the fitted rate {rate:.5f}.", ""]
    # Fig ris-*3 (the caption: three trajectories on two-dimensional surfaces, the levels
    # of F; the condensation is an approach to a periodic solution): all three
    others = rows[:-1]
    fig3 = [
        head,
        "  claim (the caption): the points of three trajectories lie on two-dimensional "
        "surfaces, the levels of the integral F (eq-d*2); the condensation of points is an "
        "asymptotic approach to a periodic solution",
        "  on levels of F: the relative spread of F along each trajectory is "
        + ", ".join(f"{r['unbalanced_F']:.1e}" for r in rows)
        + f" over {rows[0]['n']} returns each (round-off of the integration): confirmed.",
        "  two-dimensional: the two trajectories that do not condense have correlation "
        "dimension " + " and ".join(f"{r['D2']:.2f}" for r in others)
        + " (scales 0.01-0.1): each fills a surface, confirmed.",
        f"  condensation: one trajectory of three (the one of Fig ris-*2) condenses on a "
        f"3-cycle (median distance between returns n and n + 3 over the last 100 returns "
        f"{rows[-1]['d3_last100']:.1e}); the other two show no approach to a periodic "
        "solution within 3000 returns (the same median "
        + " and ".join(f"{r['d3_last100']:.2f}" for r in others) + ").",
        "  volume: the mean of log|det DP| over the first 200 returns of those two is "
        + " and ".join(f"{r['mean_logdet']:.1e}" for r in others)
        + ", as small as on the Chaplygin ball, which has a measure (Fig ris-*1): a "
        "contraction along them, if any, is not resolved by 200 returns; the 3-cycle of "
        "Fig ris-*2 is where the absence of a measure shows.", ""]
    text += lines + fig2[1:] + fig3[1:]
    data["ris-2"] = pack(res, "Unbalanced ball: one trajectory attracted to a 3-cycle",
                         fig2, only=[len(res.trajectories) - 1])
    data["ris-2"]["finding"] = {
        "status": "confirmed", "statement": "all points lie on some surface; the trajectory "
        "approaches three points in the lower part of the surface (a periodic solution)",
        "found": f"on a level of F to {rows[-1]['unbalanced_F']:.1e}; attracted to a 3-cycle "
                 f"whose multipliers contract volume by {np.prod(mult).real:.4f} every 3 "
                 "returns"}
    data["ris-3"] = pack(res, "Unbalanced ball: three trajectories on levels of the "
                         "integral eq-d*2", fig3)
    data["ris-3"]["finding"] = {
        "status": "confirmed", "statement": "the points lie on two-dimensional surfaces, the "
        "levels of the integral eq-d*2; the condensation is an approach to a periodic solution",
        "found": "on levels of F to " + ", ".join(f"{r['unbalanced_F']:.0e}" for r in rows)
                 + "; two of three fill surfaces (D2 " + ", ".join(
                     f"{r['D2']:.2f}" for r in others) + "); one condenses on a 3-cycle"}


def fig4(text, data):
    res, spec, wall = run("plane/ellipsoid", ELLIPSOID, 3000,
                          initial=[*ELL_REGULAR, ELL_LAYER])
    model = map_model("plane/ellipsoid", ELLIPSOID)
    extra = [{"mean_logdet": mean_log_det(model, spec, t.points, 100)}
             if i in (0, len(res.trajectories) - 1) else {}
             for i, t in enumerate(res.trajectories)]
    rows = describe(res, extra)
    layer = res.trajectories[-1].points
    d_small = correlation_dimension(layer, 0.003, 0.03)
    lines = [
        "Fig ris-*4  ellipsoid with spherical inertia I = mu E (lambda = 0 in eq2.29), mu "
        "= 1, m = 1, b = (1, 2, 3) (our choice), U = 0; 6 regular + 1 layer trajectory x "
        f"3000 points, {wall:.1f} s",
        "  claim: regular trajectories fill curves around stable permanent rotations; a "
        "chaotic layer (one trajectory) is not situated on any surface",
        fmt(rows),
        f"  regular: D2 ~ 1 (curves). Layer (last row): D2 = {rows[-1]['D2']:.2f} at "
        f"scales 0.01-0.1 and {d_small:.2f} at 0.003-0.03, spread of H/G "
        f"{rows[-1]['H/G']:.3f}: at this resolution the layer fills a two-dimensional "
        "set; the paper's 'not situated on any surface' is NOT confirmed by this number.",
        "  mean log|det DP| stays ~ 0 (the measure eq2.19/eq2.30 exists).", ""]
    text += lines
    data["ris-4"] = pack(res, "Ellipsoid with spherical inertia (λ = 0): invariant curves "
                         "and a chaotic layer", lines)
    # a 3D map's layer "not situated on any surface" would fill a 3D set (D2 ~ 3): what was
    # measured leans the other way, without deciding it (3000 points, two ranges of scale)
    data["ris-4"]["finding"] = {
        "status": "inconclusive", "leans": "against the paper",
        "statement": "A random layer (which is obtained from one trajectory) in this case is "
                     "not situated on any surface",
        "found": f"the layer's correlation dimension is {rows[-1]['D2']:.2f} at scales "
                 f"0.01-0.1 and {d_small:.2f} at 0.003-0.03 (a set filling the 3D map would "
                 "give about 3, a surface about 2): at this resolution the layer fills a "
                 "two-dimensional set, so the caption's 'not situated on any surface' is not "
                 f"confirmed; {len(layer)} returns of one trajectory, which does not decide it",
        "numbers": {"D2 (scales 0.01-0.1)": round(rows[-1]["D2"], 3),
                    "D2 (scales 0.003-0.03)": round(d_small, 3),
                    "spread of H/G along the layer": round(rows[-1]["H/G"], 4),
                    "returns": len(layer)}}


def pack(res, title, lines, only=None):
    """The figure for the explorer: its trajectories (at most 2000 points each) and, as
    notes, the claim and the numbers of the text report (the table rows left out)."""
    trs = res.trajectories if only is None else [res.trajectories[i] for i in only]
    notes = [ln.strip() for ln in lines[1:] if not ln.startswith("    ") and ln.strip()]
    return {"title": title, "notes": notes, "case": res.case, "params": res.params,
            "energy": res.spec.energy, "section": {"g0": res.spec.g0,
                                                   "direction": res.spec.direction},
            "trajectories": [{"initial": [round(v, 6) for v in t.initial],
                              "points": np.round(t.points[:2000], 5).tolist()}
                             for t in trs]}


def main():
    t0 = time.perf_counter()
    text = ["3D point maps of Borisov & Mamaev (2002), Figs ris-*1..ris-*4 (section 'Three-"
            "dimensional point maps', eq an-dp)",
            "map coordinates (L/G, H/G, l); spreads: (max - min)/|mean| over the points of "
            "one trajectory for the integrals, absolute for H/G; D2: correlation dimension "
            "(scales 0.01-0.1 of (L/G, H/G, l/pi)); missed/extra: the crossing check of "
            "solvers/maps/poincare.py", ""]
    data = {}
    fig1(text, data)
    fig23(text, data)
    fig4(text, data)
    text.append(f"total {time.perf_counter() - t0:.0f} s")
    out = "\n".join(text)
    print(out)
    (ROOT / "bench" / "results" / "paper_figures.txt").write_text(out + "\n")
    path = ROOT / "app" / "static" / "data" / "paper_figures.json"
    path.parent.mkdir(parents=True, exist_ok=True)
    # a versioned data file that names its generator; the explorer reads `figures`
    path.write_text(json.dumps({"format": 1, "generator": "python bench/paper_figures.py",
                                "figures": data}, separators=(",", ":")))


if __name__ == "__main__":
    if {"-h", "--help"} & set(sys.argv[1:]):     # what it does, without running it
        print(__doc__)
        sys.exit(0)
    main()
