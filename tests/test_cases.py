"""Every case of Tables 1-2 integrated: invariants held, agreement with the independent
scipy reference, singularities reported where they happen."""

import numpy as np
import pytest

from solvers.models.cases import registry
from solvers.simulate import simulate


@pytest.mark.slow
def test_energy_and_geometric_integral_over_1000(case_id):
    """Done-when of the solver core: drift <= 1e-12 relative over T = 1000. Run with
    dop853 at rtol 1e-14, the method whose kernels the warm-up compiles (energy drift
    1e-15..9e-14 on these runs); vern9 reaches the same bound at rtol 1e-12
    (docs/performance.md) but would compile one more kernel per case in CI, and
    its kernels are checked bit for bit against the reference in tests/test_small.py."""
    c = registry()[case_id]
    r = simulate(case_id, c.example, c.state, 1000.0, method="dop853", rtol=1e-14, atol=1e-16,
                 samples=2001)
    assert r.ok, r.message
    assert np.all(np.isfinite(r.state))
    assert r.drift("energy") <= 1e-12, r.stats
    if "gamma2" in r.invariants:
        assert r.drift("gamma2") <= 1e-12, r.stats
    for name in r.invariants:      # the case's own integrals, as a record (printed on failure)
        assert r.drift(name) < 1e-9, (name, r.stats["drift"])


def test_agrees_with_scipy_reference(case_id):
    """Same trajectory from the compiled integrator on the compiled field and from scipy's
    DOP853 on the independent NumPy field (solvers/models/reference.py)."""
    c = registry()[case_id]
    ours = simulate(case_id, c.example, c.state, 20.0, rtol=1e-13, atol=1e-14, samples=41)
    ref = simulate(case_id, c.example, c.state, 20.0, method="scipy-dop853", rtol=1e-13,
                   atol=1e-14, samples=41)
    assert ours.ok and ref.ok
    scale = np.max(np.abs(ref.state), axis=0)
    err = np.max(np.abs(ours.state - ref.state) / scale)
    assert err < 1e-9, err


@pytest.mark.parametrize("method", ["dop853", "vern9"])
def test_methods_agree_on_the_chaplygin_ball(method):
    c = registry()["plane/chaplygin-ball"]
    ref = simulate("plane/chaplygin-ball", c.example, c.state, 50.0, method="vern9",
                   rtol=1e-14, atol=1e-16, samples=11)
    r = simulate("plane/chaplygin-ball", c.example, c.state, 50.0, method=method,
                 rtol=1e-10, atol=1e-12, samples=11)
    assert np.max(np.abs(r.state - ref.state)) < 1e-7
    assert r.stats["steps"] > 0 and r.stats["rhs_calls"] >= r.stats["steps"]


def test_projection_holds_integrals_to_round_off():
    c = registry()["plane/chaplygin-ball"]
    r = simulate("plane/chaplygin-ball", c.example, c.state, 1000.0, rtol=1e-8, atol=1e-10,
                 project=True)
    plain = simulate("plane/chaplygin-ball", c.example, c.state, 1000.0, rtol=1e-8,
                     atol=1e-10)
    for name in ("energy", "gamma2", "M2", "area"):
        assert r.drift(name) < 1e-14, (name, r.stats["drift"])
    assert plain.drift("energy") > 100 * r.drift("energy")


def test_disk_falling_flat_stops_with_a_message():
    """A heavy disk released almost flat, without spin, falls: the run stops at the
    singularity sin(theta) = 0 and reports where, returning only finite samples."""
    params = {"I1": 0.25, "I3": 0.5, "m": 1.0, "R": 1.0, "g": 9.81}
    s = 0.05
    r = simulate("plane/round-disk", params, [0, 0, 0, s, 0, np.sqrt(1 - s * s)], 5.0,
                 samples=501)
    assert r.status == "singular"
    assert "flat" in r.message and "t =" in r.message
    assert np.all(np.isfinite(r.state)) and 0 < r.t[-1] < 5.0


def test_body_stops_when_it_no_longer_fits_the_sphere():
    """An elongated ellipsoid in a cavity: fits at the start, not after tipping over."""
    params = {"m": 1.0, "b1": 0.04, "b2": 0.05, "b3": 1.0, "mu": 0.1}
    # a cavity where the flat end fits but the long side does not
    from solvers.errors import InputError
    from solvers.models.cases import build
    with pytest.raises(InputError):
        build("plane/ellipsoid", {**params, "k": 1.0})   # plane case has no k
    r = simulate("sphere/body-of-revolution",
                 {"I1": 0.3, "I3": 0.05, "m": 1.0, "b1": 0.04, "b3": 1.0, "k": 1.2, "g": 9.81},
                 [3.0, 0.0, 0.0, 0.02, 0.0, np.sqrt(1 - 0.02**2)], 50.0, samples=201)
    assert r.status == "singular" and "fit" in r.message
    assert np.all(np.isfinite(r.state))
