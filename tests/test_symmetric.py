"""The symmetric Gauss collocation methods (solvers.integrate.collocation, solvers.kernels.gauss):
their coefficients, their order, their symmetry, and what symmetry buys on the rolling
bodies (no secular drift of the integrals), plus the run options that go with them."""

import mpmath
import numpy as np
import pytest

from solvers.errors import InputError
from solvers.integrate import collocation
from solvers.integrate.integrator import initial_integrals, integrate
from solvers.kernels import gauss
from solvers.kernels import layout as L
from solvers.models.cases import build, initial_state, registry
from solvers.simulate import simulate
from tests.test_integrator import KEP, P0, TWO_PI, kepler

METHODS = tuple(collocation.METHODS)


@pytest.mark.parametrize("name", METHODS)
def test_coefficients_satisfy_B_C_D_in_50_digits(name):
    """Gauss: B(2s) (quadrature of order 2s), C(s) (collocation), D(s), exactly up to
    the 50-digit arithmetic they are computed in; and symmetric once rounded."""
    s = collocation.METHODS[name]
    A, b, c, X = collocation.exact(s)
    with mpmath.workdps(collocation.DIGITS):
        eps = mpmath.mpf(10) ** (-40)
        for k in range(1, 2 * s + 1):
            quad = mpmath.fsum(b[i] * c[i] ** (k - 1) for i in range(s))
            assert abs(quad - mpmath.mpf(1) / k) < eps
        for k in range(1, s + 1):
            for i in range(s):
                lhs = mpmath.fsum(A[i][j] * c[j] ** (k - 1) for j in range(s))
                assert abs(lhs - c[i] ** k / k) < eps
            for j in range(s):
                lhs = mpmath.fsum(b[i] * c[i] ** (k - 1) * A[i][j] for i in range(s))
                assert abs(lhs - b[j] * (1 - c[j] ** k) / k) < eps
        # the starting-value weights reproduce polynomials of degree < s at 1 + c_i
        for k in range(s):
            for i in range(s):
                assert abs(mpmath.fsum(X[i][q] * c[q] ** k for q in range(s))
                           - (1 + c[i]) ** k) < eps
    m = collocation.load(name)
    r = slice(None, None, -1)
    # symmetry of the method: c_i + c_{s+1-i} = 1, b_i = b_{s+1-i},
    # a_ij + a_{s+1-i, s+1-j} = b_j, to the rounding of each coefficient
    assert np.allclose(m.c + m.c[r], 1.0, rtol=0, atol=2e-16)
    assert np.allclose(m.b, m.b[r], rtol=0, atol=2e-16)
    assert np.allclose(m.A + m.A[r, r], m.b[None, :], rtol=0, atol=4e-16)


@pytest.mark.parametrize("name", METHODS)
def test_empirical_order_is_2s_on_kepler(name):
    """Constant steps over one period of Kepler e = 0.5: slope of log error vs log h."""
    order = collocation.load(name).order
    Ns = {"gauss4": (200, 800), "gauss6": (60, 200), "gauss8": (66, 200)}[name]
    hs, errs = [], []
    for N in np.unique(np.round(np.geomspace(*Ns, 6)).astype(int)):
        r = integrate(KEP, P0, kepler(0.0), [0.0, TWO_PI], method=name, h_fixed=TWO_PI / N)
        assert r.success and r.steps == N
        hs.append(TWO_PI / N)
        errs.append(np.abs(r.y[-1] - kepler(TWO_PI)).max())
    errs = np.array(errs)
    assert errs.max() < 1e-4 and errs.min() > 1e-14, errs
    p = np.polyfit(np.log(hs), np.log(errs), 1)[0]
    assert abs(p - order) <= 0.5, p


def _case(cid):
    spec = registry()[cid]
    model = build(cid, spec.example)
    return model, initial_state(model, spec.state)


def _reverse(y):
    """The reversing involution of the rolling equations in (M, gamma): M -> -M."""
    return np.r_[-y[:3], y[3:]]


@pytest.mark.parametrize("cid", ["plane/chaplygin-ball", "plane/routh-ball",
                                 "plane/round-disk"])
def test_symmetric_step_runs_back_to_the_start_under_reversal(cid):
    """Phi_h is symmetric and the field is reversible (M -> -M, t -> -t), so
    R Phi_h^N R Phi_h^N y0 = y0 up to round-off, even at a step where the trajectory
    itself is only accurate to ~1e-6. An explicit method (rk45, same step) comes back
    only to its truncation error. Measured: gauss4 back 4e-16 / 2e-15 / 2e-12 for
    trajectory errors 9e-7 / 4e-6 / 0.1; rk45 back 1e-7 / 5e-6 / 0.5."""
    model, y0 = _case(cid)
    h, T = 0.25, 50.0
    fine = integrate(model.model, model.p, y0, [0, T], method="vern9", rtol=1e-14,
                     atol=1e-14).y[-1]

    def there_and_back(method):
        a = integrate(model.model, model.p, y0, [0, T], method=method, h_fixed=h)
        b = integrate(model.model, model.p, _reverse(a.y[-1]), [0, T], method=method,
                      h_fixed=h)
        assert a.success and b.success
        return np.abs(a.y[-1] - fine).max(), np.abs(_reverse(b.y[-1]) - y0).max()

    traj_g, back_g = there_and_back("gauss4")
    traj_e, back_e = there_and_back("rk45")
    assert back_g < 1e-11 and traj_g > 1e4 * back_g, (traj_g, back_g)
    assert back_e > 0.1 * traj_e and back_e > 1e4 * back_g, (traj_e, back_e, back_g)


