"""Section 2, Chaplygin ball on the plane: eq2.16-eq2b-*3, Kozlov's Brun integral."""

import numpy as np

from solvers.verify.registry import formula
from solvers.verify.variables import chaplygin_rho


@formula("chaplygin_density")
def chaplygin_density(P, x):
    """eq2.17: rho = (1 - D (gamma, A gamma))^-1/2, A = (I + D E)^-1, D = m a^2."""
    return chaplygin_rho(P, x[3:6])


@formula("kozlov_brun_F3")
def kozlov_brun_f3(P, x):
    """After eq2.17: F3 = M^2 - k/det A (gamma, A gamma); the paper's k is the Brun constant
    (our eps, U = eps/2 (I gamma, gamma))."""
    M, g = x[:3], x[3:6]
    A = 1.0 / (P.I + P.D)
    return M @ M - P.eps / np.prod(A) * (g @ (A * g))
