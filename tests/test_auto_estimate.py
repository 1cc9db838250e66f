"""method="auto" returns the tighter of two runs with an upper estimate of its own error
from the looser one, and tightens until the estimate meets the request
(solvers/integrate/auto.py, run_checked)."""

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


def test_auto_returns_an_upper_estimate_of_this_runs_error():
    params, state = _demo()
    r = simulate(BALL, params, state, 20.0, method="auto", rtol=1e-8, samples=41)
    s = r.stats
    assert r.ok and s["auto"]["met"] and 0 < s["error_estimate"] <= 1e-8
    assert "looser" in s["error_estimate_method"]
    assert s["auto"]["rounds"][-1]["error_estimate"] == s["error_estimate"]
    assert s["auto"]["rounds"][-1]["tol"] == s["rtol"]
    assert s["auto"]["runs"] >= 2 and s["auto"]["rhs_calls_total"] > s["rhs_calls"]
    # the estimate is of the returned run: above its error against an independent
    # tighter reference, and not wildly so
    achieved = auto.error_between(r.state, _reference(BALL, params, state, 20.0, 41))
    assert achieved <= s["error_estimate"] <= 30 * achieved


def test_a_plain_method_has_no_estimate_and_no_extra_run():
    params, state = _demo()
    r = simulate(BALL, params, state, 5.0, method="dop853", rtol=1e-8, atol=1e-8)
    assert "error_estimate" not in r.stats and "auto" not in r.stats


def _loose(monkeypatch, tol, method="dop853"):
    """auto's first choice forced to a tolerance far looser than the request."""
    real = auto.choose

    def loose(*a, **k):
        return {**real(*a, **k), "tol": tol, "method": method, "precision": None}
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
    assert achieved <= r.stats["error_estimate"]


def test_when_the_rounds_run_out_it_says_the_request_is_not_met(monkeypatch):
    _loose(monkeypatch, 1e-4)
    monkeypatch.setattr(auto, "MAX_ROUNDS", 1)
    params, state = _demo()
    r = simulate(BALL, params, state, 20.0, method="auto", rtol=1e-10, samples=41)
    assert r.ok and not r.stats["auto"]["met"] and r.stats["error_estimate"] > 1e-10
    assert r.stats["rtol"] == 1e-4 and "rounds spent" in r.stats["error_estimate_method"]
    achieved = auto.error_between(r.state, _reference(BALL, params, state, 20.0, 41))
    assert achieved <= r.stats["error_estimate"]


def test_the_runs_share_the_request_step_budget():
    params, state = _demo()
    r = simulate(BALL, params, state, 1000.0, method="auto", rtol=1e-10, max_steps=300)
    assert r.status == "budget" and r.stats["error_estimate"] is None
    assert r.stats["error_estimate_method"].startswith("none")
    assert not r.stats["auto"]["met"] and r.stats["auto"]["steps_total"] <= 300


def _fake_runner(calls, c=100.0, fail_below=0.0):
    """A 'method' whose global error is exactly c * tol (a Taylor run: c times its order's
    tol, auto.effective_tol), the exact solution 0: y = c * tol at every time.
    Called from two threads: calls is appended to (thread-safe), read sorted."""
    def runner(rung, budget):
        calls.append((rung["method"], rung["tol"], rung["precision"], budget))
        t = np.linspace(0.0, 1.0, 3)
        ok = rung["tol"] >= fail_below
        y = np.full((3, 2), c * auto.effective_tol(rung))
        return SimpleNamespace(t=t if ok else t[:1], y=y,
                               success=ok, steps=10, rhs_calls=100, wall_s=0.0,
                               message="" if ok else "singular")
    return runner


def _choice(method, tol, requested):
    return {"method": method, "tol": tol, "precision": None, "compensated": False,
            "requested_rtol": requested}


def test_the_returned_run_is_the_tighter_and_its_estimate_is_above_its_error():
    calls = []
    res, info = auto.run_checked(_choice("dop853", 1e-9, 1e-6), _fake_runner(calls), 1.0,
                                 1000)
    # one pair: the run at 1e-9 and its check CHECK_LOOSER looser, side by side, budgets split
    loose = 1e-9 * auto.CHECK_LOOSER
    assert sorted(t for _, t, _, _ in calls) == pytest.approx([1e-9, loose])
    assert sorted(b for *_, b in calls) == [400, 600]
    assert info["met"] and info["runs"] == 2 and info["returned"]["tol"] == 1e-9
    assert res.y[0, 0] == 100 * 1e-9
    k = auto.scale("dop853", 1e-9, loose)
    diff = 100 * (loose - 1e-9)
    assert info["error_estimate"] == pytest.approx(diff * k, rel=1e-9)
    # error ~ tol here (alpha = 1): the estimate with alpha < 1 is above the true error
    assert info["error_estimate"] > 100 * 1e-9


