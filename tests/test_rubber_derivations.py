"""The two derivations of rubber rolling agree: Newton-Euler with a contact force and a
multiplier (solvers/models/rubber_newton.py) against Lagrange-d'Alembert in (M, gamma)
(solvers/models/rubber_lagrange.py), at random states of every rubber case, to round-off;
and the comparison is sensitive: a derivation with a wrong term does not pass it."""

import dataclasses
import zlib

import numpy as np
import pytest

from solvers.errors import InputError
from solvers.models import rubber_bodies as rb
from solvers.models import rubber_lagrange as rl
from solvers.models import rubber_newton as rn

CASES = sorted(rb.CASES)
ROUND_OFF = 1e-12


def _seeds(b, rng):
    g = rng.normal(size=3)
    if b.d:                     # keep the disk off its flat position
        g[2] *= 0.3
    return rng.normal(size=3), g


def _rel(a, b):
    return float(np.max(np.abs(a - b)) / max(np.max(np.abs(b)), 1e-300))


@pytest.mark.parametrize("case_id", CASES)
def test_fields_agree_on_the_constraint_manifold(case_id):
    b = rb.body(case_id)
    rng = np.random.default_rng(zlib.crc32(case_id.encode()))
    for _ in range(25):
        y = rl.state_on_manifold(b, *_seeds(b, rng))
        fa = rn.field(b, y)
        fb, lam_b = rl.field_and_multiplier(b, y)
        assert _rel(fa, fb) < ROUND_OFF
        assert abs(rn.multiplier(b, y) - lam_b) < ROUND_OFF * max(1.0, abs(lam_b))
        assert abs(rl.spin(b, y)) < ROUND_OFF


@pytest.mark.parametrize("case_id", CASES)
def test_fields_agree_off_the_manifold_too(case_id):
    """Both keep (omega, gamma) at its value, so they are the same field on R^6."""
    b = rb.body(case_id)
    rng = np.random.default_rng(7)
    for _ in range(10):
        y = rl.state_on_manifold(b, *_seeds(b, rng)) + 0.2 * rng.normal(size=6)
        assert _rel(rn.field(b, y), rl.field(b, y)) < ROUND_OFF


@pytest.mark.parametrize("case_id", ["rubber-plane/unbalanced-ball", "rubber-sphere/ball-over",
                                     "rubber-plane/round-disk"])
def test_supports_agree(case_id):
    """The paper's per-body r(gamma) and the support function's gradient are one surface."""
    b = rb.body(case_id)
    rng = np.random.default_rng(3)
    for _ in range(10):
        g = _seeds(b, rng)[1]
        g /= np.linalg.norm(g)
        r, J = b.support_grad_hess(g)
        assert np.allclose(r, b.r_paper(g), rtol=0, atol=1e-14)
        assert np.allclose(J, b.jacobian_cs(g), rtol=0, atol=1e-13)


def test_comparison_detects_a_wrong_curvature():
    """A sign error in k in one derivation shows up far above round-off."""
    b = rb.body("rubber-sphere/ball-inside")
    wrong = dataclasses.replace(b, k=-b.k)
    y = rl.state_on_manifold(b, [0.3, -0.5, 0.7], [0.2, 0.3, 0.9])
    assert _rel(rn.field(wrong, y), rl.field(b, y)) > 1e-3


def test_the_reaction_torque_is_needed():
    """Without lambda gamma (the marble equations) the spin (omega, gamma) would change."""
    b = rb.body("rubber-plane/ellipsoid")
    y = rl.state_on_manifold(b, [0.3, -0.5, 0.7], [0.2, 0.3, 0.9])
    f, lam = rl.field_and_multiplier(b, y)
    assert abs(lam) > 1e-3
    marble = f.copy()
    marble[:3] -= lam * y[3:]
    h = 1e-30
    rate = (rl.spin(b, y + 1j * h * marble)).imag / h
    assert abs(rate) > 1e-3
    assert abs((rl.spin(b, y + 1j * h * f)).imag / h) < ROUND_OFF


@pytest.mark.parametrize("bad", [dict(m=-1.0), dict(I=(1.0, 0.0, 1.0)), dict(c=-0.5),
                                 dict(g=1.0, k=0.5), dict(eps=1.0, k=0.5),
                                 dict(nonsense=1.0)])
def test_bad_parameters_are_refused(bad):
    with pytest.raises(InputError):
        rb.body("rubber-sphere/ball-over" if "k" not in bad else "rubber-plane/chaplygin-ball",
                **bad)


def test_unknown_case_is_refused():
    with pytest.raises(InputError, match="unknown rubber case"):
        rb.body("rubber-plane/no-such-body")
