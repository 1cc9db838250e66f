"""Scenes and the planner: the smallest model that serves a scene, showing the same thing
as the full model (the cost figures: bench/scenes.py, bench/results/scenes.txt)."""

import numpy as np
import pytest
from pydantic import ValidationError

from solvers.integrate.integrator import integrate
from solvers.kernels import layout as L
from solvers.models.cases import build, registry
from solvers.models.kinematics import scene as kinematics_scene
from solvers.scenes import planner
from solvers.scenes.scenes import Scene


def close(a, b, tol):
    a, b = np.asarray(a), np.asarray(b)
    assert a.shape == b.shape
    assert np.max(np.abs(a - b)) / max(1.0, np.max(np.abs(b))) < tol


# --- declarations ----------------------------------------------------------------------
def test_scene_declaration_is_validated():
    Scene(case="plane/round-disk", t_end=10, shows={"series"}, series=["gamma3", "K1"])
    with pytest.raises(ValidationError, match="not variables"):
        Scene(case="plane/chaplygin-ball", t_end=10, shows={"series"}, series=["K1"])
    with pytest.raises(ValidationError, match="section"):
        Scene(case="plane/chaplygin-ball", t_end=10, shows={"section"})
    with pytest.raises(ValidationError):
        Scene(case="plane/chaplygin-ball", t_end=10, shows=set())
    with pytest.raises(ValidationError):
        Scene(case="plane/chaplygin-ball", t_end=10, shows={"movie"})
    with pytest.raises(ValidationError):
        Scene(case="plane/chaplygin-ball", t_end=10, shows={"drift"}, frames=3)
    with pytest.raises(ValidationError, match="section variable"):
        Scene(case="sphere/flat-base", t_end=10, shows={"section"},
              section={"variable": "g3"})


# --- what the planner picks -------------------------------------------------------------------
@pytest.mark.parametrize(("kw", "kind", "model", "samples", "dense"), [
    ({"case": "plane/round-disk", "shows": {"series"}, "series": ["gamma3", "K2"]},
     "reduced", L.MODEL_REV_REDUCED, 301, True),
    ({"case": "sphere/routh-ball", "shows": {"series"}, "series": ["K1", "K3"]},
     "reduced", L.MODEL_REV_REDUCED, 301, True),
    ({"case": "plane/round-disk", "shows": {"series"}, "series": ["M1", "g3"]},
     "full", L.MODEL_FULL, 301, True),
    ({"case": "plane/round-disk", "shows": {"series", "drift"}, "series": ["gamma3"]},
     "full", L.MODEL_FULL, 301, True),
    ({"case": "plane/chaplygin-ball", "shows": {"drift"}}, "full", L.MODEL_FULL, 301, True),
    ({"case": "plane/chaplygin-ball", "shows": {"gamma_path"}}, "full", L.MODEL_FULL, 301,
     True),
    ({"case": "plane/chaplygin-ball", "shows": {"section"},
      "section": {"variable": "g3"}}, "full", L.MODEL_FULL, 2, False),
    ({"case": "plane/chaplygin-ball", "shows": {"animation", "drift"}}, "full+orientation",
     L.MODEL_FULL_SCENE, 301, True),
    ({"case": "sphere/flat-base", "shows": {"animation"}}, "full+orientation",
     L.MODEL_FLAT_SCENE, 301, True),
])
def test_planner_picks_the_smallest_model(kw, kind, model, samples, dense):
    pl = planner.plan(Scene(t_end=10.0, samples=301, **kw))
    assert (pl.kind, pl.model, pl.samples, pl.dense_output) == (kind, model, samples, dense)
    assert pl.integrals == ("drift" in kw["shows"])


