"""Run the checks of a teaching scene (catalogue/scenes.yaml) on the scene's own run
(the preset's `scene` declaration: case, parameters, state, t_end).

One function per check kind of catalogue/scenes.py; each returns a CheckResult with the
measured value, so a failing scene says by how much.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from solvers.models.cases import build
from solvers.simulate import simulate


@dataclass(frozen=True)
class CheckResult:
    kind: str
    passed: bool
    value: float
    detail: str


def _run(preset, samples=2001):
    sc = preset.scene
    return simulate(sc.case, sc.params, sc.state, sc.t_end, samples=samples,
                    rtol=1e-11, atol=1e-13)


def check_integrals(scene, check, res=None) -> CheckResult:
    res = res or _run(scene)
    missing = [n for n in check.names if n not in res.invariants]
    if missing:
        return CheckResult("integrals", False, float("nan"),
                           f"the case does not carry {missing} with these parameters")
    worst = max(res.drift(n) for n in check.names)
    ok = res.ok and worst <= check.tol
    return CheckResult("integrals", ok, worst, f"largest relative drift of "
                       f"{', '.join(check.names)} over t <= {res.t[-1]:g}: {worst:.2e}"
                       + ("" if res.ok else f" (run stopped: {res.message})"))


def check_stays_up(scene, check, res=None) -> CheckResult:
    res = res or _run(scene)
    tilt = np.hypot(res.state[:, 3], res.state[:, 4])
    low = float(tilt.min())
    ok = res.ok and low >= check.min_tilt
    return CheckResult("stays_up", ok, low, f"min sqrt(g1^2 + g2^2) = {low:.4f} over "
                       f"t <= {res.t[-1]:g} (needs >= {check.min_tilt})")


def check_spin_reversal(scene, check, res=None) -> CheckResult:
    from solvers.models.observables import spin_reversals, vertical_spin

    res = res or _run(scene)
    model = build(scene.scene.case, scene.scene.params)
    times = spin_reversals(res.t, vertical_spin(model, res.state), check.window)
    first = times[0] if times else float("inf")
    ok = res.ok and first <= check.before
    return CheckResult("spin_reversal", ok, first, f"first reversal of the averaged "
                       f"vertical spin at t = {first:.4g} (needs <= {check.before:g}); "
                       f"{len(times)} reversal(s) up to t = {res.t[-1]:g}")


def check_map(scene, check) -> CheckResult:
    from solvers.maps.andoyer import map_point
    from solvers.maps.map_analysis import correlation_dimension
    from solvers.maps.poincare import MapSpec, map_model, trace_checked

    model = map_model(scene.scene.case, scene.scene.params)
    from solvers.kernels.integrals import ENERGY
    from solvers.kernels.rk import model_integral

    y0 = np.asarray(scene.scene.state, dtype=float)
    E = float(model_integral(ENERGY, model.model, y0, model.p))
    spec = MapSpec(energy=E, g0=check.g0, points=check.points, rtol=1e-12, atol=1e-14)
    tr = trace_checked(model, y0, spec)
    P = tr.points
    if len(P) < check.points:
        return CheckResult("map", False, float(len(P)), f"only {len(P)} returns "
                           f"({tr.status}: {tr.message})")
    if check.expect == "curve":
        d = correlation_dimension(P, 0.01, 0.1)
        ok = abs(d - 1.0) <= check.dim_tol
        return CheckResult("map", ok, d, f"correlation dimension of {len(P)} returns: "
                           f"{d:.3f} (a curve: 1 +- {check.dim_tol})")
    k = check.period
    d = P[k:] - P[:-k]
    d[:, 2] = (d[:, 2] + np.pi) % (2 * np.pi) - np.pi
    dist = np.linalg.norm(d, axis=1)
    ratio = float(np.median(dist[:100]) / max(np.median(dist[-100:]), 1e-300))
    ok = ratio >= check.factor and tr.check.get("missed", 0) == 0
    return CheckResult("map", ok, ratio, f"|x(n+{k}) - x(n)| fell by {ratio:.3g} from the "
                       f"first to the last 100 of {len(P)} returns (needs >= "
                       f"{check.factor:g}); map point of the start {map_point(y0).round(4)}")


def run_checks(scene) -> list[CheckResult]:
    """Every check of the scene (one run of the scene shared by the run-based checks)."""
    res = None
    out = []
    for c in scene.checks:
        if c.kind == "map":
            out.append(check_map(scene, c))
            continue
        res = res or _run(scene)
        fn = {"integrals": check_integrals, "stays_up": check_stays_up,
              "spin_reversal": check_spin_reversal}[c.kind]
        out.append(fn(scene, c, res))
    return out
