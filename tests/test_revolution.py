"""Profiles of bodies of revolution (solvers.models.revolution): eq2.1, eq2.1/2, eq2.28, eq2.71,
2-14*, against the compiled support function (support.py) and by complex step."""

import numpy as np
import pytest
from conftest import revolution_body

from solvers.kernels import layout as L
from solvers.kernels.reduced import rev_profile
from solvers.models import revolution as rv

KINDS = [("ellipsoid", 0.0), ("ellipsoid", 0.25), ("rounded", 0.0), ("rounded", -0.2),
         ("disk", 0.0), ("disk", 0.3), ("ball", 0.0), ("ball", 0.2)]
U = np.array([-0.93, -0.6, -0.31, -0.05, 0.12, 0.4, 0.77, 0.95])


@pytest.mark.parametrize(("kind", "a"), KINDS)
def test_meridian_condition_eq2_1_2(kind, a):
    prof = rv.Profile.from_params(revolution_body(kind, a=a))
    res = rv.meridian_residual(prof, U)
    scale = np.abs(rv.profile(prof, U)[3]) + np.abs(rv.profile(prof, U)[0]) + 1.0
    assert np.max(np.abs(res) / scale) < 1e-14


@pytest.mark.parametrize(("kind", "a"), KINDS)
def test_profile_is_kernel_support_eq2_1(kind, a):
    p = revolution_body(kind, a=a)
    rng = np.random.default_rng(3)
    for _ in range(20):
        g = rng.normal(size=3)
        g /= np.linalg.norm(g)
        assert rv.support_residual(p, g) < 1e-14


@pytest.mark.parametrize(("kind", "a"), KINDS)
def test_profile_derivatives_by_complex_step(kind, a):
    prof = rv.Profile.from_params(revolution_body(kind, a=a))
    h = 1e-30
    f = rv.profile(prof, U)
    fc = rv.profile(prof, U + 1j * h)
    for i, j in ((0, 2), (1, 3), (2, 4), (3, 5)):      # f1->f1', f2->f2', f1'->f1'', f2'->f2''
        assert np.allclose(fc[i].imag / h, f[j], rtol=1e-13, atol=1e-13)
    ph = rv.phi_derivs(prof, U)
    phc = rv.phi_derivs(prof, U + 1j * h)
    for i in range(3):
        assert np.allclose(phc[i].imag / h, ph[i + 1], rtol=1e-13, atol=1e-13)


def test_closed_forms_per_part():
    u = U
    s = np.sqrt(1 - u * u)
    # ellipsoid eq2.28: f1 = b1/sqrt(q), f2 = b3 u/sqrt(q)
    prof = rv.Profile(0.8, 0.3, 0.0, 0.0, 0.0)
    q = 0.8 * s * s + 0.3 * u * u
    f1, f2 = rv.profile(prof, u)[:2]
    assert np.allclose(f1, 0.8 / np.sqrt(q), rtol=1e-15)
    assert np.allclose(f2, 0.3 * u / np.sqrt(q), rtol=1e-15)
    # disk eq2.71: f1 = R/sqrt(1-u^2), f2 = a
    f1, f2 = rv.profile(rv.Profile(0.0, 0.0, 0.0, 0.9, 0.3), u)[:2]
    assert np.allclose(f1, 0.9 / s, rtol=1e-15)
    assert np.allclose(f2, 0.3, rtol=1e-14)
    # Routh ball 2-14*: f1 = R, f2 = R u + a
    f1, f2 = rv.profile(rv.Profile(0.0, 0.0, 0.7, 0.0, 0.2), u)[:2]
    assert np.allclose(f1, 0.7, rtol=1e-15)
    assert np.allclose(f2, 0.7 * u + 0.2, rtol=1e-15)


@pytest.mark.parametrize(("kind", "a"), KINDS)
def test_compiled_profile_matches(kind, a):
    p = revolution_body(kind, a=a)
    prof = rv.Profile.from_params(p)
    out = np.empty(6)
    for u in U:
        rev_profile(p, u, out)
        ph, d1 = rv.phi_derivs(prof, u)[:2]
        f1, f2, f1p, f2p = rv.profile(prof, u)[:4]
        assert np.allclose(out, [ph, d1, f1, f2, f1p, f2p], rtol=1e-14, atol=1e-15)


@pytest.mark.parametrize(("kind", "a"), KINDS)
def test_gravity_potential_is_m_g_phi(kind, a):
    """U = m g (r, gamma) = m g phi(gamma3) on the unit sphere (h(gamma) = (r, gamma))."""
    p = revolution_body(kind, a=a)
    prof = rv.Profile.from_params(p)
    for u in U:
        g = np.array([np.sqrt(1 - u * u) * 0.6, np.sqrt(1 - u * u) * 0.8, u])
        f1, f2 = rv.profile(prof, u)[:2]
        r = np.array([f1 * g[0], f1 * g[1], f2])
        assert abs(r @ g - rv.phi(prof, u)) < 1e-14


def test_not_a_body_of_revolution_is_refused():
    p = revolution_body("ellipsoid")
    p[L.B22] = 0.5
    with pytest.raises(ValueError, match="B11 != B22"):
        rv.Profile.from_params(p)
    p = revolution_body("ball")
    p[L.I2] = 2.5
    with pytest.raises(ValueError, match="I1 != I2"):
        rv.Profile.from_params(p)
