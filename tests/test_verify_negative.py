"""Negative claims (no measure, no further integral): the verdict of each, with the numbers
behind it, and sanity tests of solvers/verify/checks/negative.py.

Some tests call the checks with fewer points or orbits than `verify` uses, to stay fast;
the quoted numbers are from the default settings.
"""

import numpy as np
import pytest

from catalogue.load import load_catalogue
from solvers.verify.checks import negative as ng
from solvers.verify.checks.common import TOL
from solvers.verify.run import verify

CAT = load_catalogue()


def _case_claim(claim_id):
    return CAT.case(claim_id.rsplit("/", 2)[0]), CAT.claim(claim_id)


def test_unbalanced_ball_plane_no_measure_with_attractors():
    """Fig. ris-*2/ris-*3: no density of gamma alone (c . gamma != 0; measured 0.27, the
    Chaplygin-ball control 2e-15) and orbits that drift monotonically on the section
    (measured: 1 of 2 by 0.14 over t = 30000; control orbits 5e-4)."""
    case, claim = _case_claim("plane/unbalanced-ball/negative/measure")
    out = ng.check_negative_measure(CAT, case, claim)
    assert out.verdict == "evidence", out.message
    ev = out.evidence
    assert ev["position-only density: max |c . normal| / |c|"] > 0.05
    assert ev["control: max |c . normal| / |c|"] < 1e-13
    assert ev["control: max circulation"] < 1e-13
    case_d = ev["section spread per orbit (Kendall tau, relative change), case"]
    ctrl_d = ev["section spread per orbit (Kendall tau, relative change), control"]
    ctrl_change = max(c for _, c in ctrl_d)
    assert ctrl_change < 1e-2
    assert any(abs(t) >= 0.9 and c > 10 * ctrl_change for t, c in case_d)


@pytest.mark.parametrize(("claim_id", "low"), [
    ("plane/unbalanced-ball/negative/hamiltonian", 0.05),    # measured 0.27
    ("sphere/unbalanced-ball/negative/measure", 0.05),       # measured 0.27
    ("sphere/unbalanced-ball/negative/hamiltonian", 0.05),
    ("sphere/flat-base/negative/measure", 1e-3),             # c3 != 0: measured 0.022
    ("sphere/flat-base/negative/hamiltonian", 1e-3),
])
def test_no_position_density(claim_id, low):
    case, claim = _case_claim(claim_id)
    out = ng.check_negative_measure(CAT, case, claim, n_points=6, settings=1, drift=False)
    assert out.verdict == "evidence", out.message
    assert out.residual > low
    assert out.evidence["control: max |c . normal| / |c|"] < 1e-13
    assert out.evidence["control: max circulation"] < 1e-13
    if claim_id.endswith("hamiltonian"):
        assert "Hamiltonian form" in out.message


def test_spherical_inertia_measure_exists_on_a_sphere():
    """Section 2 after eq2.19: the paper could not find the sphere generalisation of
    Yaroschuk's measure and thinks it does not exist. It does: the position-only test is
    at round-off and (mu + m r^2)^-1/2 det(E - k J) satisfies the Liouville equation to
    round-off (measured 7e-16), while (mu + m r^2)^-1/2 itself fails (0.12): the negative
    claim fails."""
    case, claim = _case_claim("plane/spherical-inertia/negative/sphere-generalization")
    out = ng.check_negative_measure(CAT, case, claim, n_points=6, settings=2)
    assert out.verdict == "fails", out.message
    ev = out.evidence
    assert ev["Liouville residual of (mu + m r^2)^-1/2 det(E - k J) (project)"] <= TOL
    assert ev["Liouville residual of (mu + m r^2)^-1/2 (the plane measure)"] > 0.05
    assert "det(E - k J)" in out.message


