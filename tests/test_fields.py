"""The compiled vector fields against the independent NumPy field and the paper's forms."""

import numpy as np
import pytest
from conftest import random_states

from solvers.kernels import integrals as Q
from solvers.kernels import layout as L
from solvers.kernels.support import support
from solvers.models.cases import build, registry
from solvers.models.derivatives import field, integral_rate
from solvers.models.reference import field as ref_field
from solvers.models.reference import omega_eq1_6


def with_potentials(case_id):
    """Example parameters with gravity, Brun field and gyrostat switched on where allowed."""
    c = registry()[case_id]
    extra = {"g": 0.7, "eps": 0.3, "S1": 0.2, "S2": -0.1, "S3": 0.25}
    return {**c.example, **{k: v for k, v in extra.items() if k in c.param_names}}


def test_compiled_field_equals_independent_field(case_id):
    model = build(case_id, with_potentials(case_id))
    rng = np.random.default_rng(1)
    for y in random_states(model, 50, rng, 0.3):
        d, status = field(model.model, model.p, y)
        assert status == L.OK
        e = ref_field(model.model, model.p, y)
        assert np.max(np.abs(d - e)) <= 1e-13 * np.max(np.abs(d)) + 1e-15


def test_energy_is_conserved_pointwise(case_id):
    """dH/dt = grad H . v = 0 at random phase points, by complex step (eq1.7)."""
    model = build(case_id, with_potentials(case_id))
    rng = np.random.default_rng(2)
    rates = [integral_rate(Q.ENERGY, model.model, model.p, y)
             for y in random_states(model, 200, rng, 0.5)]
    assert max(rates) < 1e-13


def test_declared_integrals_hold_pointwise(case_id):
    """Every integral the case declares (under its example parameters) has zero rate."""
    model = build(case_id, registry()[case_id].example)
    rng = np.random.default_rng(3)
    for name, code in zip(model.integral_names, model.integral_codes, strict=True):
        rates = [integral_rate(code, model.model, model.p, y)
                 for y in random_states(model, 200, rng, 0.5)]
        assert max(rates) < 1e-12, (name, max(rates))


@pytest.mark.parametrize(("case_id", "param", "name"), [
    ("plane/chaplygin-ball", "eps", "M2"),            # M^2 needs U = 0
    ("plane/chaplygin-ball", "S1", "area"),           # (M, gamma) needs S = 0
    ("plane/unbalanced-ball", "g", "unbalanced_F"),   # eq-d*2 needs U = 0
    ("plane/routh-ball", "S3", "routh"),              # eq2.15 without the rotor
    ("sphere/borisov-fedorov", "eps", "M2"),          # Brun field breaks M^2 ...
    ("sphere/borisov-fedorov", "S2", "borisov_fedorov"),
    ("sphere/flat-base", "S3", "unbalanced_F"),
])
def test_integrals_fail_without_their_condition(case_id, param, name):
    """The condition in cases.yaml is real: break it and the integral stops holding."""
    c = registry()[case_id]
    model = build(case_id, {**c.example, param: 0.4})
    rng = np.random.default_rng(4)
    rates = [integral_rate(Q.NAMES.index(name), model.model, model.p, y)
             for y in random_states(model, 20, rng, 0.5)]
    assert max(rates) > 1e-4


def test_borisov_fedorov_integral_survives_the_brun_field():
    """eq3.13 (M, Abar gamma) holds unchanged with U = eps/2 (I gamma, gamma): the paper says
    it 'can be generalized' to the Brun field; the generalization is the same function."""
    c = registry()["sphere/borisov-fedorov"]
    model = build("sphere/borisov-fedorov", {**c.example, "eps": 0.7})
    assert "borisov_fedorov" in model.integral_names
    rng = np.random.default_rng(9)
    rates = [integral_rate(Q.BORISOV_FEDOROV, model.model, model.p, y)
             for y in random_states(model, 200, rng, 0.5)]
    assert max(rates) < 1e-13


