"""3D point maps in Andoyer-Deprit variables (solvers/maps/andoyer.py, solvers/maps/poincare.py, the
nonlinear section of solvers/kernels/sections.py), `rolling poincare` and POST /api/poincare."""

import json

import numpy as np
import pytest
from typer.testing import CliRunner

from app.cli import cli
from solvers.errors import InputError
from solvers.kernels.integrals import ENERGY
from solvers.kernels.rk import model_integral, section_value
from solvers.kernels.sections import SECTION_ANDOYER_G, andoyer_g_value
from solvers.maps.andoyer import from_andoyer, g_angle, map_point, on_energy_level, to_andoyer
from solvers.maps.poincare import MapSpec, dense_check, map_model, poincare, trace

BALL = {"I1": 1.0, "I2": 2.0, "I3": 3.0, "m": 1.0, "R": 1.0}
UNBALANCED = {**BALL, "a1": -0.24, "a2": -0.09, "a3": -0.57}
ELLIPSOID = {"m": 1.0, "b1": 1.0, "b2": 2.0, "b3": 3.0, "mu": 1.0, "lambda": 0.0}


def test_andoyer_deprit_round_trip_and_printed_components():
    rng = np.random.default_rng(0)
    lam, h = rng.uniform(-0.99, 0.99, (2, 50))
    l, g = rng.uniform(0, 2 * np.pi, (2, 50))
    Y = from_andoyer(lam, h, l, g, 2.5)
    L, G, H, l2, g2 = to_andoyer(Y)
    assert np.allclose(G, 2.5, rtol=1e-14)
    assert np.allclose(L / G, lam, atol=1e-14) and np.allclose(H / G, h, atol=1e-13)
    assert np.allclose(np.angle(np.exp(1j * (l2 - l))), 0, atol=1e-12)
    assert np.allclose(np.angle(np.exp(1j * (g2 - g))), 0, atol=1e-12)
    assert np.allclose(np.linalg.norm(Y[:, 3:], axis=1), 1.0, atol=1e-15)
    # the components as printed in eq an-dp
    sL, sH = np.sqrt(1 - lam**2), np.sqrt(1 - h**2)
    a = h * sL + lam * sH * np.cos(g)
    printed = np.stack([a * np.sin(l) + sH * np.sin(g) * np.cos(l),
                        a * np.cos(l) - sH * np.sin(g) * np.sin(l),
                        h * lam - sL * sH * np.cos(g)], axis=1)
    assert np.allclose(Y[:, 3:], printed, atol=1e-15)
    assert np.allclose(Y[:, :3] / 2.5, np.stack([sL * np.sin(l), sL * np.cos(l), lam], 1))


def test_section_value_and_exact_gradient():
    rng = np.random.default_rng(1)
    for _ in range(20):
        y = from_andoyer(*rng.uniform(-0.9, 0.9, 2), *rng.uniform(0, 6.28, 2), 1.7)
        g0 = rng.uniform(-3, 3)
        coef = np.zeros(7)
        coef[:2] = np.cos(g0), np.sin(g0)
        grad = np.empty(6)
        s = section_value(SECTION_ANDOYER_G, y, coef, grad)
        assert s == pytest.approx(np.sin(g_angle(y) - g0), abs=1e-14)
        gc = np.empty(6, dtype=np.complex128)
        for i in range(6):   # complex step: exact to round-off
            yc = y.astype(np.complex128)
            yc[i] += 1e-30j
            d = andoyer_g_value(yc, coef.astype(np.complex128), gc).imag / 1e-30
            assert d == pytest.approx(grad[i], rel=1e-12, abs=1e-14)


