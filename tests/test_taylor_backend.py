"""method "taylor" (solvers/integrate/taylor_backend.py) and method "auto"
(solvers/integrate/auto.py): heyoka's Taylor integrator on the lean generated field as a
runtime backend of simulate(), in double, long double and quad."""

from __future__ import annotations

import sys

import numpy as np
import pytest

from solvers.errors import InputError
from solvers.integrate import taylor_backend as tb
from solvers.models.cases import build, initial_state, registry
from solvers.simulate import simulate

pytest.importorskip("heyoka")

CASES = ("plane/chaplygin-ball", "plane/round-disk", "sphere/chaplygin-ball",
         "sphere/flat-base")


def _demo(cid):
    spec = registry()[cid]
    return spec.example, spec.state


def _reference(cid, t, tol=1e-19, fp="longdouble"):
    """The independent heyoka system of solvers/integrate/taylor.py (general support
    function, heyoka's own differentiation) in extended precision."""
    from solvers.integrate.taylor import Taylor

    params, state = _demo(cid)
    model = build(cid, params)
    y0 = initial_state(model, state)
    ref = Taylor(model.model, model.p, y0, tol=tol, fp=fp, compact_mode=True)
    Y, _, _, _, ok = ref.run(y0, t)
    assert ok
    return Y


@pytest.mark.parametrize("cid", CASES)
def test_taylor_agrees_with_the_kernels_and_the_long_double_reference(cid):
    params, state = _demo(cid)
    T, rtol = 20.0, 1e-12
    r = simulate(cid, params, state, T, method="taylor", rtol=rtol, samples=41)
    rk = simulate(cid, params, state, T, method="vern9", rtol=1e-13, atol=1e-15, samples=41)
    assert r.ok and rk.ok, (r.message, rk.message)
    assert r.stats["method"] == "taylor" and r.stats["precision"] == "double"
    Yref = _reference(cid, r.t)
    scale = max(1.0, float(np.abs(Yref).max()))
    err = float(np.abs(r.state - Yref).max()) / scale
    # tol bounds the local error of each step (~1 per time unit here); over T time units
    # the global error may grow like T * tol, with the conditioning of the flow on top
    assert err < 50 * T * rtol, err
    assert float(np.abs(r.state - rk.state).max()) / scale < 50 * T * rtol


def test_invariants_hold_to_about_rtol_along_a_run():
    params, state = _demo("plane/chaplygin-ball")
    for rtol in (1e-8, 1e-12):
        r = simulate("plane/chaplygin-ball", params, state, 100.0, method="taylor",
                     rtol=rtol, samples=401)
        assert r.ok
        assert set(r.stats["drift"]) == set(r.invariants) >= {"energy", "gamma_squared"}
        # the integrals are not built into the method: they drift with the error, which
        # grows with the run (100 time units, ~100 steps)
        assert max(r.stats["drift"].values()) < 100 * rtol, r.stats["drift"]


def test_disk_falling_flat_stops_singular_without_nan():
    d = {"I1": 0.25, "I3": 0.5, "m": 1, "R": 1, "g": 9.81}
    y0 = [0, 0, 0, 0.05, 0, 0.99874921777190895]
    r = simulate("plane/round-disk", d, y0, 5.0, method="taylor", rtol=1e-10)
    k = simulate("plane/round-disk", d, y0, 5.0, method="dop853", rtol=1e-10)
    assert r.status == k.status == "singular"
    assert "disk lies flat" in r.message and "stopped at t =" in r.message
    assert np.isfinite(r.state).all() and all(np.isfinite(v).all() for v in r.invariants.values())
    t_taylor = float(r.message.split("t = ")[1].rstrip(")"))
    t_rk = float(k.message.split("t = ")[1].rstrip(")"))
    assert abs(t_taylor - t_rk) < 1e-6          # the same instant (event vs step test)
    assert len(r.t) == len(k.t)


def test_body_reaching_the_fit_limit_stops_singular():
    """An oblate body of revolution (b1 = 1, b3 = 0.5) inside a sphere with k = 0.9: it
    fits near its equator (radius of curvature 1) but not near its pole (2)."""
    ex = registry()["sphere/body-of-revolution"].example
    y0 = [0, 2.0, 0, np.sqrt(1 - 0.09), 0.0, 0.3]
    r = simulate("sphere/body-of-revolution", {**ex, "k": 0.9}, y0, 1.0, method="taylor",
                 rtol=1e-10, samples=21)
    assert r.status == "singular" and "no longer fits the sphere" in r.message
    assert np.isfinite(r.state).all() and len(r.t) == 4      # samples 0, 0.05, 0.1, 0.15
    t_stop = float(r.message.split("t = ")[1].rstrip(")"))
    assert abs(t_stop - 0.16197941718797265) < 1e-6          # where dop853 stops


