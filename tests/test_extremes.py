"""The extremes: each run either stays accurate (invariants within the stated tolerance,
agreement with a tighter reference) or stops with a clear message saying why and where.
Never NaN, never garbage returned as success.

Each test compares a run at the default tolerance (rtol 1e-10) with a reference at rtol
1e-13 (vern9) over the same samples, and checks the invariants the case carries. Times are
scaled with the fast time scale of the extreme (spin, 1/(1 - kR), I/(m R^2)) so that every
run covers the same number of turns.
"""

import math

import numpy as np
import pytest

from solvers.errors import InputError
from solvers.integrate.integrator import Section, integrate
from solvers.kernels import layout as L
from solvers.models.cases import registry
from solvers.simulate import simulate

BALL = "plane/chaplygin-ball"
DISK = "plane/round-disk"
CAVITY = "sphere/chaplygin-ball"


def finite(r):
    return bool(np.all(np.isfinite(r.state)) and all(np.all(np.isfinite(v))
                                                     for v in r.invariants.values()))


def run_pair(case, params, state, t_end, rtol=1e-10, **kw):
    """The run under test and a tighter reference from the same point."""
    ex = registry()[case].example
    r = simulate(case, {**ex, **params}, state, t_end, rtol=rtol, atol=rtol * 1e-2,
                 samples=51, **kw)
    ref = simulate(case, {**ex, **params}, state, t_end, method="vern9", rtol=1e-13,
                   atol=1e-15, samples=51, **kw)
    return r, ref


def assert_accurate(r, ref, err_tol, drift_tol):
    assert r.ok and ref.ok, (r.message, ref.message)
    assert finite(r)
    scale = max(1.0, float(np.abs(ref.state).max()))
    err = float(np.abs(r.state - ref.state).max()) / scale
    assert err < err_tol, err
    drift = max(r.stats["drift"].values())
    assert drift < drift_tol, r.stats["drift"]


def assert_stops_clearly(r, *words):
    assert r.status in ("singular", "budget")
    assert finite(r)                              # what was computed before the stop
    assert "stopped at t =" in r.message, r.message
    for w in words:
        assert w in r.message, r.message


# --- disk: nearly flat (sin theta -> 0) and nearly upright with a huge spin -------------
@pytest.mark.parametrize("sin_theta", [1e-2, 1e-4])
def test_disk_nearly_flat_stays_accurate(sin_theta):
    g = [sin_theta, 0.0, math.sqrt(1.0 - sin_theta**2)]
    r, ref = run_pair(DISK, {}, [0.0, 0.3, 3.0, *g], 10.0)
    assert_accurate(r, ref, 1e-6, 1e-9)


@pytest.mark.parametrize("sin_theta", [1e-6, 1e-7])
def test_disk_falling_through_flat_stops_there(sin_theta):
    """Closer to flat, this trajectory reaches sin theta < 1e-8 (the contact point is
    undefined there): the run stops at that time with the reason, keeping the samples."""
    g = [sin_theta, 0.0, math.sqrt(1.0 - sin_theta**2)]
    ex = registry()[DISK].example
    r = simulate(DISK, ex, [0.0, 0.3, 3.0, *g], 10.0)
    assert_stops_clearly(r, "flat")
    t_stop = float(r.message.split("stopped at t =")[1].strip(" )"))
    assert 0.0 < t_stop < 1e-4


def test_disk_flat_at_the_start_is_refused():
    with pytest.raises(InputError, match="flat"):
        simulate(DISK, registry()[DISK].example, [0.0, 0.3, 3.0, 1e-9, 0.0, 1.0], 1.0)


@pytest.mark.parametrize("spin", [1e2, 1e3, 1e4])
def test_disk_nearly_upright_with_huge_spin(spin):
    """Tilt 1e-3 from upright, |omega| ~ 2 spin about the axis, 100/spin time units."""
    eps = 1e-3
    state = [0.01 * spin, 0.0, 0.5 * spin, math.cos(eps), 0.0, math.sin(eps)]
    r, ref = run_pair(DISK, {}, state, 100.0 / spin)
    assert_accurate(r, ref, 1e-8, 1e-10)


