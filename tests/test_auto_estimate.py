"""method="auto" reports an estimate of its own run's error and tightens until the estimate
meets the request (solvers/integrate/auto.py, run_checked; issue 19 item 5)."""

from types import SimpleNamespace

import numpy as np
import pytest

from solvers.integrate import auto
from solvers.models.cases import registry
from solvers.simulate import simulate

BALL = "plane/chaplygin-ball"


def _demo(case=BALL):
    c = registry()[case]
    return c.example, c.state


def _reference(case, params, state, t_end, samples):
    """vern9 at tol 1e-15: its error over these short runs is far below the levels here."""
    return simulate(case, params, state, t_end, method="vern9", rtol=1e-15, atol=1e-15,
                    samples=samples).state


def test_auto_returns_an_estimate_of_this_runs_error():
    params, state = _demo()
    r = simulate(BALL, params, state, 20.0, method="auto", rtol=1e-8, samples=41)
    s = r.stats
    assert r.ok and s["auto"]["met"] and 0 < s["error_estimate"] <= 1e-8
    assert "second run" in s["error_estimate_method"]
    assert s["auto"]["rounds"][-1]["error_estimate"] == s["error_estimate"]
    assert s["auto"]["runs"] >= 2 and s["auto"]["rhs_calls_total"] > s["rhs_calls"]
    # the estimate is an estimate of the returned run's error: within a factor 2 of the
    # error against an independent tighter reference
    achieved = auto.error_between(r.state, _reference(BALL, params, state, 20.0, 41))
    assert 0.5 < s["error_estimate"] / achieved < 2.0


def test_a_plain_method_has_no_estimate_and_no_extra_run():
    params, state = _demo()
    r = simulate(BALL, params, state, 5.0, method="dop853", rtol=1e-8, atol=1e-8)
    assert "error_estimate" not in r.stats and "auto" not in r.stats


def _loose(monkeypatch, tol):
    """auto's first choice forced to a tolerance far looser than the request."""
    real = auto.choose

    def loose(*a, **k):
        return {**real(*a, **k), "tol": tol}
    monkeypatch.setattr(auto, "choose", loose)


def test_a_loose_first_choice_is_tightened_until_the_estimate_meets_the_request(monkeypatch):
    _loose(monkeypatch, 1e-4)
    params, state = _demo()
    r = simulate(BALL, params, state, 20.0, method="auto", rtol=1e-10, samples=41)
    a = r.stats["auto"]
    assert a["tol"] == 1e-4 and a["rounds"][0]["tol"] == 1e-4
    assert a["rounds"][0]["error_estimate"] > 1e-10          # the first round missed
    assert len(a["rounds"]) >= 2 and a["met"] and r.stats["error_estimate"] <= 1e-10
    assert r.stats["rtol"] < 1e-4 and r.stats["rtol"] == a["rounds"][-1]["tol"]
    achieved = auto.error_between(r.state, _reference(BALL, params, state, 20.0, 41))
    assert achieved <= 1e-10


def test_when_the_rounds_run_out_it_says_the_request_is_not_met(monkeypatch):
    _loose(monkeypatch, 1e-4)
    monkeypatch.setattr(auto, "MAX_ROUNDS", 1)
    params, state = _demo()
    r = simulate(BALL, params, state, 20.0, method="auto", rtol=1e-10, samples=41)
    assert r.ok and not r.stats["auto"]["met"] and r.stats["error_estimate"] > 1e-10
    assert r.stats["rtol"] == 1e-4
    achieved = auto.error_between(r.state, _reference(BALL, params, state, 20.0, 41))
    assert 0.5 < r.stats["error_estimate"] / achieved < 2.0


def test_the_runs_share_the_request_step_budget():
    params, state = _demo()
    r = simulate(BALL, params, state, 1000.0, method="auto", rtol=1e-10, max_steps=300)
    assert r.status == "budget" and r.stats["error_estimate"] is None
    assert r.stats["error_estimate_method"].startswith("none")
    assert r.stats["auto"]["steps_total"] <= 300


def _fake_runner(calls, c=100.0):
    """A 'method' whose global error is exactly c * tol: y = 1 + c * tol at every time."""
    def runner(rung, budget):
        calls.append((rung["tol"], budget))
        t = np.linspace(0.0, 1.0, 3)
        return SimpleNamespace(t=t, y=np.full((3, 2), 1.0 + c * rung["tol"]), success=True,
                               steps=10, rhs_calls=100, wall_s=0.0, message="")
    return runner