def test_spherical_inertia_chaotic_layer():
    """Fig. ris-*4: an orbit of the section map fills a three-dimensional layer (median
    s3/s1 measured 0.40 >= 0.15; the integrable ball control 0.00)."""
    case, claim = _case_claim("plane/spherical-inertia/negative/integrals")
    out = ng.check_negative_integral(CAT, case, claim)
    assert out.verdict == "evidence", out.message
    assert out.residual >= ng.THICK[3]
    assert out.evidence["control: max median s3/s1"] < 0.05


@pytest.mark.parametrize("claim_id", ["plane/ellipsoid/negative/integrals",
                                      "sphere/chaplygin-ball/negative/third-integral"])
def test_regular_maps_are_inconclusive(claim_id):
    """At the drawn parameters every scanned orbit is thin: the ellipsoid (lambda = 1) max
    median s3/s1 0.00 over 8 orbits; the Chaplygin ball on a sphere max median s2/s1 0.08
    over 8 orbits (the Borisov-Fedorov control 0.04; also at k R = 0.9 and -2.5): no
    chaotic layer, so no evidence either way -- reported as unchecked, not as a verdict."""
    case, claim = _case_claim(claim_id)
    out = ng.check_negative_integral(CAT, case, claim, n_orbits=3)
    assert out.verdict == "unchecked", out.message
    assert "inconclusive" in out.message


def test_registered_and_run_through_verify():
    """The flat base's 'no measure' claim now rests on the exact proof (check no_measure,
    tests/test_nonexistence.py; it was `evidence` from negative_measure); negative_measure
    stays registered for the claim it decides (the spherical-inertia body on a sphere)."""
    from solvers.verify.registry import CHECKS

    recs = verify(case="sphere/flat-base", claim="sphere/flat-base/negative/measure")
    assert [r["verdict"] for r in recs] == ["verified"]
    assert recs[0]["check"] == "no_measure"
    assert recs[0]["evidence"]["control"].startswith("z = 0")
    assert CHECKS["negative_measure"] is ng.check_negative_measure


# --- sanity of the tools --------------------------------------------------------------------

def test_thickness_of_synthetic_sets():
    rng = np.random.default_rng(0)
    t = rng.uniform(0, 2 * np.pi, 1500)
    s = rng.uniform(0, 2 * np.pi, 1500)
    curve = np.stack([np.cos(t), np.sin(t), 0.3 * np.cos(3 * t), 0 * t, 0 * t, 0 * t], 1)
    torus = np.stack([(2 + np.cos(s)) * np.cos(t), (2 + np.cos(s)) * np.sin(t), np.sin(s),
                      0 * t, 0 * t, 0 * t], 1)
    blob = np.concatenate([rng.uniform(-1, 1, (1500, 3)), np.zeros((1500, 3))], 1)
    c21, _ = ng.orbit_thickness(curve + 1e-9 * rng.standard_normal(curve.shape), 5)
    t21, t31 = ng.orbit_thickness(torus + 1e-9 * rng.standard_normal(torus.shape), 5)
    _, b31 = ng.orbit_thickness(blob + 1e-9 * rng.standard_normal(blob.shape), 5)
    assert c21 < ng.THICK[2] and t21 > ng.THICK[2] and t31 < ng.THICK[3] < b31


def test_position_density_test_on_known_measures():
    """Chaplygin ball (eq2.17) and flat base z = 0 (eq3.16): both conditions at round-off;
    the divergence is linear in M, as the test assumes."""
    rng = np.random.default_rng(1)
    for claim_id in ("plane/unbalanced-ball/negative/measure", "sphere/flat-base/negative/measure"):
        case, claim = _case_claim(claim_id)
        P = ng.case_params(case, claim, rng)
        Pc, _ = ng.control_params(case, P, ng.CONTROLS)
        n, c = ng.position_density_test(Pc, rng, 4)
        assert n < 1e-13 and c < 1e-13
        y = ng.random_states(P, 1, rng)[0]
        pos = ng._position(P, y)
        assert ng.omega_coefficients(P, pos / (1.0 if ng._flat(P) else np.linalg.norm(pos)))[1] \
            < 1e-13
