"""The marble-against-rubber teaching scene (catalogue/scenes.yaml `marble-against-rubber`) and
the rubber quantities it and the rubber case pages plot (solvers/models/observables.py):

  * the two runs start from the same (M, gamma), on the rubber manifold;
  * its checks pass, each on the values it plots: the rubber ball's (omega, gamma) stays at
    zero and the marble's does not; the marble keeps (M, gamma) and M^2, the rubber ball F;
  * and the rubber ball does NOT keep the marble's integrals (M, gamma) and M^2 (the scene's
    point: the invariants differ), while both keep F = M^2 - (M, gamma)^2;
  * moving the slider keeps the start on the rubber manifold, and the checks still pass;
  * a scene that declares checks on a body beside without one, or a state slider beside a
    rubber body, is refused;
  * POST /api/observables answers the named quantities, refuses bad input with a 422.
"""

import copy

import numpy as np
import pytest

from solvers.models.cases import build
from solvers.models.observables import (
    RUBBER,
    RUBBER_INTEGRALS,
    omega,
    rubber_integrals,
    series,
)
from solvers.scenes.rerun import moved
from solvers.scenes.scene_checks import _run, run_checks
from solvers.scenes.teaching import PATH, load_scenes, parse

SID = "marble-against-rubber"
SCENE = load_scenes()[SID]


def _rel_change(v):
    v = np.asarray(v, dtype=float)
    return float(np.max(np.abs(v - v[0])) / max(abs(v[0]), 1.0))


def test_both_bodies_start_from_the_same_state_on_the_rubber_manifold():
    sc = SCENE.scene
    assert SCENE.beside.case.startswith("rubber-plane/")
    for case in (sc.case, SCENE.beside.case):
        w = omega(build(case, sc.params), sc.state)[0]
        assert abs(w @ np.array(sc.state[3:6])) < 1e-14, case
        assert np.linalg.norm(w) > 0.5          # the balls do move


def test_every_check_passes_on_its_plotted_values():
    results = run_checks(SCENE)
    assert [r.kind for r in results] == [c.kind for c in SCENE.checks]
    for r, c in zip(results, SCENE.checks, strict=True):
        assert r.passed, r.detail
        traces = [t for t in r.plot["traces"] if t["role"] in ("claim", "contrast")]
        if c.kind == "no_spin":
            by_run = {t["run"]: np.array(t["y"], dtype=float) for t in traces}
            assert np.max(np.abs(by_run["beside"])) == r.value <= c.tol
            assert np.max(np.abs(by_run["main"])) >= c.marble_min
        else:
            claim = [t for t in traces if t["role"] == "claim"]
            assert [t["quantity"] for t in claim] == c.names
            assert max(_rel_change(t["y"]) for t in claim) == r.value <= c.tol


def test_the_invariants_differ_between_the_two_bodies():
    """The marble's integrals (M, gamma) and M^2 change along the rubber run, by far more than
    the checks' bound (1e-8); the rubber F = M^2 - (M, gamma)^2 (|gamma| = 1) holds along
    both runs, the marble's as a consequence of its two."""
    sc = SCENE.scene
    marble, rubber = _run(SCENE), _run(SCENE, which="beside")
    assert "spin" in rubber.invariants
    m_rubber = build(SCENE.beside.case, sc.params)
    area_r = np.sum(rubber.state[:, :3] * rubber.state[:, 3:6], axis=1)
    M2_r = np.sum(rubber.state[:, :3] ** 2, axis=1)
    assert _rel_change(area_r) > 1e-2 and _rel_change(M2_r) > 1e-2
    F_m = series(build(sc.case, sc.params), marble.state, ["rubber_ball_F"])["rubber_ball_F"]
    assert _rel_change(F_m) < 1e-8
    F_r = series(m_rubber, rubber.state, ["rubber_ball_F"])["rubber_ball_F"]
    assert _rel_change(F_r) < 1e-8


def test_the_slider_keeps_the_start_on_the_rubber_manifold_and_the_claim():
    s = moved(SCENE, {"I3": 2.4})
    assert s.scene.params["I3"] == 2.4
    assert s.scene.state[3:6] == SCENE.scene.state[3:6]
    w0 = omega(build(SCENE.scene.case, SCENE.scene.params), SCENE.scene.state)[0]
    w1 = omega(build(s.scene.case, s.scene.params), s.scene.state)[0]
    assert np.allclose(w0, w1, rtol=0, atol=1e-14)             # the same omega at the start
    assert s.scene.state[:3] != SCENE.scene.state[:3]          # a new M = I_Q omega
    first = run_checks(s)[0]
    assert first.kind == "no_spin" and first.passed, first.detail