def test_run_checked_logic_on_a_method_of_known_error():
    calls = []
    choice = {"method": "dop853", "tol": 1e-6, "precision": None, "compensated": True,
              "requested_rtol": 1e-8}
    res, info = auto.run_checked(choice, _fake_runner(calls), 1.0, 1000)
    # round 1: 1e-6 (error 1e-4), check at 10^-7.5; the estimate 1e-4 (1 - 10^-1.5) misses;
    # error ~ tol aims at half the request: tol 5e-11 snapped down to 10^-10.5 (error 3e-9),
    # checked at 1e-12
    tols = [t for t, _ in calls]
    assert tols == pytest.approx([1e-6, 10 ** -7.5, 10 ** -10.5, 1e-12])
    assert [b for _, b in calls] == [1000, 990, 980, 970]     # one budget for all runs
    assert info["met"] and info["runs"] == 4 and info["steps_total"] == 40
    assert info["error_estimate"] == pytest.approx(100 * (10 ** -10.5 - 1e-12), rel=1e-6)
    assert res.y[0, 0] == 1.0 + 100 * 10 ** -10.5 and info["returned"]["tol"] == tols[2]


def test_a_check_run_tight_enough_becomes_the_returned_run():
    calls = []
    choice = {"method": "vern9", "tol": 1e-9, "precision": None, "compensated": True,
              "requested_rtol": 1e-8}
    _res, info = auto.run_checked(choice, _fake_runner(calls, c=20.0), 1.0, 1000)
    # error 2e-8 > 1e-8; aiming at 5e-9 wants tol 2.5e-10 -> 10^-9.75, looser than the check
    # run's 10^-10.5: that run is reused as the result and checked once more at 1e-12
    assert [t for t, _ in calls] == pytest.approx([1e-9, 10 ** -10.5, 1e-12])
    assert info["met"] and info["returned"]["tol"] == pytest.approx(10 ** -10.5)


def _runner_by_method(calls, c, fail_below=0.0):
    def runner(rung, budget):
        calls.append((rung["method"], rung["tol"], rung["precision"]))
        t = np.linspace(0.0, 1.0, 3)
        ok = rung["tol"] >= fail_below
        return SimpleNamespace(t=t if ok else t[:1], y=np.full((3, 2), 1.0 + c * rung["tol"]),
                               success=ok, steps=10, rhs_calls=100, wall_s=0.0,
                               message="" if ok else "singular")
    return runner


def test_below_the_runge_kutta_floor_it_goes_to_the_taylor_backend():
    calls = []
    choice = {"method": "dop853", "tol": 1e-12, "precision": None, "compensated": True,
              "requested_rtol": 1e-8}
    _res, info = auto.run_checked(choice, _runner_by_method(calls, 1e7), 1.0, 1000,
                                 taylor_ok=True)
    # the estimate 1e-5 wants tol 5e-16: below RK_MIN_RUN, so the Taylor backend, in double
    # at 10^-15.5 and its check in long double at 1e-17 (T = 1: the floors of taylor_backend)
    assert [(m, p) for m, _, p in calls] == [("dop853", None), ("dop853", None),
                                             ("taylor", "double"), ("taylor", "long double")]
    assert [t for _, t, _ in calls] == pytest.approx([1e-12, 10 ** -13.5, 10 ** -15.5, 1e-17])
    assert info["met"] and info["returned"]["method"] == "taylor"


def test_without_taylor_it_stops_at_the_floor_and_returns_the_run_it_checked():
    calls = []
    choice = {"method": "dop853", "tol": 1e-12, "precision": None, "compensated": True,
              "requested_rtol": 1e-8}
    res, info = auto.run_checked(choice, _runner_by_method(calls, 1e8), 1.0, 1000)
    assert [t for _, t, _ in calls] == pytest.approx([1e-12, 10 ** -13.5, 1e-16])
    # the 1e-16 run has no tighter check: the returned run is the checked one, with its
    # own estimate, and the request is reported as not met
    assert not info["met"] and info["returned"]["tol"] == 1e-12
    assert res.y[0, 0] == 1.0 + 1e8 * 1e-12
    # (divided by max(1, max |y_check|) = 1 + 3e-6: the benchmark's measure)
    assert info["error_estimate"] == pytest.approx(1e8 * (1e-12 - 10 ** -13.5), rel=1e-5)
    assert "as tight as auto runs" in info["error_estimate_method"]


def test_a_tightened_run_that_fails_is_not_returned():
    calls = []
    choice = {"method": "vern9", "tol": 1e-8, "precision": None, "compensated": True,
              "requested_rtol": 1e-8}
    res, info = auto.run_checked(choice, _runner_by_method(calls, 100.0, fail_below=1e-9),
                                 1.0, 1000)
    # the check at 10^-9.5 fails at once: no estimate at all, the first run returned
    assert info["error_estimate"] is None and not info["met"] and res.success
    assert info["error_estimate_method"].startswith("none: the check run")
    calls = []
    res, info = auto.run_checked(choice, _runner_by_method(calls, 100.0, fail_below=1e-10),
                                 1.0, 1000)
    # checked once (estimate ~1e-6), the tightened run at 10^-10.5 fails: the checked run
    # comes back with its estimate
    assert info["returned"]["tol"] == 1e-8 and res.success and not info["met"]
    assert info["error_estimate"] == pytest.approx(100 * (1e-8 - 10 ** -9.5))
    assert "stopped early" in info["error_estimate_method"]
