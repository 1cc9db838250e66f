"""Run the checks of a teaching scene (catalogue/scenes.yaml) on the scene's own run
(the preset's `scene` declaration: case, parameters, state, t_end).

One function per check kind of solvers/scenes/teaching.py; each returns a CheckResult with the
measured value, so a failing scene says by how much, and the plot of exactly the data the
verdict was taken from (`plot`): /scenes draws it (GET /api/scenes/{id}/checks/{k}), so
what a class sees is what the test suite checked.
"""

from __future__ import annotations

from dataclasses import asdict, dataclass, field

import numpy as np

from solvers.kernels.integrals import ENERGY
from solvers.kernels.rk import model_integral
from solvers.maps.andoyer import map_point
from solvers.maps.map_analysis import correlation_dimension
from solvers.maps.poincare import MapSpec, map_model, trace_checked
from solvers.models.cases import build
from solvers.models.observables import RUBBER, spin_reversals, vertical_spin
from solvers.models.observables import series as observed
from solvers.scenes.teaching import load_scenes
from solvers.simulate import simulate

# what a reader calls each integral (the plot's legend); the keys are
# solvers/kernels/integrals.py NAMES
PRETTY = {
    "energy": "energy H", "area": "(M, γ)", "M2": "M²", "gamma2": "γ²",
    "jellett": "Jellett (M, r)", "routh": "Routh integral",
    "unbalanced_F": "M² − m r² (M, ω)", "borisov_fedorov": "Borisov–Fedorov (M, Aγ)",
    "gyro_M2": "(M+S)²", "gyro_area": "(M+S, γ)",
    **{n: label for n, (label, _f) in RUBBER.items()},
}


@dataclass(frozen=True)
class CheckResult:
    kind: str
    passed: bool
    value: float
    detail: str
    plot: dict | None = field(default=None, compare=False)

    def to_json(self) -> dict:
        return {k: (None if isinstance(v, float) and not np.isfinite(v) else v)
                for k, v in asdict(self).items()}


def _list(a) -> list:
    """Plot data for JSON: non-finite values (an exact zero's logarithm) as null."""
    return [float(v) if np.isfinite(v) else None for v in np.asarray(a, dtype=float)]


def _run(preset, samples=2001, which="main"):
    """The scene's run, or (which = "beside") the same run of the body beside it."""
    sc = preset.scene
    case = preset.beside.case if which == "beside" else sc.case
    return simulate(case, sc.params, sc.state, sc.t_end, samples=samples,
                    rtol=1e-11, atol=1e-13)


def _values(scene, res, names, which="main") -> dict:
    """The named quantities along the run: the kernels' integrals as the run reports them,
    the others (solvers/models/observables.py RUBBER) from its states."""
    case = scene.beside.case if which == "beside" else scene.scene.case
    other = [n for n in names if n not in res.invariants]
    extra = observed(build(case, scene.scene.params), res.state, other) if other else {}
    return {n: np.asarray(res.invariants[n] if n in res.invariants else extra[n], dtype=float)
            for n in names}


def _drift_series(v) -> np.ndarray:
    """|F(t) - F(0)| / max(|F(0)|, 1) at every sample after the first: the series whose
    maximum is SimResult.drift (the check's value)."""
    v = np.asarray(v, dtype=float)
    return np.abs(v[1:] - v[0]) / max(abs(v[0]), 1.0)