def test_support_point_matches_paper_formulas():
    rng = np.random.default_rng(5)
    p = np.zeros(L.N_PARAMS)
    for _ in range(50):
        g = rng.standard_normal(3)
        g /= np.linalg.norm(g)
        r, J = np.empty(3), np.empty((3, 3))
        # ball with displaced centre: r = R gamma + a (eq-d*1)
        p[:] = 0
        p[L.BALL_C], p[L.A1:L.A3 + 1] = 1.3, [0.1, -0.2, 0.3]
        support(p, g, r, J)
        assert np.allclose(r, 1.3 * g + [0.1, -0.2, 0.3], atol=1e-15)
        # ellipsoid: r = B gamma / sqrt(B gamma . gamma) lies on (r, B^-1 r) = 1 (eq2.28)
        p[:] = 0
        b = np.array([1.0, 2.0, 0.5])
        p[L.B11], p[L.B22], p[L.B33] = b
        support(p, g, r, J)
        assert np.isclose(r @ (r / b), 1.0, rtol=1e-14)
        assert np.allclose(r, b * g / np.sqrt(b * g @ g), atol=1e-15)
        # disk: r = (R g1/s, R g2/s, a), s = sqrt(g1^2 + g2^2) (eq2.71)
        p[:] = 0
        p[L.DISK_D], p[L.A3] = 0.8, 0.25
        support(p, g, r, J)
        s = np.hypot(g[0], g[1])
        assert np.allclose(r, [0.8 * g[0] / s, 0.8 * g[1] / s, 0.25], atol=1e-15)


def test_gauss_map_jacobian_is_symmetric_and_kills_gamma():
    """J = Hess h: symmetric, J gamma = 0 (degree-1 homogeneity), i.e. (dr, gamma) = 0."""
    rng = np.random.default_rng(6)
    p = np.zeros(L.N_PARAMS)
    p[L.B11], p[L.B22], p[L.B33], p[L.B12] = 1.0, 2.0, 0.5, 0.3
    p[L.BALL_C], p[L.DISK_D], p[L.A1] = 0.2, 0.1, 0.4
    r, J = np.empty(3), np.empty((3, 3))
    for _ in range(50):
        g = rng.standard_normal(3)
        support(p, g, r, J)
        assert np.allclose(J, J.T, atol=1e-14)
        assert np.allclose(J @ g, 0.0, atol=1e-13)
        # J is the derivative of r (complex step of the kernel itself)
        for j in range(3):
            gc = g.astype(complex)
            gc[j] += 1e-30j
            rc, Jc = np.empty(3, complex), np.empty((3, 3), complex)
            support(p, gc, rc, Jc)
            assert np.allclose(rc.imag / 1e-30, J[:, j], atol=1e-13)


def test_balanced_ball_on_sphere_is_eq3_12():
    """eq3.12: dM/dt = M x w, dgamma/dt = K gamma x w with K = R0/(R0 - a) (k = 1/R0)."""
    rng = np.random.default_rng(7)
    for k in (0.3, -0.4, 2.0):  # cavity, outside, Borisov-Fedorov (K = -1)
        a = 1.0
        model = build("sphere/chaplygin-ball" if k != 2.0 else "sphere/borisov-fedorov",
                      {"I1": 1.0, "I2": 2.0, "I3": 2.5, "m": 1.2, "R": a,
                       **({"k": k} if k != 2.0 else {})})
        K = 1.0 / (1.0 - k * a)
        for y in random_states(model, 30, rng, 0.5):
            d, _ = field(model.model, model.p, y)
            M, g = y[:3], y[3:]
            D = model.p[L.MASS] * a * a
            Iv = model.p[L.I1:L.I3 + 1]
            # omega from eq3.12's M = (I + D) w - D gamma (w, gamma)
            A = np.diag(Iv + D) - D * np.outer(g, g)
            w = np.linalg.solve(A, M)
            assert np.allclose(d[:3], np.cross(M, w), atol=1e-13)
            assert np.allclose(d[3:], K * np.cross(g, w), atol=1e-13)


def test_eq1_6_printed_sign_is_a_misprint():
    """eq1.6 prints omega = (A M - m r x (A r x A M)) / (1 - m (r, A r)); only '+' inverts
    M = I w + m r x (w x r). Measured: printed form off by O(1), corrected form 1e-16."""
    rng = np.random.default_rng(8)
    p = np.zeros(L.N_PARAMS)
    p[L.I1:L.I3 + 1], p[L.MASS] = [1.0, 2.0, 3.0], 1.3
    worst_printed, worst_fixed = 0.0, 0.0
    for _ in range(100):
        r, w = rng.standard_normal(3), rng.standard_normal(3)
        M = p[L.I1:L.I3 + 1] * w + p[L.MASS] * np.cross(r, np.cross(w, r))
        worst_fixed = max(worst_fixed, np.max(abs(omega_eq1_6(p, M, r) - w)) / np.max(abs(w)))
        worst_printed = max(worst_printed,
                            np.max(abs(omega_eq1_6(p, M, r, sign=-1.0) - w)) / np.max(abs(w)))
    assert worst_fixed < 1e-13
    assert worst_printed > 1e-2