def test_step_budget():
    params, state = _demo("plane/chaplygin-ball")
    r = simulate("plane/chaplygin-ball", params, state, 1000.0, method="taylor",
                 rtol=1e-10, max_steps=50)
    assert r.status == "budget" and "step budget" in r.message
    assert r.stats["steps"] <= 50 and 1 < len(r.t) < 201
    assert np.isfinite(r.state).all()


def test_wall_limit_stops_the_run():
    params, state = _demo("plane/round-disk")
    model = build("plane/round-disk", params)
    y0 = initial_state(model, state)
    r = tb.run(model.model, model.p, y0, np.linspace(0, 1e6, 11), rtol=1e-10,
               precision="double", wall_limit=0.0)
    assert r.budget_exhausted and "wall-time limit" in r.message


@pytest.mark.slow
def test_extended_precision_reaches_below_1e_14_where_double_cannot():
    """Chaplygin ball, T = 1000, against heyoka in real128 (quad) at tol 1e-24 on the
    independent general system: double stalls above 1e-14 even at tol 1e-16, long double
    goes below."""
    cid = "plane/chaplygin-ball"
    params, state = _demo(cid)
    t = np.linspace(0.0, 1000.0, 21)
    Yq = _reference(cid, t, tol=1e-24, fp="real128")
    errs = {}
    for prec in ("double", "long double"):
        r = simulate(cid, params, state, 1000.0, method="taylor", rtol=1e-16,
                     precision=prec, samples=21)
        assert r.ok and r.stats["precision"] == prec
        assert r.state.dtype == np.float64
        errs[prec] = float(np.abs(r.state - Yq).max())
    assert errs["double"] > 1e-14, errs
    assert errs["long double"] < 1e-14, errs


def test_precision_is_chosen_from_rtol_and_the_length_of_the_run():
    assert tb.choose_precision(1e-10, 1000.0) == "double"
    assert tb.choose_precision(1e-14, 1000.0) == "double"          # floor 7e-15
    assert tb.choose_precision(1e-15, 1000.0) == "long double"
    assert tb.choose_precision(1e-15, 1.0) == "double"
    assert tb.choose_precision(1e-16, 1.0) == "long double"
    assert tb.choose_precision(1e-16, 1e4) == "long double"         # floor 1.1e-17
    assert "double" in tb.precisions()
    for prec in tb.precisions():
        assert tb.floor(prec, 1000.0) < tb.floor(prec, 1e5)


@pytest.fixture
def empty_disk(tmp_path, monkeypatch):
    """An empty disk cache of compiled integrators (taylor_backend.disk_dir), so that a
    cleared process cache means a compile."""
    monkeypatch.setattr(tb, "disk_dir", lambda: tmp_path)
    tb.clear_cache()
    yield tmp_path
    tb.clear_cache()


def test_the_compile_cache_serves_other_values_of_the_same_structure(empty_disk):
    params, state = _demo("plane/chaplygin-ball")
    before = tb.COMPILES[0]
    r1 = simulate("plane/chaplygin-ball", params, state, 10.0, method="taylor", rtol=1e-9)
    assert tb.COMPILES[0] == before + 1 and r1.stats["compiled"]
    r2 = simulate("plane/chaplygin-ball", {**params, "I2": 2.5}, state, 10.0,
                  method="taylor", rtol=1e-9)
    assert tb.COMPILES[0] == before + 1 and not r2.stats["compiled"]
    assert r2.stats["compile_s"] == 0.0
    assert not np.allclose(r1.state, r2.state)          # the new values were used
    again = simulate("plane/chaplygin-ball", params, state, 10.0, method="taylor", rtol=1e-9)
    np.testing.assert_array_equal(again.state, r1.state)
    assert tb.COMPILES[0] == before + 1
    # the compiled tol: the largest quarter decade <= rtol (never looser than asked)
    assert tb.snap_tol(1e-9) == 1e-9 and tb.snap_tol(8e-10) == pytest.approx(10 ** -9.25)
    r3 = simulate("plane/chaplygin-ball", params, state, 10.0, method="taylor", rtol=1.5e-9)
    assert tb.COMPILES[0] == before + 1 and r3.stats["tol"] == 1e-9


def test_a_new_process_loads_the_integrator_from_disk_with_the_same_bits(empty_disk):
    """heyoka keeps compiled code per process (and in its own disk cache, where a new
    process still rebuilds the expressions and the Taylor decomposition): taylor_backend
    stores the integrator, so that another worker (the explorer's prepare job compiles in
    one, the request may run in another) loads it instead of compiling (issue 19)."""
    params, state = _demo("plane/round-disk")       # two events: they travel too
    first = simulate("plane/round-disk", params, state, 5.0, method="taylor", rtol=1e-10)
    assert first.stats["compiled"] and first.stats["integrator_cache"] is None
    assert len(list(empty_disk.glob("*.pkl"))) == 1
    tb.clear_cache()                                 # what a new process has in memory
    before = tb.COMPILES[0]
    again = simulate("plane/round-disk", params, state, 5.0, method="taylor", rtol=1e-10)
    assert tb.COMPILES[0] == before and not again.stats["compiled"]
    assert again.stats["integrator_cache"] == "disk" and again.stats["load_s"] > 0
    assert again.state.tobytes() == first.state.tobytes()
    model = build("plane/round-disk", params)
    assert tb.ready(model.model, model.p, "double", 1e-10)
    assert not tb.ready(model.model, model.p, "long double", 1e-10)