def check_integrals(scene, check, res=None) -> CheckResult:
    res = res or _run(scene)
    missing = [n for n in check.names if n not in res.invariants]
    if missing:
        return CheckResult("integrals", False, float("nan"),
                           f"the case does not carry {missing} with these parameters")
    drifts = {n: _drift_series(res.invariants[n]) for n in check.names}
    worst = max(float(d.max()) for d in drifts.values())
    ok = res.ok and worst <= check.tol
    t = res.t[1:]
    # exact zeros have no logarithm: left out of the log plot, not clipped to a floor
    traces = [{"name": PRETTY.get(n, n), "x": _list(t),
               "y": _list(np.where(d > 0, d, np.nan)), "role": "claim", "quantity": n}
              for n, d in drifts.items()]
    if res.state.shape[1] == 6:
        # a quantity the rolling does change, on the same scale, for contrast
        g3 = res.state[:, 5]
        traces.append({"name": "γ₃ (not conserved)", "x": _list(t),
                       "y": _list(_drift_series(g3)), "role": "contrast", "quantity": "g3"})
    traces.append({"name": f"bound of the check ({check.tol:g})", "x": [float(t[0]), float(t[-1])],
                   "y": [check.tol, check.tol], "role": "limit"})
    names = ", ".join(PRETTY.get(n, n) for n in check.names)
    plot = {"title": f"Numerical drift of {names}", "x_title": "time t",
            "y_title": "relative change", "log_y": True, "traces": traces,
            "cursor": {"axis": "t"},
            "headline": f"largest relative change {worst:.1e}"}
    return CheckResult("integrals", ok, worst, f"largest relative drift of "
                       f"{', '.join(check.names)} over t <= {res.t[-1]:g}: {worst:.2e}"
                       + ("" if res.ok else f" (run stopped: {res.message})"), plot)


def check_conserved(scene, check, res=None) -> CheckResult:
    """The integrals themselves against time on linear axes: flat lines beside gamma3,
    which moves; the verdict is that of check_integrals, taken from these values."""
    res = res or _run(scene, which=check.run)
    missing = [n for n in check.names if n not in res.invariants and n not in RUBBER]
    if missing:
        return CheckResult("conserved", False, float("nan"),
                           f"the case does not carry {missing} with these parameters")
    values = _values(scene, res, check.names, check.run)
    worst = max(float(_drift_series(v).max()) for v in values.values())
    ok = res.ok and worst <= check.tol
    t = res.t
    traces = [{"name": PRETTY.get(n, n), "x": _list(t), "y": _list(v), "role": "claim",
               "quantity": n} for n, v in values.items()]
    if res.state.shape[1] == 6:
        traces.append({"name": "γ₃ (not conserved)", "x": _list(t), "y": _list(res.state[:, 5]),
                       "role": "contrast", "quantity": "g3"})
    # the legend names the quantities; a short title reads on a projector
    plot = {"title": "Constant while the body rolls", "x_title": "time t",
            "y_title": "value", "log_y": False, "traces": traces, "cursor": {"axis": "t"},
            "headline": "flat lines: constant" if ok else "not constant"}
    return CheckResult("conserved", ok, worst, f"largest relative change of "
                       f"{', '.join(check.names)} over t <= {res.t[-1]:g}: {worst:.2e} "
                       f"(needs <= {check.tol:g})"
                       + ("" if res.ok else f" (run stopped: {res.message})"), plot)


def check_stays_up(scene, check, res=None) -> CheckResult:
    res = res or _run(scene)
    s = np.hypot(res.state[:, 3], res.state[:, 4])   # sin(angle of the axis to the vertical)
    low = float(s.min())
    ok = res.ok and low >= check.min_tilt
    # the same numbers as a tilt a class reads: the disk's plane against the vertical,
    # 90 deg - (axis to vertical) = arccos(sqrt(g1^2 + g2^2)); 90 deg is lying flat
    tilt = np.degrees(np.arccos(np.clip(s, 0.0, 1.0)))
    limit = float(np.degrees(np.arccos(check.min_tilt)))
    t = res.t
    plot = {"title": "Tilt of the disk from the vertical", "x_title": "time t",
            "y_title": "tilt (degrees)", "log_y": False,
            "y_range": [0, 90], "cursor": {"axis": "t"},
            "traces": [{"name": "tilt", "x": _list(t), "y": _list(tilt), "role": "claim",
                        "quantity": "tilt"},
                       {"name": f"bound of the check ({limit:.1f}°)",
                        "x": [float(t[0]), float(t[-1])], "y": [limit, limit],
                        "role": "limit"}],
            "headline": f"tilt {tilt.min():.1f}° … {tilt.max():.1f}°, bounded"}
    return CheckResult("stays_up", ok, low, f"min sqrt(g1^2 + g2^2) = {low:.4f} over "
                       f"t <= {res.t[-1]:g} (needs >= {check.min_tilt}): tilt at most "
                       f"{tilt.max():.1f} deg", plot)


