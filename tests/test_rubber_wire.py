"""The rubber cases through the solver stack: registered in solvers/models/cases.yaml
(constraint "rubber"), run by `simulate`, the CLI and POST /api/simulate, their compiled
fields (general and generated) against both NumPy derivations."""

import json
import subprocess
import sys

import numpy as np
import pytest

import solvers
from solvers.errors import InputError
from solvers.kernels import generate
from solvers.kernels import layout as L
from solvers.kernels.fields import rhs
from solvers.models import rubber_bodies as rb
from solvers.models import rubber_lagrange as rl
from solvers.models import rubber_newton as rn
from solvers.models.cases import build, registry, rubber_case_ids

RUBBER = rubber_case_ids()


def test_the_rubber_cases_are_registered():
    """Every rubber case of rubber_bodies.CASES is a registry case with the same body."""
    assert sorted(RUBBER) == sorted(rb.CASES)
    assert sum(cid.startswith("rubber-plane/") for cid in RUBBER) == 8
    for cid in RUBBER:
        spec = registry()[cid]
        assert spec.constraint == "rubber" and not spec.in_tables
        got = rb.from_vector(build(cid, spec.example).p)
        want = rb.body(cid)
        for name in ("I", "m", "k", "g", "eps", "S", "B", "c", "d", "a"):
            assert getattr(got, name) == pytest.approx(getattr(want, name), abs=1e-15), (cid, name)
    assert all(c.constraint == "marble" for cid, c in registry().items() if cid not in RUBBER)


@pytest.mark.parametrize("cid", RUBBER)
def test_example_state_lies_on_the_rubber_manifold(cid):
    spec = registry()[cid]
    y = np.array(spec.state)
    b = rb.body(cid)
    assert abs(np.linalg.norm(y[3:]) - 1.0) < 4 * L.EPS
    assert abs(rl.spin(b, y)) < 4 * L.EPS * max(1.0, np.linalg.norm(rl.omega(b, y)))
    model = build(cid, spec.example)
    assert model.integral_names == ("energy", "gamma2", "spin")
    assert model.p[L.RUBBER] == 1.0


def test_marble_cases_have_no_rubber_flag():
    for cid, spec in registry().items():
        if spec.constraint == "marble":
            assert build(cid, spec.example).p[L.RUBBER] == 0.0
            assert "spin" not in build(cid, spec.example).integral_names


def test_a_spinning_state_is_refused():
    spec = registry()["rubber-plane/chaplygin-ball"]
    marble_state = registry()["plane/chaplygin-ball"].state
    with pytest.raises(InputError, match=r"\(omega, gamma\) = .*does not spin"):
        solvers.simulate(spec.id, spec.example, marble_state, t_end=1.0)


def test_a_potential_on_a_sphere_is_refused():
    spec = registry()["rubber-sphere/ball-over"]
    with pytest.raises(InputError, match="unknown parameter g"):
        solvers.simulate(spec.id, {**spec.example, "g": 1.0}, spec.state, t_end=1.0)


def test_no_point_map_of_a_rubber_case():
    from solvers.maps.poincare import map_model

    spec = registry()["rubber-plane/chaplygin-ball"]
    with pytest.raises(InputError, match="rubber"):
        map_model(spec.id, spec.example)


def _points(cid, n, rng, on_manifold):
    """n states near the example: on the rubber manifold, or off it ((omega, gamma) != 0 and
    |gamma| != 1), where both derivations are still defined (the fields live on R^6)."""
    b = rb.body(cid)
    spec = registry()[cid]
    y0 = np.array(spec.state)
    out = []
    while len(out) < n:
        w = rl.omega(b, y0) + 0.5 * rng.standard_normal(3)
        g = y0[3:] + 0.3 * rng.standard_normal(3)
        if np.hypot(g[0], g[1]) < 0.2 * np.linalg.norm(g):   # keep away from a flat disk
            continue
        y = rl.state_on_manifold(b, w, g)
        if not on_manifold:
            y = y + 0.2 * rng.standard_normal(6)
        out.append(y)
    return out


def _generated_field(model):
    f = generate.generated(model.model, model.p).field

    def field(y):
        d = np.empty(6)
        assert f(model.p, np.ascontiguousarray(y), d) == L.OK
        return d
    return field


def _general_field(model):
    def field(y):
        d = np.empty(6)
        assert rhs(model.model, 0.0, np.ascontiguousarray(y), model.p, d) == L.OK
        return d
    return field