def test_a_damaged_stored_integrator_is_compiled_again(empty_disk):
    params, state = _demo("plane/chaplygin-ball")
    simulate("plane/chaplygin-ball", params, state, 1.0, method="taylor", rtol=1e-8)
    (stored,) = empty_disk.glob("*.pkl")
    stored.write_bytes(b"not a pickle")
    tb.clear_cache()
    r = simulate("plane/chaplygin-ball", params, state, 1.0, method="taylor", rtol=1e-8)
    assert r.ok and r.stats["compiled"]
    assert stored.read_bytes() != b"not a pickle"      # replaced by the new compile


def test_the_cache_is_bounded(empty_disk):
    params, _state = _demo("plane/chaplygin-ball")
    model = build("plane/chaplygin-ball", params)
    for i in range(tb.MAX_CACHED + 2):
        tb.compiled(model.model, model.p, "long double", 10.0 ** (-4 - i / 4))
    assert len(tb._cache) == tb.MAX_CACHED


def test_without_heyoka_the_message_names_the_extra(monkeypatch):
    monkeypatch.setitem(sys.modules, "heyoka", None)      # import heyoka -> ImportError
    params, state = _demo("plane/chaplygin-ball")
    with pytest.raises(InputError, match=r"pip install rolling-hierarchy\[taylor\]"):
        simulate("plane/chaplygin-ball", params, state, 1.0, method="taylor")
    # auto leaves the Taylor candidate out and says so
    r = simulate("plane/chaplygin-ball", params, state, 1.0, method="auto", rtol=1e-15)
    assert r.stats["method"] != "taylor" and "heyoka is not installed" in \
        r.stats["auto"]["reason"]


def test_bad_options_are_refused():
    params, state = _demo("plane/chaplygin-ball")
    with pytest.raises(InputError, match="precision"):
        simulate("plane/chaplygin-ball", params, state, 1.0, method="taylor",
                 precision="octuple")
    with pytest.raises(InputError, match="only method 'taylor'"):
        simulate("plane/chaplygin-ball", params, state, 1.0, method="dop853",
                 precision="quad")
    with pytest.raises(InputError, match="does not project"):
        simulate("plane/chaplygin-ball", params, state, 1.0, method="taylor", project=True)


def test_auto_says_what_it_chose_and_why():
    params, state = _demo("plane/chaplygin-ball")
    r = simulate("plane/chaplygin-ball", params, state, 10.0, method="auto", rtol=1e-6)
    a = r.stats["auto"]
    assert r.stats["method"] == a["method"] in ("dop853", "vern9", "taylor")
    # the choice is the many-start data's (solvers/integrate/auto_choice.py): the method
    # cheapest at the level on most starts, at the tolerance that reached it on most
    from solvers.integrate import auto, auto_choice

    pick = auto_choice.first_choice("plane/chaplygin-ball", 1e-6, auto.CANDIDATES)
    assert (a["method"], a["tol"]) == (pick["method"], pick["tol"]) and "starts" in a["reason"]
    assert pick["level"] <= 1e-6 * auto_choice.AIM_FIRST
    # and the run reaches the error the benchmark promised, over the benchmark's T = 1000
    ref = simulate("plane/chaplygin-ball", params, state, 1000.0, method="vern9",
                   rtol=1e-14, atol=1e-14, samples=101)
    run = simulate("plane/chaplygin-ball", params, state, 1000.0, method="auto", rtol=1e-6,
                   samples=101)
    assert np.abs(run.state - ref.state).max() / max(1.0, np.abs(ref.state).max()) < 1e-6


def test_api_taylor_run_and_precision_validation():
    from fastapi.testclient import TestClient

    from app.main import create_app
    from app.testing import settings_for_tests

    app = create_app(settings_for_tests(max_steps=20_000))
    body = {"case": "plane/chaplygin-ball", "example": True, "t_end": 1.0}
    with TestClient(app) as c:
        r = c.post("/api/simulate", json={**body, "method": "taylor", "rtol": 1e-9})
        assert r.status_code == 200, r.text
        s = r.json()["stats"]
        assert s["method"] == "taylor" and s["precision"] == "double" and s["max_steps"]
        r = c.post("/api/simulate", json={**body, "method": "taylor", "precision": "octuple"})
        assert r.status_code == 422 and "precision" in r.text
        r = c.post("/api/validate", json={**body, "method": "dop853", "precision": "quad"})
        assert r.status_code == 422 and "only method 'taylor'" in r.text
        kinds = {m["name"]: m["kind"] for m in c.get("/api/methods").json()}
        assert kinds["taylor"] == "taylor" and kinds["auto"] == "auto"