def test_a_miss_tightens_and_a_looser_run_before_is_the_check():
    calls = []
    res, info = auto.run_checked(_choice("vern9", 1e-6, 1e-8), _fake_runner(calls), 1.0,
                                 1000)
    tols = [t for _, t, _, _ in calls]
    # CHECK_LOOSER looser than 1e-6 is beyond CHECK_MAX_TOL: the first check is as much
    # tighter, and the estimate is of the returned 1e-6 run, 100 (1e-6 - tight) / (1 - rho)
    tight = 1e-6 / auto.CHECK_LOOSER
    assert sorted(tols[:2]) == pytest.approx([tight, 1e-6])
    e0 = info["rounds"][0]["error_estimate"]
    assert info["rounds"][0]["tol"] == 1e-6 and e0 == pytest.approx(
        100 * (1e-6 - tight) * auto.scale("vern9", 1e-6, tight))
    assert len(info["rounds"]) == 2 and info["runs"] == 3 and info["met"]
    # e0 wants a tol (e0 / (AIM E))^(1/alpha) tighter; its check is the earlier run
    # closest to it and looser: the tight one
    want = 1e-6 / max((e0 / (auto.AIM * 1e-8)) ** (1 / auto.ALPHA["vern9"]), auto.MIN_TIGHTEN)
    assert tols[2] == pytest.approx(want) and info["returned"]["tol"] == tols[2]
    assert f"{tight:.3g}" in info["rounds"][1]["check"]
    assert 100 * tols[2] < info["error_estimate"] <= 1e-8
    assert sum(b for *_, b in calls[:2]) <= 1000 and calls[2][3] == 1000 - 20
    assert res.y[0, 0] == 100 * tols[2]


def test_below_the_runge_kutta_floor_it_goes_to_the_taylor_backend_in_double():
    calls = []
    _res, info = auto.run_checked(_choice("dop853", 1e-13, 1e-12), _fake_runner(calls, 1e3),
                                  1000.0, 10_000, taylor_ok=True)
    ms = [(m, p) for m, _, p, _ in calls]
    assert ms[:2] == [("dop853", None)] * 2
    # a request above 1e-14 never runs in extended precision: the Taylor backend in double
    assert ms[2:] == [("taylor", "double")] * 2
    assert info["returned"]["method"] == "taylor"
    assert info["returned"]["precision"] == "double"
    # at double's floor, its estimate more than PAST_FLOOR_REACH times the request: nothing
    # past the floor, and not met
    assert info["error_estimate"] > auto.PAST_FLOOR_REACH * 1e-12 and not info["met"]


def test_past_doubles_floor_a_compensated_pair_meets_in_double():
    """A Taylor run at double's floor whose error (c x its order's tol) stays above the
    request, a pair whose error is c x tol: the compensated pair at PAST_FLOOR_TOL is run,
    checked by its own looser run, and meets the request in double."""
    calls = []
    E = 1e-10
    choice = {**_choice("taylor", 1e-14, E), "precision": None}
    res, info = auto.run_checked(choice, _fake_runner(calls, 1e4), 1000.0, 100_000,
                                 taylor_ok=True)
    kinds = [(x["method"], x["precision"], x["compensated"]) for x in info["rounds"]]
    assert kinds == [("taylor", "double", False), (auto.PAST_FLOOR_METHOD, None, True)]
    assert info["met"] and info["error_estimate"] <= E
    assert info["returned"]["tol"] == auto.PAST_FLOOR_TOL
    assert res.y[0, 0] == 1e4 * auto.PAST_FLOOR_TOL <= info["error_estimate"]