@pytest.mark.parametrize("cid", ["plane/chaplygin-ball", "sphere/borisov-fedorov"])
def test_no_secular_drift_of_the_integrals(cid):
    """gauss8 with a constant step over 2e4 time units (5e4 steps): every integral's
    error over the second half is no larger than twice its largest error over the first
    1e3 time units, or than the round-off random walk of 5e4 steps (Brouwer's law:
    ~1e-16 sqrt(steps) = 2e-14, bounded here by 5e-14): no secular drift. gamma^2, a
    quadratic invariant, is kept by Gauss methods exactly (round-off only). An adaptive
    explicit method at a lower or equal cost drifts: its energy error grows tenfold."""
    model, y0 = _case(cid)
    T, h = 2e4, 0.4
    t = np.linspace(0.0, T, 2001)
    v0 = initial_integrals(model.model, model.p, y0, model.integral_codes)

    def drift(res):
        v = np.array([initial_integrals(model.model, model.p, y, model.integral_codes)
                      for y in res.y])
        return np.abs(v - v0) / np.maximum(np.abs(v0), 1.0)

    g = integrate(model.model, model.p, y0, t, method="gauss8", h_fixed=h)
    assert g.success
    d = drift(g)
    early, late = d[t <= 1e3].max(axis=0), d[t >= T / 2].max(axis=0)
    assert np.all(late <= 2 * np.maximum(early, 2.5e-14)), (early, late)
    assert d.max() < 1e-12, d.max(axis=0)
    gamma2 = list(model.integral_names).index("gamma2")
    assert d[:, gamma2].max() < 3e-13
    v = integrate(model.model, model.p, y0, t, method="vern9", rtol=1e-10, atol=1e-10)
    assert v.rhs_calls <= g.rhs_calls
    dv = drift(v)
    energy = list(model.integral_names).index("energy")
    assert dv[t >= T / 2, energy].max() > 10 * dv[t <= 1e3, energy].max()


def test_too_large_a_step_stops_with_a_message_not_nan():
    model, y0 = _case("plane/round-disk")
    r = integrate(model.model, model.p, y0, np.linspace(0, 50, 11), method="gauss8",
                  h_fixed=5.0)
    assert r.status == gauss.NO_CONVERGENCE and not r.success
    assert "smaller step" in r.message and "stopped at t = 0" in r.message
    assert np.all(np.isfinite(r.y)) and len(r.t) == 1


def test_step_budget():
    model, y0 = _case("plane/chaplygin-ball")
    r = integrate(model.model, model.p, y0, [0, 100], method="gauss6", h_fixed=0.1,
                  max_steps=50)
    assert r.budget_exhausted and r.steps == 50 and r.t_stop == pytest.approx(5.0)


def test_simulate_options_of_a_symmetric_method():
    spec = registry()["plane/chaplygin-ball"]
    res = simulate("plane/chaplygin-ball", spec.example, spec.state, 100.0,
                   method="gauss8", step=0.2, samples=201)
    # equal steps <= 0.2 that land on the samples, 0.5 apart: three of 1/6 each
    assert res.ok and res.stats["steps"] == 600
    assert res.stats["step"] == pytest.approx(0.5 / 3) and res.stats["step_requested"] == 0.2
    assert max(res.stats["drift"].values()) < 1e-14
    bad = [dict(method="gauss8"),                       # no step
           dict(method="vern9", step=0.1),              # a step for an adaptive method
           dict(method="gauss8", step=-0.1),
           dict(method="gauss8", step=float("nan")),
           dict(method="gauss8", step=0.2, project=True),
           dict(method="gauss8", step=1e-6, max_steps=1000)]
    for kw in bad:
        with pytest.raises(InputError):
            simulate("plane/chaplygin-ball", spec.example, spec.state, 100.0, **kw)


def test_field_status_reaches_the_caller():
    """A singular rhs inside the stages (disk lying flat) stops the run with its status."""
    model, _ = _case("plane/round-disk")
    y = np.array([0.0, 0.0, 0.0, 0.0, 0.0, 1.0])      # gamma along the axis: flat disk
    r = integrate(model.model, model.p, y, [0, 1], method="gauss4", h_fixed=0.1)
    assert not r.success and r.status < 20 and r.status != L.OK
    assert np.all(np.isfinite(r.y_stop))


def test_stiff_near_contact_stops_with_a_message():
    """1 - kR = 1e-6 (a ball that barely fits its cavity): off the sphere |gamma| = 1 the
    field is amplified by 1/(1 - kR), so the fixed-point iteration of the implicit stages
    cannot contract at any step that resolves the motion. The run stops at once, saying
    why; the adaptive explicit methods do this run (tests/test_extremes.py)."""
    cid = "sphere/chaplygin-ball"
    spec = registry()[cid]
    r = simulate(cid, {**spec.example, "k": 1.0 - 1e-6}, spec.state, 1e-5, samples=11,
                 method="gauss8", step=1e-8)
    assert r.status == "singular" and "implicit stages could not be solved" in r.message
    assert np.all(np.isfinite(r.state))