def check_no_spin(scene, check, res=None, res_beside=None) -> CheckResult:
    """(omega, gamma) of both bodies against time: the rubber body's (beside) stays at zero
    within tol, the marble body's (the scene's own) leaves zero by marble_min."""
    res = res or _run(scene)
    res_beside = res_beside or _run(scene, which="beside")
    marble = _values(scene, res, ["spin"])["spin"]
    rubber = _values(scene, res_beside, ["spin"], "beside")["spin"]
    m_max, r_max = float(np.nanmax(np.abs(marble))), float(np.nanmax(np.abs(rubber)))
    ok = (res.ok and res_beside.ok and r_max <= check.tol and m_max >= check.marble_min
          and bool(np.all(np.isfinite(rubber))))
    b = scene.beside
    traces = [{"name": f"{b.main_label}", "x": _list(res.t), "y": _list(marble),
               "role": "contrast", "quantity": "spin", "run": "main"},
              {"name": f"{b.label}", "x": _list(res_beside.t), "y": _list(rubber),
               "role": "claim", "quantity": "spin", "run": "beside"}]
    plot = {"title": "Spin about the normal (ω, γ)", "x_title": "time t",
            "y_title": "(ω, γ)", "log_y": False, "traces": traces, "cursor": {"axis": "t"},
            "headline": (f"{b.label}: zero (|(ω, γ)| ≤ {r_max:.0e}); {b.main_label}: up to "
                         f"{m_max:.2f}")}
    stopped = [f"{name} run stopped: {r.message}" for name, r in
               ((b.main_label, res), (b.label, res_beside)) if not r.ok]
    return CheckResult("no_spin", ok, r_max, f"max |(omega, gamma)| of the {b.label}: "
                       f"{r_max:.2e} (needs <= {check.tol:g}); of the {b.main_label}: "
                       f"{m_max:.3g} (needs >= {check.marble_min:g})"
                       + "".join(f"; {m}" for m in stopped), plot)


