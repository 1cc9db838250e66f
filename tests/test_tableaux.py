"""Butcher tableaux: consistency, agreement with scipy's copies, and the order conditions.

Order conditions by rooted trees (Butcher): a method with weights w has order p iff
Phi(t) = w . Psi(t) = 1/gamma(t) for every rooted tree t with |t| <= p, where Psi(leaf) =
(1, ..., 1) and Psi(t)_i = prod over the subtrees u of t of (A Psi(u))_i. A continuous
extension b_i(theta) has order q iff sum_i b_i(theta) Psi(t)_i = theta^|t| / gamma(t) for
|t| <= q, checked here coefficient by coefficient in theta. Each check is made in
extended precision with the published rationals/decimals (they carry 30-40 digits, so the
residual must be far below float64 round-off) and in float64 with the tableau the
integrator uses; each method must also FAIL at order p + 1, so a wrong order is caught.
"""

from dataclasses import replace
from functools import cache

import mpmath as mp
import numpy as np
import pytest
from scipy.integrate import _ivp

from solvers.integrate import tableaux as T

EXACT_TOL = 1e-24       # the data has >= 30 significant digits (DOP853: scipy's 30)
FLOAT_TOL = 1e-13
FAIL_MIN = 1e-9         # a violated condition of order p + 1 is far larger than this


@cache
def forests(m):
    """All multisets (sorted tuples) of rooted trees with total order m."""
    if m == 0:
        return frozenset({()})
    out = set()
    for k in range(1, m + 1):
        for t in trees(k):
            out.update(tuple(sorted((*f, t))) for f in forests(m - k))
    return frozenset(out)


@cache
def trees(n):
    """Rooted trees of order n, a tree being the sorted tuple of its subtrees."""
    return sorted(forests(n - 1))


def order(t):
    return 1 + sum(order(u) for u in t)


def gamma(t):
    g = order(t)
    for u in t:
        g *= gamma(u)
    return g


def test_tree_counts():
    # OEIS A000081: 1, 1, 2, 4, 9, 20, 48, 115, 286, 719
    assert [len(trees(n)) for n in range(1, 11)] == [1, 1, 2, 4, 9, 20, 48, 115, 286, 719]


class Conditions:
    """Elementary weights of one tableau, in mpmath (exact data) or float64."""

    def __init__(self, tab, exact):
        self.exact = exact
        if exact:
            mp.mp.dps = 60
            self.conv = lambda v: [mp.mpf(x.numerator) / x.denominator for x in v]
            self.A = [self.conv(row) for row in tab.A]
        else:
            self.A = np.asarray(tab.A, dtype=float)
        self.S = len(tab.c)
        self.memo = {}

    def psi(self, t):
        if t not in self.memo:
            if self.exact:
                v = [mp.mpf(1)] * self.S
                for u in t:
                    pu = self.psi(u)
                    v = [v[i] * mp.fsum(self.A[i][j] * pu[j] for j in range(i))
                         for i in range(self.S)]
            else:
                v = np.ones(self.S)
                for u in t:
                    v = v * (self.A @ self.psi(u))
            self.memo[t] = v
        return self.memo[t]

    def weight(self, w, t):
        ps = self.psi(t)
        if self.exact:
            return mp.fsum(x * p for x, p in zip(self.conv(w), ps[:len(w)], strict=True))
        return float(np.dot(np.asarray(w, dtype=float), ps[:len(w)]))

    def residual(self, w, n):
        """max over trees of order n of |Phi(t) - 1/gamma(t)|."""
        return max(abs(self.weight(w, t) - mp.mpf(1) / gamma(t)) for t in trees(n))


def weight_sets(tab):
    yield "b", tab.b, tab.order
    for row, q in zip(tab.b_hat, tab.b_hat_order, strict=True):
        yield f"b_hat{q}", row, q


@pytest.mark.parametrize("exact", [True, False], ids=["extended", "float64"])
@pytest.mark.parametrize("name", T.METHODS)
def test_order_conditions(name, exact):
    tab = T.load_exact(name) if exact else T.load(name)
    cond = Conditions(tab, exact)
    tol = EXACT_TOL if exact else FLOAT_TOL
    for label, w, p in weight_sets(tab):
        for n in range(1, p + 1):
            assert cond.residual(w, n) < tol, f"{name} {label}: order {n} condition fails"
        assert cond.residual(w, p + 1) > FAIL_MIN, f"{name} {label}: is of order {p + 1}"