def test_starts_lie_on_the_energy_level_and_the_section():
    model = map_model("plane/unbalanced-ball", UNBALANCED)
    for lam, h, l in [(0.1, -0.3, 1.0), (-0.8, 0.6, 4.0), (0.5, 0.5, 0.1)]:
        y = on_energy_level(model, lam, h, l, 0.7, 2.5)
        assert float(model_integral(ENERGY, model.model, y, model.p)) == pytest.approx(2.5,
                                                                                       rel=1e-13)
        assert np.allclose(map_point(y), [lam, h, l], atol=1e-13)
        assert g_angle(y) == pytest.approx(0.7, abs=1e-13)
    # a level below the potential has no point: InputError, nothing runs
    grav = map_model("plane/routh-ball", {"I1": 2, "I3": 3, "m": 1, "R": 1, "a": 0.3, "g": 1})
    with pytest.raises(InputError, match="potential"):
        poincare("plane/routh-ball", grav.params, MapSpec(energy=0.1), trajectories=2)


@pytest.mark.parametrize("direction", [1, -1, 0])
def test_crossings_are_on_the_section_in_the_asked_direction(direction):
    g0 = 0.4
    # g mostly increases: crossings with g decreasing are rare, so a step budget
    spec = MapSpec(energy=1.0, g0=g0, direction=direction, points=60, max_steps=300_000)
    res = poincare("plane/unbalanced-ball", UNBALANCED, spec, trajectories=2, seed=3)
    model = map_model("plane/unbalanced-ball", UNBALANCED)
    from solvers.kernels.fields import rhs

    for tr in res.trajectories:
        if direction >= 0:
            assert tr.status == "ok" and len(tr.points) == 60
        else:
            assert tr.status in ("ok", "budget") and len(tr.points) > 0
        assert tr.check["missed"] == 0 and tr.check["extra"] == 0
        g = g_angle(tr.states)
        assert np.max(np.abs(np.sin(g - g0))) < 1e-13          # located to round-off
        assert np.all(np.cos(g - g0) > 0)                         # not the branch g0 + pi
        gdot = []
        for y in tr.states:
            f = np.empty(6)
            rhs(model.model, 0.0, np.ascontiguousarray(y), model.p, f)
            grad = np.empty(6)
            coef = np.zeros(7)
            coef[:2] = np.cos(g0), np.sin(g0)
            section_value(SECTION_ANDOYER_G, np.ascontiguousarray(y), coef, grad)
            gdot.append(grad @ f)
        if direction:
            assert np.all(np.sign(gdot) == direction)
        E = [float(model_integral(ENERGY, model.model, np.ascontiguousarray(y), model.p))
             for y in tr.states]
        assert np.allclose(E, 1.0, rtol=1e-6, atol=0)   # drift of long runs at rtol 1e-10
        assert np.all(np.diff(tr.t) > 0)


def test_no_crossing_missed_against_an_independent_fine_sampling():
    """Count the crossings of g = g0 on a fine sampling of an independent scipy run over
    the same time span, on a trajectory that passes near the pole L/G = -1 (g fast)."""
    from scipy.integrate import solve_ivp

    from solvers.kernels.fields import rhs

    model = map_model("plane/ellipsoid", ELLIPSOID)
    spec = MapSpec(energy=1.0, points=80, rtol=1e-11, atol=1e-13)
    y0 = on_energy_level(model, -0.85, 0.3, 2.0, 0.0, 1.0)
    tr = trace(model, y0, spec)
    T = float(tr.t[-1])

    def f(_t, y):
        out = np.empty(6)
        rhs(model.model, 0.0, np.ascontiguousarray(y), model.p, out)
        return out

    t = np.linspace(0.0, T + 1e-9, 80 * 400 + 1)
    sol = solve_ivp(f, (0, t[-1]), y0, method="DOP853", rtol=1e-11, atol=1e-13, t_eval=t)
    kernel, dense, _, _, unresolved = dense_check(sol.t[1:], sol.y.T[1:], tr.t,
                                                  0.0, 1)
    assert unresolved == 0
    assert dense == len(tr.t) == kernel


