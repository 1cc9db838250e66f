"""The scene planner: the smallest model that serves what a scene shows, and its run.

Rules (`plan`), from what the scene declares (solvers/scenes/scenes.py):
  * the reduced system (gamma3, K1, K2, K3) of (2.6) (MODEL_REV_REDUCED, 4 equations
    instead of 6) when the case has one and the scene shows only time series of reduced
    variables (gamma3 = g3, K1, K2, K3);
  * the full state (M, gamma) otherwise: integral drift, sections, gamma's path and series
    of M or gamma need it;
  * the orientation and the centre of mass (MODEL_FULL_SCENE / MODEL_FLAT_SCENE, 18 or 17
    equations) only when the scene animates: the contact path needs them, nothing else does;
  * only as many output times as are plotted; integrals evaluated only for "drift";
  * dense output only when samples are plotted; a section alone needs no samples at all
    (its crossings are located inside the steps by Henon's trick), so its steps run free
    without the interpolant.
`full_plan` is what a view would run without a planner: the animation model with every
output (orientation and contact path, dense output, integrals, samples), the baseline of
bench/scenes.py.
"""

from __future__ import annotations

import time
from dataclasses import dataclass

import numpy as np

from solvers.integrate.integrator import IntegrationResult, Section, integrate
from solvers.kernels import layout as L
from solvers.kernels.fields import flat_kinematics, full_kinematics
from solvers.kernels.integrals import integral_series
from solvers.models.bodies import STATE_LABELS
from solvers.models.cases import Model, build, get_case, initial_state
from solvers.models.reduced_systems import to_reduced
from solvers.scenes.scenes import REDUCED_LABELS, Scene, has_reduced

E3 = np.array([0.0, 0.0, 1.0])
SCENE_MODEL = {L.MODEL_FULL: L.MODEL_FULL_SCENE, L.MODEL_FLAT: L.MODEL_FLAT_SCENE}


@dataclass(frozen=True)
class Plan:
    kind: str                 # "reduced" | "full" | "full+orientation"
    model: int                # kernel model code
    samples: int              # output times computed
    dense_output: bool
    integrals: bool           # evaluate the case's integrals along the samples
    reason: str

    def describe(self) -> dict:
        return {"kind": self.kind, "model": self.model, "dim": L.STATE_DIM[self.model],
                "samples": self.samples, "dense_output": self.dense_output,
                "integrals": self.integrals, "reason": self.reason}


def _base_model(scene: Scene) -> int:
    return L.MODEL_FLAT if get_case(scene.case).body == "flat" else L.MODEL_FULL


def plan(scene: Scene) -> Plan:
    """The smallest model and outputs that serve `scene` (module docstring)."""
    base = _base_model(scene)
    shows = scene.shows
    plotted = shows & {"series", "drift", "animation", "gamma_path"}
    samples = scene.samples if plotted else 2
    drift = "drift" in shows
    if "animation" in shows:
        return Plan("full+orientation", SCENE_MODEL[base], samples, True, drift,
                    "animation: orientation and contact path are integrated along")
    series_only = shows == {"series"}
    if series_only and has_reduced(scene.case) and \
            all(v in (*REDUCED_LABELS, "g3") for v in scene.series_names):
        return Plan("reduced", L.MODEL_REV_REDUCED, samples, samples > 2, False,
                    "series of reduced variables only: eq2-*1 in (gamma3, K1, K2, K3)")
    need = sorted(shows)
    return Plan("full", base, samples, samples > 2, drift,
                f"{', '.join(need)} need the full state; no orientation (not animated)")


def full_plan(scene: Scene) -> Plan:
    """The baseline: the animation model with every output, at the scene's samples."""
    base = _base_model(scene)
    return Plan("full+orientation", SCENE_MODEL[base], scene.samples, True, True,
                "baseline: everything computed whatever is shown")


# --- running a plan ------------------------------------------------------------------------
def rotation_taking(a, b) -> np.ndarray:
    """The smallest rotation R with R a = b (unit vectors), as solvers/models/kinematics.py."""
    a = np.asarray(a, float) / np.linalg.norm(a)
    b = np.asarray(b, float) / np.linalg.norm(b)
    v = np.cross(a, b)
    c = float(a @ b)
    if c < -1.0 + 1e-12:
        axis = np.cross(a, np.eye(3)[np.argmin(abs(a))])
        axis /= np.linalg.norm(axis)
        return 2.0 * np.outer(axis, axis) - np.eye(3)
    V = np.array([[0.0, -v[2], v[1]], [v[2], 0.0, -v[0]], [-v[1], v[0], 0.0]])
    return np.eye(3) + V + V @ V / (1.0 + c)