@pytest.mark.parametrize("mutate, message", [
    (lambda sc: sc.pop("beside"), "needs `beside`"),
    (lambda sc: sc["sliders"].append({"name": "M1", "label": "the first component",
                                      "symbol": "M_1", "units": "1", "state": 0,
                                      "min": 0.0, "max": 3.0, "step": 0.1}),
     "parameter sliders only"),
    (lambda sc: sc["checks"][1].update(names=["not_a_quantity"]), "unknown integrals"),
])
def test_a_scene_beside_is_validated(mutate, message):
    import yaml

    raw = yaml.safe_load(PATH.read_text())
    sc = next(s for s in raw["scenes"] if s["id"] == SID)
    mutate(sc)
    with pytest.raises(ValueError, match=message):
        parse(copy.deepcopy(raw))


def test_the_rubber_integrals_of_each_case():
    assert rubber_integrals("rubber-plane/chaplygin-ball", {}) == ["rubber_ball_F"]
    assert rubber_integrals("rubber-plane/routh-ball", {"S3": 0.0}) == ["rubber_routh_F"]
    assert rubber_integrals("rubber-plane/routh-ball", {"S3": 0.5}) == []
    assert rubber_integrals("rubber-plane/unbalanced-ball", {}) == []
    # the ball's F is proved with a gyrostat or with a Brun field, not with both
    assert rubber_integrals("rubber-plane/chaplygin-ball", {"S1": 1.0, "eps": 0.1}) == []
    with pytest.raises(KeyError, match="known"):
        series(build("plane/chaplygin-ball", {"I1": 1, "I2": 2, "I3": 3, "m": 1, "R": 1}),
               np.zeros((1, 6)), ["nope"])
    assert {"spin", "gamma_norm_defect"} <= set(RUBBER)


@pytest.mark.filterwarnings("ignore::DeprecationWarning")
def test_observables_api(patient_client):
    from solvers.models.cases import get_case

    cid = "rubber-plane/routh-ball"
    spec = get_case(cid)
    res = _run_case(cid)
    body = {"case": cid, "params": {}, "state": res.state[::10].tolist()}
    r = patient_client.post("/api/observables", json=body)
    assert r.status_code == 200, r.text
    d = r.json()
    assert d["names"] == ["spin", "gamma_norm_defect", "rubber_routh_F"]
    assert max(abs(v) for v in d["series"]["spin"]) < 1e-8
    assert max(abs(v) for v in d["series"]["gamma_norm_defect"]) < 1e-8
    assert _rel_change(d["series"]["rubber_routh_F"]) < 1e-8
    assert spec.example["a"] != 0.0                 # the Routh ball is unbalanced here
    for bad, word in (({**body, "names": ["nope"]}, "nope"),
                      ({**body, "state": [[0.0] * 5]}, "state"),
                      ({**body, "case": "no/such"}, "case"),
                      ({**body, "params": {"I1": -1.0}}, "I1")):
        r = patient_client.post("/api/observables", json=bad)
        assert r.status_code == 422 and word in r.text, (bad, r.text)


def _run_case(cid):
    from solvers.models.cases import get_case
    from solvers.simulate import simulate

    spec = get_case(cid)
    return simulate(cid, spec.example, spec.state, 50.0, samples=501, rtol=1e-11, atol=1e-13)


@pytest.mark.parametrize("cid", sorted(RUBBER_INTEGRALS))
def test_each_rubber_integral_a_page_plots_is_constant_along_its_case(cid):
    """The integrals the rubber case pages plot (observables.RUBBER_INTEGRALS), along a run
    of the case's example: constant to 1e-8 (rtol 1e-11), while the state moves."""
    from solvers.models.cases import get_case

    spec = get_case(cid)
    names = rubber_integrals(cid, spec.example)
    assert names, cid
    res = _run_case(cid)
    assert res.ok, res.message
    got = series(build(cid, spec.example), res.state, [*names, "spin", "gamma_norm_defect"])
    for n in names:
        assert _rel_change(got[n]) < 1e-8, (cid, n, _rel_change(got[n]))
    assert np.max(np.abs(got["spin"])) < 1e-8 and np.max(np.abs(got["gamma_norm_defect"])) < 1e-8
    assert np.ptp(res.state[:, 5]) > 1e-3            # the body does move