def test_fast_turning_g_near_the_pole_gives_no_wild_crossing():
    """Near M along e3 the angle g turns by almost pi between two output samples; the
    kernel's step control keeps every located crossing on the trajectory."""
    model = map_model("plane/ellipsoid", ELLIPSOID)
    spec = MapSpec(energy=1.0, points=1000)
    from solvers.maps.poincare import sample_initial

    y0 = sample_initial(model, spec, 6, np.random.default_rng(2))[0]
    tr = trace(model, y0, spec)
    E = np.array([float(model_integral(ENERGY, model.model, np.ascontiguousarray(y), model.p))
                  for y in tr.states])
    assert np.ptp(E) < 1e-7
    assert np.allclose(np.linalg.norm(tr.states[:, 3:], axis=1), 1.0, atol=1e-8)
    assert tr.check["unresolved_intervals"] > 0      # the samples could not follow g here


def test_chaplygin_ball_points_keep_h_over_g():
    """Fig ris-*1: each trajectory on a joint level of (M, gamma) and M^2."""
    spec = MapSpec(energy=1.0, points=200, rtol=1e-12, atol=1e-14)
    res = poincare("plane/chaplygin-ball", BALL, spec, trajectories=3, seed=1)
    for tr, sp in zip(res.trajectories, res.integral_spread(), strict=True):
        assert sp["H/G"] < 1e-9 and sp["M_squared"] < 1e-9 and sp["area"] < 1e-9
        assert np.ptp(tr.points[:, 2]) > 1.0              # l moves: a curve, not a point


def test_unbalanced_ball_surface_and_condensation():
    """Figs ris-*2/3: the integral eq-d*2 is constant on the points, and the trajectory of
    bench/paper_figures.py condenses on a 3-cycle."""
    spec = MapSpec(energy=1.0, points=1500, rtol=1e-12, atol=1e-14)
    start = (-0.7163524877143389, -0.851714459230827, 5.341909778560195)
    res = poincare("plane/unbalanced-ball", UNBALANCED, spec, initial=[start])
    assert res.integral_spread()[0]["unbalanced_F"] < 1e-8
    P = res.trajectories[0].points
    d = P[3:] - P[:-3]
    d[:, 2] = (d[:, 2] + np.pi) % (2 * np.pi) - np.pi
    dist = np.linalg.norm(d, axis=1)
    assert np.median(dist[-100:]) < 1e-2 * np.median(dist[:100])   # ~650x at 1500 returns


def test_map_is_reproducible_with_a_seed():
    spec = MapSpec(energy=1.0, points=20)
    a = poincare("plane/chaplygin-ball", BALL, spec, trajectories=2, seed=5)
    b = poincare("plane/chaplygin-ball", BALL, spec, trajectories=2, seed=5)
    c = poincare("plane/chaplygin-ball", BALL, spec, trajectories=2, seed=6)
    assert np.array_equal(a.trajectories[1].points, b.trajectories[1].points)
    assert not np.array_equal(a.trajectories[1].points, c.trajectories[1].points)


def test_a_heavy_ball_where_lapack_calls_the_contact_inertia_singular_still_maps():
    # m = 1e16, R = 1: I_Q = I + m (E - gamma gamma^T) keeps the moment along gamma (~1)
    # below the round-off of the others (~1e16); LAPACK's LU finds an exact zero pivot at
    # some starts, the field's adjugate does not and runs. The rotation time that sizes the
    # pilot run is |omega| as the field computes it, so such a start is traced, not an error.
    heavy = {**BALL, "m": 1e16}
    spec = MapSpec(energy=1.0, points=5)
    res = poincare("plane/chaplygin-ball", heavy, spec, trajectories=4, seed=0)
    assert [t.status for t in res.trajectories] == ["ok"] * 4
    assert all(len(t.points) == 5 for t in res.trajectories)


def test_flat_base_cases_are_refused():
    with pytest.raises(InputError, match=r"\(M, gamma\)"):
        map_model("sphere/flat-base", {"I1": 1, "I2": 2, "I3": 3, "m": 1, "k": -0.5, "z": 0.3})


# --- command line -----------------------------------------------------------------------

runner = CliRunner()