def averaged(t, y, window: float) -> tuple[np.ndarray, np.ndarray]:
    """y averaged over a sliding `window`, at the window centres (as spin_reversals
    averages, solvers/models/observables.py)."""
    t = np.asarray(t, dtype=float)
    k = max(1, round(window / float(t[1] - t[0])))
    avg = np.convolve(np.asarray(y, dtype=float), np.ones(k) / k, mode="valid")
    return t[k // 2: k // 2 + len(avg)], avg


def check_spin_reversal(scene, check, res=None) -> CheckResult:
    res = res or _run(scene)
    model = build(scene.scene.case, scene.scene.params)
    spin = vertical_spin(model, res.state)
    times = spin_reversals(res.t, spin, check.window)
    first = times[0] if times else float("inf")
    ok = res.ok and first <= check.before
    ta, avg = averaged(res.t, spin, check.window)
    traces = [{"name": "spin", "x": _list(res.t), "y": _list(spin), "role": "raw",
               "quantity": "vertical_spin"},
              {"name": f"spin averaged over {check.window:g}", "x": _list(ta), "y": _list(avg),
               "role": "claim", "quantity": "vertical_spin"}]
    if times:
        traces.append({"name": f"reversal at t = {first:.1f}", "x": [first], "y": [0.0],
                       "role": "event"})
    plot = {"title": "Spin about the vertical", "x_title": "time t",
            "y_title": "spin −(ω, γ)", "log_y": False,
            "traces": traces,
            "vline": {"x": check.before, "name": f"check: before t = {check.before:g}"},
            "cursor": {"axis": "t"},
            "headline": (f"reverses at t = {first:.1f}" if times else "no reversal")}
    return CheckResult("spin_reversal", ok, first, f"first reversal of the averaged "
                       f"vertical spin at t = {first:.4g} (needs <= {check.before:g}); "
                       f"{len(times)} reversal(s) up to t = {res.t[-1]:g}", plot)


def check_map(scene, check) -> CheckResult:
    model = map_model(scene.scene.case, scene.scene.params)
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
        plot = {"title": f"{len(P)} returns to the section lie on a curve",
                "x_title": "l (angle, rad)", "y_title": "L/G", "log_y": False,
                "traces": [{"name": "returns (l, L/G)", "x": _list(P[:, 2]),
                            "y": _list(P[:, 0]),
                            "hg": _list(P[:, 1]), "role": "claim", "mode": "markers",
                            "quantity": "returns"}],
                "cursor": _map_track(scene),
                "headline": f"correlation dimension {d:.2f} (1 = a curve)"}
        return CheckResult("map", ok, d, f"correlation dimension of {len(P)} returns: "
                           f"{d:.3f} (a curve: 1 +- {check.dim_tol})", plot)
    k = check.period
    d = P[k:] - P[:-k]
    d[:, 2] = (d[:, 2] + np.pi) % (2 * np.pi) - np.pi
    dist = np.linalg.norm(d, axis=1)
    first, last = float(np.median(dist[:100])), float(np.median(dist[-100:]))
    ratio = first / max(last, 1e-300)
    ok = ratio >= check.factor and tr.check.get("missed", 0) == 0
    n = np.arange(len(dist))
    # linear axes: the distance falls to zero, which is what "settles" means; the cursor
    # stands at the last return before the animation's time
    plot = {"title": f"Returns approach a {k}-cycle", "x_title": "return n",
            "y_title": f"|x(n+{k}) − x(n)|", "log_y": False,
            "cursor": {"axis": "x", "t": _list(tr.t[:len(dist)]), "x": _list(n)},
            "traces": [{"name": f"|x(n+{k}) − x(n)|", "x": _list(n), "y": _list(
                np.where(dist > 0, dist, np.nan)), "role": "claim", "mode": "markers",
                "quantity": "cycle_distance"},
                {"name": "median of the first and last 100", "x": [50.0, float(n[-50])],
                 "y": [first, last], "role": "event"}],
            "headline": f"fell by {ratio:.1e}"}
    return CheckResult("map", ok, ratio, f"|x(n+{k}) - x(n)| fell by {ratio:.3g} from the "
                       f"first to the last 100 of {len(P)} returns (needs >= "
                       f"{check.factor:g}); map point of the start {map_point(y0).round(4)}",
                       plot)


def _map_track(scene) -> dict:
    """Where the body is now in the map's coordinates (l, L/G), along the scene's run at
    its animation frames: on the page a marker that moves with the 3D view and sits on
    the returns' curve each time the body crosses the section."""
    sc = scene.scene
    res = simulate(sc.case, sc.params, sc.state, sc.t_end, samples=sc.samples,
                   rtol=1e-10, atol=1e-12)
    P = map_point(res.state)
    return {"axis": "point", "t": _list(res.t), "x": _list(P[:, 2]), "y": _list(P[:, 0])}


_RUN_BASED = {"integrals": check_integrals, "conserved": check_conserved,
              "stays_up": check_stays_up,
              "spin_reversal": check_spin_reversal}


def _needs(check) -> tuple[str, ...]:
    """The runs a check reads: the scene's own ("main"), the body's beside, or none (map)."""
    if check.kind == "map":
        return ()
    if check.kind == "no_spin":
        return ("main", "beside")
    return (getattr(check, "run", "main"),)


def run_check(scene, check, runs: dict | None = None) -> CheckResult:
    """Check `check` of `scene`; `runs` ("main", "beside" -> a run) are reused, the
    missing ones computed (and added to it)."""
    runs = {} if runs is None else runs
    for which in _needs(check):
        if which not in runs:
            runs[which] = _run(scene, which=which)
    if check.kind == "map":
        return check_map(scene, check)
    if check.kind == "no_spin":
        return check_no_spin(scene, check, runs["main"], runs["beside"])
    return _RUN_BASED[check.kind](scene, check, runs[_needs(check)[0]])


def run_checks(scene) -> list[CheckResult]:
    """Every check of the scene (each run of the scene shared by the run-based checks)."""
    runs: dict = {}
    return [run_check(scene, c, runs) for c in scene.checks]


_runs: dict[str, dict] = {}


def check_json(scene_id: str, k: int) -> dict:
    """Check k of scene `scene_id` with its plot, for GET /api/scenes/{id}/checks/{k}
    (a worker process: the scene's runs are kept for its other checks)."""
    scene = load_scenes()[scene_id]
    check = scene.checks[k]
    runs = _runs.setdefault(scene_id, {})
    return {**run_check(scene, check, runs).to_json(), "caption": check.caption,
            "index": k, "count": len(scene.checks)}