# --- a body that just fits the sphere: 1 - k R -> 0+ ---------------------------------------
@pytest.mark.parametrize("fit", [1e-2, 1e-4])
def test_ball_that_just_fits_its_cavity(fit):
    """A ball of radius 1 in a cavity of radius 1/(1 - fit): gamma turns 1/fit times
    faster; 10 fit time units."""
    r, ref = run_pair(CAVITY, {"k": 1.0 - fit}, registry()[CAVITY].state, 10.0 * fit)
    assert_accurate(r, ref, 1e-8, 1e-10)


def test_ball_that_barely_fits_keeps_its_integrals():
    """1 - kR = 1e-6: the run is stiff for an explicit method (the stages leave |gamma| = 1
    by O(h^2 |dgamma/dt|^2), and the tangent factor 1 - kR/|gamma| of eq1.3 is 1e-6):
    ~2e5 steps for 10 turns, and the integrals hold."""
    fit = 1e-6
    ex = registry()[CAVITY].example
    r = simulate(CAVITY, {**ex, "k": 1.0 - fit}, registry()[CAVITY].state, 10.0 * fit,
                 samples=11)
    assert r.ok and finite(r)
    assert max(r.stats["drift"].values()) < 1e-11, r.stats["drift"]


def test_ball_that_fits_to_1e_8_stops_on_its_step_budget():
    """1 - kR = 1e-8: the step size the explicit method needs is ~1e-15 of a turn; the run
    stops on the step budget, saying so and where (projection does not help: the stages,
    not the steps, leave the sphere)."""
    fit = 1e-8
    ex = registry()[CAVITY].example
    r = simulate(CAVITY, {**ex, "k": 1.0 - fit}, registry()[CAVITY].state, 10.0 * fit,
                 samples=11, max_steps=50_000)
    assert_stops_clearly(r, "step budget")


def test_ball_that_does_not_fit_is_refused():
    with pytest.raises(InputError, match="does not fit"):
        simulate(CAVITY, {**registry()[CAVITY].example, "k": 1.0}, registry()[CAVITY].state,
                 1.0)


# --- nearly equal moments of inertia and the exactly symmetric limit ----------------------
def test_nearly_equal_moments_match_the_symmetric_limit():
    state = registry()[BALL].state
    ex = registry()[BALL].example
    near = simulate(BALL, {**ex, "I2": 1.0 + 1e-12, "I3": 1.5}, state, 100.0, samples=51)
    exact = simulate(BALL, {**ex, "I2": 1.0, "I3": 1.5}, state, 100.0, samples=51)
    r, ref = run_pair(BALL, {"I2": 1.0 + 1e-12, "I3": 1.5}, state, 100.0)
    assert_accurate(r, ref, 1e-8, 1e-10)
    assert np.abs(near.state - exact.state).max() < 1e-9
    assert exact.ok and max(exact.stats["drift"].values()) < 1e-10


def test_exactly_symmetric_routh_ball():
    c = registry()["plane/routh-ball"]
    r, ref = run_pair("plane/routh-ball", {"I1": 2.0, "I2": 2.0}, c.state, 100.0)
    assert_accurate(r, ref, 1e-8, 1e-9)


# --- mass ratios m R^2 / I from 1e-6 to 1e6 -------------------------------------------------
@pytest.mark.parametrize("ratio", [1e-6, 1e-3, 1.0, 1e3, 1e6])
def test_mass_ratio(ratio):
    """I = (1, 2, 2.5) / ratio with m = R = 1. Large ratios make I_Q nearly singular along
    r (the spin about the normal is fast, ~ratio): time scaled by min(1, 1/ratio)."""
    params = {"I1": 1.0 / ratio, "I2": 2.0 / ratio, "I3": 2.5 / ratio}
    r, ref = run_pair(BALL, params, registry()[BALL].state, 100.0 * min(1.0, 1.0 / ratio))
    assert_accurate(r, ref, 1e-7, 1e-9)