def test_cli_json_has_trajectories_initial_and_points():
    r = runner.invoke(cli, ["poincare", "plane/chaplygin-ball", "--set", "I1=1", "--set", "I2=2",
                            "--set", "I3=3", "--set", "m=1", "--set", "R=1", "--energy", "2",
                            "--section", "g=0.5", "--trajectories", "2", "--points", "5",
                            "--json"])
    assert r.exit_code == 0, r.output
    d = json.loads(r.stdout.strip().splitlines()[-1])
    assert len(d["trajectories"]) == 2
    for t in d["trajectories"]:
        assert len(t["initial"]) == 3 and len(t["points"]) == 5
        assert all(len(p) == 3 for p in t["points"])
    assert d["section"] == {"g0": 0.5, "direction": 1} and d["energy"] == 2.0


def test_cli_given_starts_and_errors():
    r = runner.invoke(cli, ["poincare", "plane/chaplygin-ball", "--example", "--initial",
                            "0.2,0.3,1.0", "--points", "3", "--json"])
    assert r.exit_code == 0, r.output
    d = json.loads(r.stdout.strip().splitlines()[-1])
    assert d["trajectories"][0]["initial"] == pytest.approx([0.2, 0.3, 1.0], abs=1e-12)
    for bad in (["--section", "h=1"], ["--initial", "1.5,0,0"], ["--points", "0"]):
        r = runner.invoke(cli, ["poincare", "plane/chaplygin-ball", "--example", *bad])
        assert r.exit_code == 2 and "error:" in r.output


# --- API ---------------------------------------------------------------------------------

@pytest.mark.filterwarnings("ignore::DeprecationWarning")
def test_api_poincare_same_content_as_the_cli(patient_client):
    body = {"case": "plane/chaplygin-ball", "params": BALL, "energy": 2.0, "section": "g=0.5",
            "trajectories": 2, "points": 5}
    r = patient_client.post("/api/poincare", json=body)
    assert r.status_code == 200, r.text
    d = r.json()
    cli_out = runner.invoke(cli, ["poincare", "plane/chaplygin-ball", "--set", "I1=1",
                                  "--set", "I2=2", "--set", "I3=3", "--set", "m=1", "--set",
                                  "R=1", "--energy", "2", "--section", "g=0.5",
                                  "--trajectories", "2", "--points", "5", "--json"])
    c = json.loads(cli_out.stdout.strip().splitlines()[-1])
    assert [t["points"] for t in d["trajectories"]] == [t["points"] for t in c["trajectories"]]
    # streamed: progress events, then the same result
    r = patient_client.post("/api/poincare?stream=true", json=body)
    events = [json.loads(x) for x in r.text.strip().splitlines()]
    assert r.headers["content-type"].startswith("application/x-ndjson")
    assert [e["done"] for e in events if e["event"] == "progress"][-1] == 2
    assert events[-1]["event"] == "result"
    assert events[-1]["result"]["trajectories"][0]["points"] == d["trajectories"][0]["points"]


@pytest.mark.filterwarnings("ignore::DeprecationWarning")
def test_api_poincare_bad_input_is_422(patient_client):
    for body in ({"case": "sphere/flat-base", "example": True},
                 {"case": "plane/chaplygin-ball", "example": True, "section": "l=0"},
                 {"case": "plane/chaplygin-ball", "example": True, "points": 0},
                 {"case": "plane/chaplygin-ball", "example": True, "energy": -1.0}):
        r = patient_client.post("/api/poincare", json=body)
        assert r.status_code == 422, body
        assert r.json()["detail"]


@pytest.mark.filterwarnings("ignore::DeprecationWarning")
def test_poincare_page_and_figure_data(patient_client):
    assert patient_client.get("/poincare").status_code == 200
    r = patient_client.get("/static/data/paper_figures.json")
    assert r.status_code == 200
    data = r.json()
    assert data["format"] == 1 and data["generator"] == "python bench/paper_figures.py"
    figs = data["figures"]
    assert set(figs) == {"ris-1", "ris-2", "ris-3", "ris-4"}
    for f in figs.values():
        assert f["trajectories"] and f["notes"]
        assert all(len(p) == 3 for t in f["trajectories"] for p in t["points"])
