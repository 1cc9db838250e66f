"""Exact checks behind the rubber tables' "no measure" cells (solvers/models/rubber_exact.py):
the unbalanced ball on a plane and on a sphere and the triaxial ellipsoid have no invariant
density depending on gamma alone, shown by an exact non-zero obstruction (the curl of the
1-form the density's logarithm would need) at a rational point, for the case's parameters
written as exact rationals. The exact field is first compared with rubber_lagrange.py's at a
point of N, so the obstruction is computed for the equations the project integrates."""

import numpy as np
import pytest
import sympy as sp

from solvers.models import rubber_bodies as rb
from solvers.models import rubber_exact as rx
from solvers.models import rubber_lagrange as rl
from solvers.models import rubber_proofs as rp

R = sp.Rational
G = rx.G
GAMMA0 = (R(1, 9), R(4, 9), R(8, 9))   # on |gamma| = 1; also g.B g = 225/81 for B = (1, 2, 3)
H = 1e-30


_exact = rp.exact


def _case_field(case_id):
    """The case's body (rubber_bodies.CASES) and its exact sympy field, as a function of
    where gamma is put (rubber_exact.body_field's `at`; None: the symbols g)."""
    b = rb.body(case_id)
    r = sp.Matrix([_exact(x) for x in b.a])
    if any(b.B):
        B = sp.diag(*[_exact(x) for x in b.B])
        r = r + B * G / sp.sqrt(G.dot(B * G))
    if b.c:
        r = r + _exact(b.c) * G          # the ball: any extension off |gamma| = 1 will do
    assert not b.d
    scale = 1 / (1 - _exact(b.k) * _exact(b.c))
    return b, lambda at=None: rx.body_field([_exact(x) for x in b.I], _exact(b.m),
                                            _exact(b.g), r, scale, at)


CASES = ["rubber-plane/unbalanced-ball", "rubber-plane/ellipsoid",
         "rubber-sphere/unbalanced-ball"]


@pytest.mark.parametrize("case_id", CASES)
def test_no_density_of_gamma_alone_exact(case_id):
    b, field = _case_field(case_id)
    v = field()
    # the exact field is the one integrated: d omega/dt against rubber_lagrange at a point
    y = rl.state_on_manifold(b, [0.3, -0.2, 0.5], [0.2, 0.4, 0.8])
    w_dot = rl.omega(b, y + 1j * H * rl.field(b, y)).imag / H
    at = dict(zip(rx.X, [*rl.omega(b, y), *y[3:]], strict=True))
    exact = np.array([float(e.subs(at)) for e in v])
    assert np.allclose(exact[:3], w_dot, rtol=1e-10, atol=1e-12)
    assert np.allclose(exact[3:], rl.field(b, y)[3:], rtol=1e-12, atol=1e-14)
    # the obstruction: exact rationals, the curl is not zero
    div0, curl = rx.gamma_density_obstruction(field, GAMMA0)
    assert div0.is_Rational and curl.is_Rational
    assert curl != 0, (case_id, curl)


def test_the_obstruction_vanishes_where_a_density_exists():
    """Control: the Chaplygin ball (density Q^(1/2)) and the body with spherical inertia
    (density (mu + m r^2)(mu + m (r, gamma)^2)^(1/2)) give a zero curl at the same point."""
    for case_id in ("rubber-plane/chaplygin-ball", "rubber-plane/spherical-inertia"):
        _b, field = _case_field(case_id)
        assert rx.gamma_density_obstruction(field, GAMMA0) == (0, 0), case_id


# the disk and the ellipsoid of revolution reduce in seconds and run here; the body of
# revolution and the body with spherical inertia take minutes and are kept proved in
# solvers/models/rubber_proofs.json (python -m solvers.models.rubber_proofs)
LIVE_CASES = ["rubber-plane/ellipsoid-of-revolution", "rubber-plane/round-disk"]


@pytest.mark.parametrize("case_id", LIVE_CASES)
def test_revolution_density_exact(case_id):
    """rho = (I1 + m r^2) N(gamma) is an invariant density on N: the residual of the
    Liouville equation reduces to zero exactly, for the case's parameters as rationals."""
    assert rx.revolution_density_residuals(**rp.surface_params(case_id)) == [0, 0, 0]


@pytest.mark.parametrize("case_id", rp.STORED_CASES)
def test_revolution_density_exact_stored(case_id):
    """The same proof for the body of revolution and the body with spherical inertia
    (I1 = I3), as stored: run on the current rubber_exact.py and the case's current
    parameters (else the fingerprint differs: run the module again), every remainder zero."""
    record = rp.stored()[case_id]
    assert record["fingerprint"] == rp.fingerprint(case_id), \
        f"stale proof of {case_id}: run python -m solvers.models.rubber_proofs {case_id}"
    assert record["residuals"] == ["0", "0", "0"]


def test_revolution_density_check_fails_a_wrong_density():
    """Control: without the factor I1 + m r^2 the same reduction leaves a remainder."""
    kw = rp.surface_params("rubber-plane/ellipsoid-of-revolution")
    res = rx.revolution_density_residuals(**kw, density=lambda r, P1, N2: sp.log(N2) / 2)
    assert any(x != 0 for x in res)
