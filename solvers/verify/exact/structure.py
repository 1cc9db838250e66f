"""Exact residuals of the Poisson-structure checks (solvers/verify/checks/structure.py):
the Jacobi identity of a printed tensor and the Hamiltonian form after a change of time."""

import numpy as np

from solvers.verify.checks.structure import bracket_fn, hamiltonian_parts, state_vars
from solvers.verify.exact.certify import directional, plain, residual_vector, seeded
from solvers.verify.exact.jet import Jet
from solvers.verify.exact.model import field
from solvers.verify.variables import to_vars


def _values(X):
    return np.array([Jet.const(c).value() for c in np.atleast_1d(X)], dtype=object)


def jacobi(catalogue, claim, use_corrected):
    """J_il d_l J_jk + J_jl d_l J_ki + J_kl d_l J_ij and J + J^T, all entries."""
    J = bracket_fn(catalogue, claim, use_corrected)
    V = state_vars(catalogue, claim.check_args.bracket)

    def res(P, y):
        x = _values(to_vars(V, P, plain(y)))
        Jx = np.asarray(J(P, seeded(x)), dtype=object)
        n = len(x)
        J0 = np.array([[Jet.const(Jx[i, j]).value() for j in range(n)] for i in range(n)],
                      dtype=object)
        dJ = [[[Jet.const(Jx[j, k]).partial(l) for k in range(n)] for j in range(n)]
              for l in range(n)]
        out = [J0[i, j] + J0[j, i] for i in range(n) for j in range(i, n)]
        for i in range(n):
            for j in range(n):
                for k in range(n):
                    out.append(sum((J0[i, l] * dJ[l][j][k] + J0[j, l] * dJ[l][k][i]
                                    + J0[k, l] * dJ[l][i][j] for l in range(n)), Jet(0)))
        return residual_vector(np.array(out, dtype=object))
    return res


def hamiltonian(catalogue, claim, use_corrected):
    """(1/N) dx/dt - J grad H, dx/dt the exact field pushed forward to the bracket's
    variables (through check_args.transform when given)."""
    a = claim.check_args
    J, Hf, Nf, to_b = hamiltonian_parts(catalogue, claim, use_corrected)

    def res(P, y):
        v = field(P, plain(y))
        X = to_b(P, seeded(y))
        xdot = directional(X, v)
        x = _values(X)
        N = 1 if Nf is None else Jet.const(
            Nf(P, to_vars(state_vars(catalogue, a.multiplier), P, plain(y)))).value()
        lhs = xdot / N
        Hx = Jet.const(Hf(P, seeded(x)))
        grad = np.array([Hx.partial(j) for j in range(len(x))], dtype=object)
        Jx = np.asarray(J(P, x), dtype=object)
        rhs = Jx @ grad
        return residual_vector(lhs - rhs)
    return res
