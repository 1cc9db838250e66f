"""Which extension of the plane Chaplygin ball's field off |gamma| = 1 integrates with the
smaller error (issue 19 item 4: the plane ball's worst start against the hand-written
limit).

The equations hold on |gamma| = 1; an integrator's stages leave it, so every field is some
extension of them off it, and the extensions agree on the manifold and differ off it.
Three, each as a scalar numba field in bench/limit.py's DOP853 (the same integrator, the
same controller):
  hand  the limit's hand-written field, as a user writes it for |gamma| = 1: r = c gamma,
        I_Q = I + m c^2 (E - gamma gamma^T) (|r|^2 taken as c^2), dr = c dgamma;
  gen   the project's generated field (generate.py, from the support function h = c
        |gamma|): r = c gamma / |gamma|, I_Q = I + m (|r|^2 E - r r^T); (M, gamma /
        |gamma|) then move independently of |gamma|;
  phys  a ball of radius c |gamma|: r = c gamma, I_Q = I + m (|r|^2 E - r r^T), the
        general formula with r = grad(c |gamma|^2 / 2).
Per body, random starts (gamma uniform on the sphere, |M| = (mean I + m c^2) * 0.25 *
10^U(-1, 1)), T = 1000, rtol = atol from 1e-5 to 1e-14 every half decade; the final-state
error (max-norm / max(1, |y|)) against heyoka's Taylor integrator in long double (tol
1e-18, the project's field: every extension's exact flow is the same from a start on the
manifold). Reported: the right-hand-side calls at matched errors 1e-6 and 1e-10 (log-log
interpolation on each front) of gen and phys over hand, median and range over the starts:
no clock, so the figures do not depend on the machine's load.

    PYTHONPATH=$PWD .venv/bin/python bench/ball_extension.py  -> bench/results/ball_extension.txt
"""

import os
import sys
from pathlib import Path

import numba
import numpy as np

ROOT = Path(__file__).resolve().parents[1]
sys.path[:0] = [str(ROOT), str(ROOT / "bench")]

import limit as B  # noqa: E402

from solvers.integrate.taylor import Taylor  # noqa: E402
from solvers.models.cases import build, registry  # noqa: E402

OUT = ROOT / "bench" / "results" / "ball_extension.txt"
CASE = "plane/chaplygin-ball"
BODIES = ((1.0, 2.0, 3.0), (0.01, 0.02, 0.025), (0.1, 0.2, 0.25), (1.0, 1.2, 1.5),
          (10.0, 20.0, 25.0))      # I1, I2, I3 with m = c = 1 (the first: the example)
STARTS = 12
T = 1000.0
RTOLS = [10.0 ** (-k / 2) for k in range(10, 29)]
TARGETS = (1e-6, 1e-10)


@numba.njit(inline="always")
def phys_s(p, M0, M1, M2, g0, g1, g2):
    """A ball of radius c |gamma|: I_Q = I + m c^2 (|gamma|^2 E - gamma gamma^T), r = c
    gamma: the hand-written field (bench/limit.py's ball_s, Cramer's solve) with |r|^2 =
    c^2 |gamma|^2 in place of c^2."""
    mc2 = p[3] * p[16] * p[16]
    return B.ball_of_diagonal(p, M0, M1, M2, g0, g1, g2, mc2 * (g1 * g1 + g2 * g2),
                              mc2 * (g0 * g0 + g2 * g2), mc2 * (g0 * g0 + g1 * g1))


def main() -> None:
    c = registry()[CASE]
    rng = np.random.default_rng(23)
    hand = B.make_scalar_dop853(B.HAND[CASE][0], 6)
    phys = B.make_scalar_dop853(phys_s, 6)
    load0 = os.getloadavg()
    lines = [f"bench/ball_extension.py: {CASE}, three extensions of its field off |gamma| = 1 "
             "in bench/limit.py's scalar DOP853 (module doc); calls at matched error over "
             f"hand's, median [min, max] over {STARTS} starts per body, T = {T:g}; "
             f"load average at the start: {load0[0]:.2f} {load0[1]:.2f} {load0[2]:.2f} "
             "(calls do not depend on it)"]
    for I in BODIES:
        prm = {**c.example, "I1": I[0], "I2": I[1], "I3": I[2]}
        model = build(CASE, prm)
        p = np.asarray(model.p, dtype=float)
        gen = B.make_scalar_dop853(*B._gen_field(model.model, p))
        scale = (sum(I) / 3.0 + float(prm["m"]) * float(p[16]) ** 2) * 0.25
        ratios = {k: {t: [] for t in TARGETS} for k in ("gen", "phys")}
        err_ratio = {k: [] for k in ("gen", "phys")}
        for _ in range(STARTS):
            d, g = rng.normal(size=3), rng.normal(size=3)
            y0 = np.concatenate([d / np.linalg.norm(d) * scale * 10.0 ** rng.uniform(-1, 1),
                                 g / np.linalg.norm(g)])
            ref = np.asarray(Taylor(model.model, p, y0, tol=1e-18, fp="longdouble")
                             .run(y0, [0.0, T])[1][-1], dtype=float)
            fronts = {}
            for k, f in (("hand", hand), ("gen", gen), ("phys", phys)):
                pts = []
                for rt in RTOLS:
                    y, _, calls = f(y0, p, T, rt, rt)
                    pts.append((float(np.max(np.abs(y - ref)) / max(1.0, np.max(np.abs(ref)))),
                                float(calls)))
                fronts[k] = pts
            for k in ("gen", "phys"):
                err_ratio[k] += [a[0] / b[0] for a, b in zip(fronts[k], fronts["hand"],
                                                              strict=True) if b[0] > 0]
                for t in TARGETS:
                    a, b = B.at_error(fronts[k], t), B.at_error(fronts["hand"], t)
                    if a and b:
                        ratios[k][t].append(a / b)
        parts = []
        for k in ("gen", "phys"):
            for t in TARGETS:
                v = ratios[k][t]
                parts.append(f"{k} {t:.0e}: " + (f"{np.median(v):.3f} [{min(v):.3f}, "
                                                 f"{max(v):.3f}] ({len(v)} matched)"
                                                 if v else "none matched"))
            parts.append(f"{k} error / hand's at the same rtol: median "
                         f"{np.median(err_ratio[k]):.2f}")
        lines.append(f"I = {I}: " + "; ".join(parts))
        print(lines[-1], flush=True)
    load1 = os.getloadavg()
    lines.append(f"load average at the end: {load1[0]:.2f} {load1[1]:.2f} {load1[2]:.2f}")
    OUT.write_text("\n".join(lines) + "\n")


if __name__ == "__main__":
    main()