@pytest.mark.parametrize("name", T.METHODS)
def test_dense_output_order(name):
    tab = T.load_exact(name)
    cond = Conditions(tab, exact=True)
    P = [cond.conv(row) for row in tab.dense]
    degree = len(P[0])

    def residual(n):
        res = mp.mpf(0)
        for t in trees(n):
            ps = cond.psi(t)
            for j in range(degree):   # coefficient of theta^(j+1)
                val = mp.fsum(P[i][j] * ps[i] for i in range(cond.S))
                res = max(res, abs(val - (mp.mpf(1) / gamma(t) if j + 1 == n else 0)))
        return res

    for n in range(1, tab.dense_order + 1):
        assert residual(n) < EXACT_TOL, f"{name} dense output: order {n} fails"
    assert residual(tab.dense_order + 1) > FAIL_MIN


def test_declared_orders():
    got = {m: (T.load(m).order, T.load(m).b_hat_order, T.load(m).dense_order,
               T.load(m).stages, len(T.load(m).c)) for m in T.METHODS}
    assert got == {"dop853": (8, (5, 3), 7, 12, 16), "vern9": (9, (8,), 8, 16, 21),
                   "rk45": (5, (4,), 4, 7, 7)}


def test_dop853_equals_scipy():
    coef = _ivp.dop853_coefficients
    tab = T.load("dop853")
    assert np.array_equal(tab.c, coef.C)
    assert np.array_equal(tab.A, coef.A)
    assert np.array_equal(tab.b, coef.B)
    assert np.array_equal(tab.e[0], coef.E5[:12]) and coef.E5[12] == 0
    # scipy stores E3 = b - bhh by a float subtraction; ours is the exact difference, rounded
    assert np.allclose(tab.e[1], coef.E3[:12], rtol=0, atol=1e-16)
    assert coef.E3[12] == 0


def test_dop853_dense_output_equals_scipy():
    """Our polynomial weights reproduce scipy's Dop853DenseOutput (Hairer's form)."""
    coef = _ivp.dop853_coefficients
    tab = T.load("dop853")
    rng = np.random.default_rng(1)
    K = rng.normal(size=(16, 3))
    h, y0 = 0.37, rng.normal(size=3)
    dy = h * coef.B @ K[:12]
    F = np.empty((7, 3))
    F[0] = dy
    F[1] = h * K[0] - dy
    F[2] = 2 * dy - h * (K[12] + K[0])
    F[3:] = h * coef.D @ K
    ref = _ivp.rk.Dop853DenseOutput(0.0, h, y0, F)
    for theta in (0.0, 0.1, 0.5, 0.77, 1.0):
        w = tab.dense @ theta ** np.arange(1, 8)
        assert np.allclose(y0 + h * w @ K, ref(theta * h), rtol=0, atol=1e-13)


def test_rk45_equals_scipy():
    tab, ref = T.load("rk45"), _ivp.RK45
    assert np.array_equal(tab.c[:6], ref.C) and tab.c[6] == 1
    assert np.array_equal(tab.A[:6, :5], ref.A)
    assert np.array_equal(tab.b[:6], ref.B)
    assert np.allclose(tab.e[0], -ref.E, rtol=1e-15, atol=0)
    assert np.allclose(tab.dense, ref.P, rtol=0, atol=1e-14)


@pytest.mark.parametrize("breaking", ["upper", "row_sum", "b_sum", "new_stage", "dense"])
def test_inconsistent_tableau_is_refused(breaking):
    tab = T.load("rk45")
    A, b, c, P = tab.A.copy(), tab.b.copy(), tab.c.copy(), tab.dense.copy()
    kw = {}
    if breaking == "upper":
        A[1, 2] = 1e-3
        kw = {"A": A}
    elif breaking == "row_sum":
        c[3] += 1e-12
        kw = {"c": c}
    elif breaking == "b_sum":
        b[0] += 1e-12
        kw = {"b": b}
    elif breaking == "new_stage":
        kw = {"new_stage": 5}
    else:
        P[2, 1] += 1e-9
        kw = {"dense": P}
    with pytest.raises(ValueError, match="inconsistent Butcher tableau"):
        replace(tab, **kw)


def test_unknown_method():
    with pytest.raises(KeyError, match="unknown method"):
        T.load("rk4_classic")