def _omega_r(model: Model, y):
    r, w = np.empty(3), np.empty(3)
    if model.model == L.MODEL_FLAT:
        flat_kinematics(model.p, np.ascontiguousarray(y[:5]), r, w)
        return w, r, E3
    J, gd = np.empty((3, 3)), np.empty(3)
    g = np.ascontiguousarray(y[3:6])
    full_kinematics(model.p, np.ascontiguousarray(y[:3]), g, r, J, w, gd)
    return w, r, g


def scene_initial(model: Model, y0) -> np.ndarray:
    """(state, Q0, x_G0) with the space frame of solvers/models/kinematics.py: Q0 gamma0 = -e_z,
    the contact point at the origin (plane) or at Q0 gamma0 / k (sphere)."""
    _, r0, g0 = _omega_r(model, y0)
    Q0 = rotation_taking(g0, -E3)
    k = float(model.p[L.CURV])
    xP0 = np.zeros(3) if k == 0.0 else Q0 @ g0 / k
    return np.concatenate([y0, Q0.ravel(), xP0 - Q0 @ r0])


@dataclass
class SceneRun:
    scene: Scene
    plan: Plan
    t: np.ndarray
    shown: dict              # what the scene shows, by kind
    status: str
    message: str
    stats: dict

    @property
    def ok(self) -> bool:
        return self.status == "ok"


def run(scene: Scene, the_plan: Plan | None = None) -> SceneRun:
    """Run `the_plan` (default: `plan(scene)`) and return what the scene shows."""
    pl = the_plan or plan(scene)
    case = get_case(scene.case)
    model = build(scene.case, {**case.example, **scene.params})
    y0 = initial_state(model, scene.state if scene.state is not None else case.state)
    n_base = model.dim
    t_out = np.linspace(0.0, scene.t_end, pl.samples)
    if pl.kind == "reduced":
        z0 = to_reduced(model.p, y0)
    elif pl.kind == "full+orientation":
        z0 = scene_initial(model, y0)
    else:
        z0 = y0
    section = None
    if scene.section is not None:
        labels = STATE_LABELS[model.model]
        coef = np.zeros(L.STATE_DIM[pl.model])
        coef[labels.index(scene.section.variable)] = 1.0
        section = Section(coef=tuple(coef), offset=scene.section.value,
                          direction=scene.section.direction)
    t0 = time.perf_counter()
    res = integrate(pl.model, model.p, z0, t_out, rtol=scene.rtol, atol=scene.atol,
                    compensated=True, dense_output=pl.dense_output, section=section,
                    max_crossings=scene.section.crossings if scene.section else 100_000)
    shown = _shown(scene, pl, model, res, n_base)
    wall = time.perf_counter() - t0
    status = "ok" if res.success else ("budget" if res.budget_exhausted else "singular")
    stats = {"steps": res.steps, "rhs_calls": res.rhs_calls, "wall_s": wall,
             "integrate_s": res.wall_s, "plan": pl.describe()}
    return SceneRun(scene, pl, res.t, shown, status, "" if res.success else res.message,
                    stats)


def _shown(scene: Scene, pl: Plan, model: Model, res: IntegrationResult, n: int) -> dict:
    out = {}
    Y = res.y
    if "series" in scene.shows:
        names = scene.series_names
        if pl.kind == "reduced":
            cols = {"gamma3": 0, "g3": 0, "K1": 1, "K2": 2, "K3": 3}
            out["series"] = {v: Y[:, cols[v]] for v in names}
        else:
            labels = STATE_LABELS[model.model]
            red = None
            if any(v in REDUCED_LABELS for v in names):
                red = np.array([to_reduced(model.p, y[:n]) for y in Y]).reshape(-1, 4)
            out["series"] = {v: (Y[:, labels.index(v)] if v in labels
                                 else red[:, REDUCED_LABELS.index(v)]) for v in names}
    if pl.integrals and len(Y):
        Ys = np.ascontiguousarray(Y[:, :n])
        drift = {}
        for name, code in zip(model.integral_names, model.integral_codes, strict=True):
            v = np.empty(len(Ys))
            integral_series(code, model.model, Ys, model.p, v)
            drift[name] = (v - v[0]) / max(abs(v[0]), 1.0)
        if "drift" in scene.shows or pl.kind == "full+orientation":
            out["drift"] = drift
    if "gamma_path" in scene.shows or pl.kind == "full+orientation":
        if model.model == L.MODEL_FULL:
            out["gamma_path"] = Y[:, 3:6]
    if scene.section is not None:
        out["section"] = res.crossings_y[:, :n]
        out["section_t"] = res.crossings_t
    if pl.kind == "full+orientation" and len(Y):
        Q = Y[:, n:n + 9].reshape(-1, 3, 3)
        xG = Y[:, n + 9:n + 12]
        contact = np.array([xg + q @ _omega_r(model, y)[1]
                            for xg, q, y in zip(xG, Q, Y, strict=True)])
        out["animation"] = {"Q": Q, "x_G": xG, "contact": contact}
    return out
