"""Gauss-Legendre collocation methods: the coefficients, computed, not tabulated.

The s-stage Gauss method (order 2s, symmetric, symplectic) has nodes c_i = the roots of
the shifted Legendre polynomial P_s(2x - 1), a_ij = int_0^{c_i} l_j, b_j = int_0^1 l_j
(l_j: Lagrange basis on the nodes). The nodes are irrational, so unlike the explicit
tableaux (`solvers/integrate/tableaux/*.yaml`, published rationals) they are computed here in
50-digit arithmetic (mpmath) and rounded once to float64. The kernel is
`solvers.kernels.gauss`; tests check the simplifying assumptions B(2s), C(s), D(s) and
the symmetry of the rounded coefficients.
"""

from dataclasses import dataclass
from functools import cache

import mpmath
import numpy as np

METHODS = {"gauss4": 2, "gauss6": 3, "gauss8": 4}     # name -> stages s (order 2s)
DIGITS = 50


@dataclass(frozen=True, eq=False)
class Collocation:
    name: str
    order: int
    A: np.ndarray       # (s, s) full
    b: np.ndarray
    c: np.ndarray
    X: np.ndarray       # X[i, j] = l_j(1 + c_i): starting values from the previous step

    @property
    def stages(self) -> int:
        return self.b.size


def _lagrange(c, j):
    """Coefficients (highest first) of l_j, as mpf."""
    poly = [mpmath.mpf(1)]
    den = mpmath.mpf(1)
    for q, cq in enumerate(c):
        if q != j:
            poly = [a - cq * b for a, b in zip([*poly, 0], [0, *poly], strict=True)]
            den *= c[j] - cq
    return [a / den for a in poly]


def exact(s: int):
    """(A, b, c) of the s-stage Gauss method as nested lists of mpf (DIGITS digits)."""
    with mpmath.workdps(DIGITS):
        c = sorted((1 + x) / 2 for x in mpmath.polyroots(
            mpmath.taylor(lambda x: mpmath.legendre(s, x), 0, s)[::-1],
            maxsteps=200, extraprec=200))
        A, b, X = [], [], []
        for j in range(s):
            lj = _lagrange(c, j)
            integral = [a / (s - k) for k, a in enumerate(lj)] + [0]   # antiderivative
            b.append(mpmath.polyval(integral, 1))
            A.append([mpmath.polyval(integral, ci) for ci in c])
            X.append([mpmath.polyval(lj, 1 + ci) for ci in c])
        A = [[A[j][i] for j in range(s)] for i in range(s)]             # A[i][j]
        X = [[X[j][i] for j in range(s)] for i in range(s)]
        return A, b, c, X


@cache
def load(name: str) -> Collocation:
    if name not in METHODS:
        raise ValueError(f"unknown collocation method {name!r}; one of {sorted(METHODS)}")
    s = METHODS[name]
    A, b, c, X = exact(s)
    f = np.vectorize(float, otypes=[np.float64])
    return Collocation(name, 2 * s, np.ascontiguousarray(f(np.array(A, dtype=object))),
                       f(np.array(b, dtype=object)), f(np.array(c, dtype=object)),
                       np.ascontiguousarray(f(np.array(X, dtype=object))))