@pytest.mark.parametrize("on_manifold", [True, False], ids=["on", "off"])
@pytest.mark.parametrize("cid", RUBBER)
def test_compiled_fields_equal_both_derivations(cid, on_manifold):
    """The general compiled field (fields.rubber_reaction) and the generated one
    (generate._rubber_reaction) against Newton-Euler (rubber_newton) and
    Lagrange-d'Alembert (rubber_lagrange), at random points, to round-off."""
    spec = registry()[cid]
    extra = {"S1": 0.2, "S2": -0.1, "S3": 0.25, "eps": 0.3}
    model = build(cid, {**spec.example, **{k: v for k, v in extra.items()
                                           if k in spec.param_names}})
    b = rb.from_vector(model.p)
    compiled = {"general": _general_field(model), "generated": _generated_field(model)}
    rng = np.random.default_rng(7)
    for y in _points(cid, 20, rng, on_manifold):
        a = rl.field(b, y)
        c = rn.field(b, y)
        scale = np.max(np.abs(a))
        assert np.max(np.abs(a - c)) <= 1e-13 * scale
        for name, f in compiled.items():
            d = f(y)
            assert np.max(np.abs(d - a)) <= 1e-13 * scale, (name, y)
            assert np.max(np.abs(d - c)) <= 1e-13 * scale, (name, y)


def test_simulate_routes_name_their_field():
    """The scipy reference route runs the Lagrange-d'Alembert NumPy field; the compiled
    ones the generated (default) or general field, all holding the rubber constraint."""
    spec = registry()["rubber-plane/routh-ball"]
    runs = {m: solvers.simulate(spec.id, spec.example, spec.state, t_end=5.0, samples=11,
                                method=m, rtol=1e-11, atol=1e-13)
            for m in ("scipy-dop853", "dop853")}
    gen = runs["dop853"]
    ref = solvers.simulate(spec.id, spec.example, spec.state, t_end=5.0, samples=11,
                           rtol=1e-11, atol=1e-13, field="general")
    assert runs["scipy-dop853"].stats["field"] == "numpy"
    assert gen.stats["field"] == "generated" and ref.stats["field"] == "general"
    for r in (*runs.values(), ref):
        assert r.ok and list(r.invariants) == ["energy", "gamma_squared", "spin"]
        assert np.max(np.abs(r.invariants["spin"])) < 1e-9
    assert np.max(np.abs(gen.state - runs["scipy-dop853"].state)) < 1e-8
    assert np.max(np.abs(gen.state - ref.state)) < 1e-8


def test_cli_takes_a_rubber_case():
    proc = subprocess.run([sys.executable, "-m", "app.cli", "simulate",
                           "rubber-plane/chaplygin-ball", "--example", "--t-end", "5",
                           "--samples", "6", "--method", "scipy-dop853", "--json"],
                          capture_output=True, text=True, timeout=300)
    assert proc.returncode == 0, proc.stderr
    out = json.loads(proc.stdout)
    assert out["case"] == "rubber-plane/chaplygin-ball" and out["status"] == "ok"
    assert out["state"][0] == pytest.approx(registry()[out["case"]].state, abs=0)
    assert max(abs(v) for v in out["invariants"]["spin"]) < 1e-9


def test_api_takes_a_rubber_case():
    from fastapi.testclient import TestClient

    from app.main import create_app
    from app.testing import settings_for_tests

    with TestClient(create_app(settings_for_tests(max_steps=20_000))) as client:
        r = client.post("/api/simulate", json={"case": "rubber-sphere/ball-inside",
                                               "example": True, "t_end": 2.0, "samples": 5,
                                               "method": "scipy-dop853"})
        assert r.status_code == 200, r.text
        d = r.json()
        assert d["status"] == "ok" and "spin" in d["invariants"]
        assert max(abs(v) for v in d["invariants"]["spin"]) < 1e-9
        bad = client.post("/api/simulate", json={
            "case": "rubber-sphere/ball-inside", "t_end": 2.0,
            "params": registry()["rubber-sphere/ball-inside"].example,
            "state": registry()["plane/chaplygin-ball"].state})
        assert bad.status_code == 422, bad.text
        assert "does not spin" in bad.text


@pytest.mark.parametrize("kw", [dict(method="vern9"), dict(method="gauss4", step=0.02),
                                dict(method="taylor"), dict(method="auto"),
                                dict(method="dop853", project=True)],
                         ids=["vern9", "gauss4", "taylor", "auto", "projected"])
def test_every_kind_of_method_runs_the_rubber_field(kw):
    """Each route (small kernel, Gauss collocation, heyoka's Taylor integrator on the
    generated equations, auto, rk.py with projection) follows the scipy run of the
    Lagrange-d'Alembert field and keeps (omega, gamma) = 0."""
    spec = registry()["rubber-sphere/ball-inside"]
    ref = solvers.simulate(spec.id, spec.example, spec.state, t_end=10.0, samples=11,
                           method="scipy-dop853", rtol=1e-12, atol=1e-14)
    res = solvers.simulate(spec.id, spec.example, spec.state, t_end=10.0, samples=11,
                           **({"rtol": 1e-11, "atol": 1e-13} if "step" not in kw else {}), **kw)
    assert res.ok, res.message
    assert np.max(np.abs(res.invariants["spin"])) < 1e-9
    assert np.max(np.abs(res.state - ref.state)) < 1e-6