# --- the planned model shows what the full one shows ---------------------------------------
SAME = [
    Scene(case="plane/round-disk", t_end=50.0, shows={"series"},
          series=["gamma3", "K1", "K2", "K3"], samples=101, rtol=1e-12, atol=1e-14),
    Scene(case="sphere/body-of-revolution", t_end=50.0, shows={"series"},
          series=["gamma3", "K1", "K2", "K3"], samples=101, rtol=1e-12, atol=1e-14),
    Scene(case="plane/unbalanced-ball", t_end=50.0, shows={"gamma_path", "series"},
          series=["M1", "g2"], samples=101, rtol=1e-12, atol=1e-14),
    Scene(case="sphere/flat-base", t_end=50.0, shows={"drift"}, samples=51, rtol=1e-12,
          atol=1e-14),
    Scene(case="sphere/chaplygin-ball", t_end=400.0, shows={"section"}, rtol=1e-12,
          atol=1e-14, section={"variable": "g3", "value": 0.1, "direction": -1,
                               "crossings": 10}),
]


@pytest.mark.parametrize("scene", SAME, ids=lambda s: f"{s.case}:{'+'.join(sorted(s.shows))}")
def test_planned_run_shows_what_the_full_model_shows(scene):
    a = planner.run(scene)
    b = planner.run(scene, planner.full_plan(scene))
    assert a.ok and b.ok, (a.message, b.message)
    for name, v in a.shown.get("series", {}).items():
        close(v, b.shown["series"][name], 1e-8)
    if "gamma_path" in scene.shows:
        close(a.shown["gamma_path"], b.shown["gamma_path"], 1e-8)
    if "section" in scene.shows:
        assert len(a.shown["section_t"]) == scene.section.crossings
        close(a.shown["section_t"], b.shown["section_t"], 1e-7)
        close(a.shown["section"], b.shown["section"], 1e-7)
    if "drift" in scene.shows:
        for name, v in a.shown["drift"].items():
            assert np.max(np.abs(v)) < 1e-11, name
    assert a.stats["rhs_calls"] <= b.stats["rhs_calls"] * 1.05 or a.plan.kind == "reduced"


# --- the animation model ---------------------------------------------------------------------
@pytest.mark.parametrize("case_id", ["plane/chaplygin-ball", "sphere/routh-ball",
                                     "sphere/flat-base", "plane/round-disk"])
def test_animation_model_matches_the_kinematics_module(case_id):
    """MODEL_FULL_SCENE / MODEL_FLAT_SCENE (compiled) against solvers/models/kinematics.py
    (scipy DOP853 on the same equations): orientation, centre of mass, contact path; Q
    stays a rotation and the contact point on the support."""
    c = registry()[case_id]
    sc = Scene(case=case_id, t_end=5.0, shows={"animation"}, samples=51, rtol=1e-12,
               atol=1e-14)
    a = planner.run(sc)
    assert a.ok
    k = kinematics_scene(case_id, c.example, c.state, 5.0, frames=51, rtol=1e-12,
                         atol=1e-14)
    anim = a.shown["animation"]
    close(anim["Q"].reshape(-1, 9), np.asarray(k["Q"]), 1e-8)
    close(anim["x_G"], np.asarray(k["x_G"]), 1e-8)
    close(anim["contact"], np.asarray(k["contact"]), 1e-8)
    Q = anim["Q"]
    assert np.max(np.abs(np.einsum("nji,njk->nik", Q, Q) - np.eye(3))) < 1e-9
    model = build(case_id, c.example)
    kk = model.p[L.CURV]
    P = anim["contact"]
    if kk == 0.0:
        assert np.max(np.abs(P[:, 2])) < 1e-9
    else:
        assert np.max(np.abs(np.linalg.norm(P, axis=1) - 1 / abs(kk))) < 1e-9


def test_scene_models_leave_the_body_field_unchanged():
    """The first 6 (5) components of the animation model are the body's own field."""
    c = registry()["plane/unbalanced-ball"]
    m = build("plane/unbalanced-ball", c.example)
    y0 = np.array(c.state)
    t = np.linspace(0.0, 20.0, 21)
    base = integrate(m.model, m.p, y0, t, rtol=1e-12, atol=1e-14)
    z0 = planner.scene_initial(m, y0)
    full = integrate(L.MODEL_FULL_SCENE, m.p, z0, t, rtol=1e-12, atol=1e-14)
    close(full.y[:, :6], base.y, 1e-9)