def test_not_met_it_returns_the_run_of_the_least_estimate():
    """Past double's floor the compensated pair may do worse than the Taylor run before
    it: where nothing meets the request, the run returned is the one of the least
    estimate, with that estimate."""
    calls = []
    choice = {**_choice("taylor", 1e-14, 5e-14), "precision": None}

    def runner(rung, budget):       # the Taylor backend far better than the pair here
        return _fake_runner(calls, 1.0 if rung["method"] == "taylor" else 1e5)(rung, budget)
    res, info = auto.run_checked(choice, runner, 1000.0, 100_000, taylor_ok=True)
    assert not info["met"] and len(info["rounds"]) >= 2
    best = min(info["rounds"], key=lambda x: x["error_estimate"])
    assert best["method"] == "taylor" and info["returned"]["method"] == "taylor"
    assert info["error_estimate"] == best["error_estimate"]
    assert res.y[0, 0] == auto.effective_tol(info["returned"])


@pytest.mark.parametrize("requested", [1e-12, 2e-14])
def test_no_request_above_1e_14_runs_in_extended_precision(requested):
    """A Taylor first choice that misses by far asks for tols below double's floor: they
    stay in double, and the request is reported as not met rather than run in long
    double."""
    calls = []
    choice = {**_choice("taylor", 1e-13, requested), "precision": None}
    _res, info = auto.run_checked(choice, _fake_runner(calls, 1e6), 1000.0, 10_000,
                                  taylor_ok=True)
    assert calls and all(p in (None, "double") for _, _, p, _ in calls), calls
    assert not info["met"] and info["error_estimate"] > requested


def test_at_1e_14_and_below_extended_precision_is_allowed():
    calls = []
    choice = {**_choice("taylor", 1e-13, 1e-15), "precision": None}
    auto.run_checked(choice, _fake_runner(calls, 1e3), 1000.0, 10_000, taylor_ok=True)
    assert any(p == "long double" for _, _, p, _ in calls)


def test_without_taylor_it_stops_at_the_floor_and_says_so():
    calls = []
    res, info = auto.run_checked(_choice("dop853", 1e-12, 1e-8), _fake_runner(calls, 1e8),
                                 1.0, 1000)
    # 1e-12 misses (error 1e-4); the tighter run stops at RK_MIN_RUN, checked by 1e-12;
    # its estimate is far above the request: nothing past the floor
    assert sorted(t for _, t, _, _ in calls) == pytest.approx(
        [1e-14, 1e-12, 1e-12 * auto.CHECK_LOOSER])
    assert not info["met"] and info["returned"]["tol"] == 1e-14
    assert res.y[0, 0] == 1e8 * 1e-14
    assert "as tight as auto runs" in info["error_estimate_method"]


def test_near_the_floor_it_goes_past_it_compensated_and_says_when_rounds_run_out():
    calls = []
    E = 2e-10
    res, info = auto.run_checked(_choice("dop853", 1e-12, E), _fake_runner(calls, 1e5),
                                 1.0, 1000)
    # the run at RK_MIN_RUN is estimated within PAST_FLOOR_REACH of the request: then the
    # compensated pair at PAST_FLOOR_TOL with its own looser check
    assert E < info["rounds"][1]["error_estimate"] <= auto.PAST_FLOOR_REACH * E
    assert [t for _, t, _, _ in calls] == pytest.approx(
        [1e-12, 1e-12 * auto.CHECK_LOOSER, 1e-14, auto.PAST_FLOOR_TOL,
         auto.PAST_FLOOR_TOL * auto.CHECK_LOOSER])
    assert [x["compensated"] for x in info["rounds"]] == [False, False, True]
    # not met: the run of the least estimate comes back, the compensated one here
    assert not info["met"] and info["returned"]["tol"] == auto.PAST_FLOOR_TOL
    assert res.y[0, 0] == 1e5 * auto.PAST_FLOOR_TOL
    assert f"{auto.MAX_ROUNDS} rounds spent" in info["error_estimate_method"]


def test_a_compensated_pair_is_as_tight_as_auto_runs():
    calls = []
    choice = {**_choice("vern9", auto.PAST_FLOOR_TOL, 1e-8), "compensated": True}
    _res, info = auto.run_checked(choice, _fake_runner(calls, 1e12), 1.0, 1000)
    assert not info["met"] and len(info["rounds"]) == 1
    assert "as tight as auto runs" in info["error_estimate_method"]