# --- |omega| up to 1e4 ---------------------------------------------------------------------
@pytest.mark.parametrize("scale", [1e2, 1e4])
def test_fast_rotation(scale):
    """M scaled by 1e2 and 1e4 (|omega| ~ 1e4), the same number of turns: the drift at
    rtol 1e-10 is what the unscaled run has (~1e-10 over these turns)."""
    st = registry()[BALL].state
    r, ref = run_pair(BALL, {}, [scale * v for v in st[:3]] + list(st[3:]), 100.0 / scale)
    assert_accurate(r, ref, 1e-8, 1e-9)


# --- section crossings near tangency ----------------------------------------------------------
OSC = L.MODEL_TEST_OSC


@pytest.mark.parametrize("depth", [1e-3, 1e-6, 1e-10])
@pytest.mark.parametrize("method", ["dop853", "vern9"])
def test_grazing_section_crossings_are_found(method, depth):
    """y = (sin t, cos t); the section y0 = 1 - depth is grazed: crossed up at
    asin(1 - depth) + 2 pi k and down at pi - asin(1 - depth) + 2 pi k, the two within
    2 sqrt(2 depth) of each other (inside one step of ~0.5). Every crossing is found,
    in the right direction, where it is."""
    level = 1.0 - depth
    a = math.asin(level)
    t_end = 6 * math.pi
    up = [a + 2 * math.pi * k for k in range(3)]
    down = [math.pi - a + 2 * math.pi * k for k in range(3)]
    for direction, exact in ((1, up), (-1, down), (0, sorted(up + down))):
        r = integrate(OSC, np.zeros(L.N_PARAMS), [0.0, 1.0], [0.0, t_end], method=method,
                      rtol=1e-10, atol=1e-12,
                      section=Section(coef=(1.0, 0.0), offset=level, direction=direction))
        assert r.status == 0, r.message
        # the crossing time is ill-conditioned near tangency: dt ~ dy / |cos t|
        tol = 1e-9 / math.sqrt(2 * depth)
        np.testing.assert_allclose(r.crossings_t, exact, rtol=0, atol=tol)
        assert np.abs(r.crossings_y[:, 0] - level).max() < 1e-14


def test_section_crossings_agree_across_methods_and_tolerances():
    """The Chaplygin ball on a sphere grazes g3 = 0 near t = 144.6 (down, then up at
    144.853): every method and tolerance finds the same upward crossings."""
    c = registry()[CAVITY]
    from solvers.models.cases import build

    m = build(CAVITY, c.example)
    runs = [integrate(m.model, m.p, c.state, [0.0, 240.0], method=meth, rtol=rtol,
                      atol=rtol * 1e-2, section=Section(coef=(0, 0, 0, 0, 0, 1.0)),
                      max_crossings=100)
            for meth in ("dop853", "vern9") for rtol in (1e-8, 1e-10, 1e-12)]
    ref = runs[-1].crossings_t
    assert ref.size == 8 and abs(ref[4] - 144.85328878) < 1e-7
    for r in runs:
        assert r.crossings_t.size == ref.size
        np.testing.assert_allclose(r.crossings_t, ref, rtol=0, atol=1e-5)
    fine = integrate(m.model, m.p, c.state, np.linspace(0.0, 240.0, 240_001),
                     method="vern9", rtol=1e-12, atol=1e-14)
    g3 = fine.y[:, 5]
    ups = np.flatnonzero((g3[:-1] < 0) & (g3[1:] >= 0))
    np.testing.assert_allclose(fine.t[ups], ref, rtol=0, atol=1e-3)


# --- long runs ---------------------------------------------------------------------------------
def test_unprojected_long_run_reports_bounded_drift():
    """1e4 time units without projection (the 1e5 projected runs: tests/test_longrun.py)."""
    c = registry()[BALL]
    r = simulate(BALL, c.example, c.state, 1e4, method="vern9", samples=101)
    assert r.ok and finite(r)
    assert max(r.stats["drift"].values()) < 1e-7
