"""The exact layer's arithmetic: jets against known derivatives, radicals, exact linear
algebra, and the rational parametrisations exactly on their constraints."""

from fractions import Fraction

import numpy as np
import pytest
from flint import fmpq

from solvers.verify.exact.exact_mode import exact_linalg
from solvers.verify.exact.jet import Jet, Radical
from solvers.verify.exact.linalg import det, solve
from solvers.verify.exact.points import GridRng, pythagorean, sphere_point, stereographic
from solvers.verify.exact.rational import NotRational

X0, Y0 = fmpq(3, 7), fmpq(-5, 11)


def xy():
    return Jet.seed(X0, 0, 2), Jet.seed(Y0, 1, 2)


def test_product_quotient_and_power_rules():
    x, y = xy()
    f = x * x * y / (1 + x)                   # d/dx = y (x^2 + 2x)/(1+x)^2, d/dy = x^2/(1+x)
    assert f.v == X0 ** 2 * Y0 / (1 + X0)
    assert f.g[0] == Y0 * (X0 ** 2 + 2 * X0) / (1 + X0) ** 2
    assert f.g[1] == X0 ** 2 / (1 + X0)
    h = (x - y) ** 3                           # 3 (x - y)^2 (1, -1)
    assert h.g == (3 * (X0 - Y0) ** 2, -3 * (X0 - Y0) ** 2)
    k = x ** -2
    assert k.v == 1 / X0 ** 2 and k.g[0] == -2 / X0 ** 3


def test_sqrt_of_a_square_and_log_derivative():
    x, _ = xy()
    s = (x * x * 4).sqrt()                     # 2|x|, derivative 2 for x > 0
    assert s.v == 2 * X0 and s.g[0] == 2
    lg = np.log(x * x + 1)                     # value unknown, derivative 2x/(x^2+1)
    assert lg.g[0] == 2 * X0 / (X0 ** 2 + 1)
    with pytest.raises(NotRational):
        lg * x                                 # the unknown constant must not be multiplied


def test_radical_derivatives():
    """sqrt(R) with R not a square: value c sqrt(R), d/dy = C_j sqrt(R)."""
    x, y = xy()
    R = 2 + x * x
    r = np.sqrt(R)
    assert isinstance(r, Radical)
    assert r.c.v == 1 and r.c.g[0] == X0 / (2 + X0 ** 2)          # d sqrt(R) = x / sqrt R
    q = y / r                                                    # y R^-1/2
    assert isinstance(q, Radical)
    # q = (y / R) sqrt R: value coefficient y/R, dq/dx = -x y R^-3/2 = (-x y / R^2) sqrt R
    assert q.c.v == Y0 / (2 + X0 ** 2)
    assert q.c.g[0] == -X0 * Y0 / (2 + X0 ** 2) ** 2
    assert (r * r).v == 2 + X0 ** 2                               # back in Q
    assert np.log(r ** 3).g[0] == 3 * X0 / (2 + X0 ** 2)
    s = 1 + r                                                    # in Q(sqrt r)
    t = (s * s - 2 * s).value()                                  # = R - 1, rational again
    assert not isinstance(t, Radical) and t.v == 1 + X0 ** 2
    assert (1 / s * s).v == 1
    assert (r - r).v == 0 and (r > 0) and (-r < 0)
    other = np.sqrt(3 + y * y)                                   # an independent root
    with pytest.raises(NotRational):
        r + other


def test_degree_bounds_follow_the_rules():
    z = Jet(fmpq(2), None, 1, 0)               # one free coordinate
    assert (z * z).n == 2
    q = 1 / (1 + z * z)      # value 1/(1+z^2), derivative rule over Q_a N_b^2: (2, 4)
    assert q.n >= 0 and q.d >= 2 and (q.n, q.d) == (2, 4)


def test_exact_solve_and_det_agree_with_numpy():
    A = np.array([[Jet(fmpq(2)), Jet(fmpq(1, 3)), Jet(0)], [Jet(fmpq(1)), Jet(fmpq(5)),
                  Jet(fmpq(-1))], [Jet(0), Jet(fmpq(2)), Jet(fmpq(7, 2))]], dtype=object)
    b = np.array([Jet(1), Jet(2), Jet(3)], dtype=object)
    x = solve(A, b)
    assert all((A @ x - b)[i].v == 0 for i in range(3))
    Af = np.array([[float(Fraction(int(a.v.p), int(a.v.q))) for a in row] for row in A])
    assert abs(float(Fraction(int(det(A).v.p), int(det(A).v.q))) - np.linalg.det(Af)) < 1e-12
    with exact_linalg():
        assert np.linalg.solve(A, b)[0].v == x[0].v
        assert np.linalg.solve(Af, [1.0, 2.0, 3.0]).dtype == float      # floats untouched


@pytest.mark.parametrize("seed", range(5))
def test_parametrisations_lie_exactly_on_their_constraints(seed):
    rng = GridRng(seed)
    u, v, t, w = (rng.grid(-3, 3) for _ in range(4))
    g = stereographic(u, v)
    assert (g @ g).v == 1
    c, s = pythagorean(t)
    assert (c * c + s * s).v == 1
    g = sphere_point(t, w)
    assert (g @ g).v == 1
    rho = g[0] * g[0] + g[1] * g[1]            # the disk's radicand is a rational square
    assert not isinstance(rho.sqrt(), Radical)


def test_ellipsoid_radicand_is_solved_to_a_square():
    from solvers.kernels import layout as L
    from solvers.verify.exact.points import ellipsoid_radicand, free, rational_gamma
    rng = GridRng(3)
    p = np.array([Jet(0)] * L.N_PARAMS, dtype=object)
    for slot, val in ((L.B11, 2), (L.B22, 3), (L.B33, 5)):
        p[slot] = free(val)
    g = rational_gamma(rng)
    p[L.B33] = ellipsoid_radicand(p, g, rng)
    q = g[0] * g[0] * p[L.B11] + g[1] * g[1] * p[L.B22] + g[2] * g[2] * p[L.B33]
    assert not isinstance(q.sqrt(), Radical)
    # B33 moves by O(2^-20 / g3^2) relative: still the drawn body
    assert abs(p[L.B33].to_float() - 5) < 5e-3