def test_a_failed_check_gives_no_estimate_and_a_failed_tighter_run_is_not_returned():
    calls = []
    res, info = auto.run_checked(_choice("vern9", 1e-8, 1e-6),
                                 _fake_runner(calls, 100.0, fail_below=1e-6), 1.0, 1000)
    # the returned run itself failed: no estimate, not met
    assert info["error_estimate"] is None and not info["met"] and not res.success
    calls = []
    res, info = auto.run_checked(_choice("vern9", 1e-6, 1e-8),
                                 _fake_runner(calls, 100.0, fail_below=1e-7), 1.0, 1000)
    # checked once (estimate > 1e-8), the tighter run fails: the checked run comes back
    assert info["returned"]["tol"] == 1e-6 and res.success and not info["met"]
    assert "stopped early" in info["error_estimate_method"]


@pytest.mark.parametrize("c, fail_below", [(1.0, 0.0), (1e4, 0.0), (1e9, 0.0),
                                            (1e4, 1e-9), (1e6, 1e-12)])
@pytest.mark.parametrize("method", ["dop853", "vern9", "taylor"])
def test_met_means_the_estimate_is_within_the_request(method, c, fail_below):
    """Whatever path the rounds take (met at once, tightened, run out, a failed run), the
    returned estimate is the returned run's and `met` is true only where it is <= E."""
    for E in (1e-6, 1e-10, 1e-12):
        calls = []
        res, info = auto.run_checked(_choice(method, E, E), _fake_runner(calls, c, fail_below),
                                     1000.0, 10_000, taylor_ok=True)
        est = info["error_estimate"]
        assert info["met"] == (est is not None and est <= E), (info, E)
        if est is not None:
            assert est in [x["error_estimate"] for x in info["rounds"]]
            assert info["met"] <= (info["rounds"][-1]["error_estimate"] == est)
            true = c * auto.effective_tol(info["returned"])
            assert res.y[0, 0] == true
            if c * 1e-5 <= 1:     # the measure is absolute (no check above 1): est >= true
                assert est >= true * 0.999


@pytest.mark.parametrize("E", [1e-6, 1e-12])
def test_simulate_met_agrees_with_its_estimate_and_stays_in_double(E):
    params, state = _demo()
    r = simulate(BALL, params, state, 100.0, method="auto", rtol=E, samples=21)
    a = r.stats["auto"]
    assert a["met"] == (r.stats["error_estimate"] is not None
                        and r.stats["error_estimate"] <= E)
    assert r.stats.get("precision") in (None, "double")
    assert all(x["precision"] in (None, "double") for x in a["rounds"])


def test_a_front_point_in_long_double_is_not_taken_above_1e_14(monkeypatch):
    """Where the one-start front (no many-start data) names a long double Taylor run for a
    request above 1e-14, auto still runs double."""
    from solvers.integrate import auto_choice

    monkeypatch.setattr(auto_choice, "first_choice", lambda *a, **k: None)
    monkeypatch.setattr(auto, "_one_start_front",
                        lambda *a: ("taylor", 1e-13, "long double", "a front point"))
    c = auto.choose(BALL, 1, 1e-12, 1000.0)
    assert c["method"] == "taylor" and c["precision"] is None
    assert auto.plan(c, 1000.0)[0]["precision"] == "double"
    c = auto.choose(BALL, 1, 1e-15, 1000.0)
    assert c["precision"] == "long double"


def test_the_check_joins_a_long_run_on_the_check_thread_and_follows_a_short_one():
    """auto._pair: the check starts on the check thread once the run has gone on `defer`
    seconds; a run that ends sooner has its check run after it on the caller's thread.
    Which thread ran what is asserted, not how long it took."""
    import threading
    import time

    def pair(run_s, defer):
        where = {}

        def runner(rung, budget):
            where[rung["tol"]] = threading.current_thread()
            if rung["tol"] == 1.0:
                time.sleep(run_s)
            return rung["tol"]
        got = auto._pair(runner, {"tol": 1.0}, 1, {"tol": 2.0}, 1, defer=defer)
        return got, where

    me = threading.current_thread()
    (ra, rb), where = pair(0.0, 5.0)             # the run ends long before the wait
    assert (ra, rb) == (1.0, 2.0) and where[1.0] is me and where[2.0] is me
    (ra, rb), where = pair(0.5, 0.01)            # the run goes on past the wait
    assert (ra, rb) == (1.0, 2.0) and where[1.0] is me and where[2.0] is not me
    assert where[2.0].name.startswith("auto-check")
    (ra, rb), where = pair(0.0, -1.0)            # defer < 0: one after the other, no thread
    assert where[2.0] is me
