"""Section 3, a body with a flat base on a sphere, state (M, r1, r2): (3.16)-(3.21), (3.20)
and the axisymmetric reduced variables (after (3.21)).

gamma = e3 is fixed in the body and r = (r1, r2, z). The paper's (3.17) is read with k the
signed curvature of CONVENTIONS.md (k = -1/R0 < 0 outside a fixed ball, where a flat base
rolls); the paper's own k = +1/R gives the same equations with gamma pointing out of the
support (gamma = (0, 0, -1) in CONVENTIONS.md's orientation), as in solvers/kernels/fields.py.
"""

import numpy as np

from solvers.verify.formulas.general import contact_inertia, flat_field, flat_r, omega_of
from solvers.verify.registry import compares, corrected, formula

E3 = np.eye(3)


def _printed_momentum(P):
    """(3.16) as printed: M = I omega + m gamma x (omega x gamma), gamma = e3."""
    g = np.array([0.0, 0.0, 1.0])
    return lambda r: np.diag(P.I) + P.m * (E3 - np.outer(g, g)) + 0.0 * r[0]


@formula("flat_system")
def flat_system(P, x):
    """(3.16) as printed: dM/dt = M x omega + m dr/dt x (omega x r) with
    M = I omega + m gamma x (omega x gamma), dr/dt of (3.17)."""
    return flat_field(P, x, momentum=_printed_momentum(P))


@corrected("flat_system", "M = I omega + m r x (omega x r) (eq1.6) in eq3.14: the printed "
           "m gamma x (omega x gamma) is a misprint (the measures eq3.16-eq3.18 and the "
           "integral eq* hold with eq1.6's momentum)")
def flat_system_corrected(P, x):
    return flat_field(P, x)


@formula("flat_kinematics")
def flat_kinematics(P, x):
    """(3.17): dr1/dt = omega2/k, dr2/dt = -omega1/k (k signed, see the module docstring),
    closed with (1.1) and (1.6) for dM/dt."""
    return flat_field(P, x, kin=lambda w: np.array([w[1], -w[0], 0.0 * w[0]]) / P.k)


def _r2(P, x):
    r = flat_r(P, x)
    return r @ r


@formula("flat_density_M")
def flat_density_m(P, x):
    """(3.18) (z = 0): rho(M, r1, r2) = (I3 + m r^2)^(-1/2)."""
    return (P.I[2] + P.m * _r2(P, x)) ** -0.5


@formula("flat_density_omega")
def flat_density_omega(P, x):
    """(3.19) (z = 0): rho(omega, r1, r2) = (I1 I2 + m (r, I r))(I3 + m r^2)^(1/2)."""
    r = flat_r(P, x)
    return (P.I[0] * P.I[1] + P.m * (r @ (P.I * r))) * (P.I[2] + P.m * (r @ r)) ** 0.5


@formula("flat_F")
def flat_f(P, x):
    """(3.20): F = M^2 - 2 m r^2 H, H = (M, omega)/2."""
    M, r = x[:3], flat_r(P, x)
    return M @ M - P.m * (r @ r) * (M @ omega_of(P, M, r))


@formula("flat_axisym_density")
def flat_axisym_density(P, x):
    """(3.21) (I1 = I2): rho = (I1 I3 + m (r, I r))^(-1/2)."""
    r = flat_r(P, x)
    return (P.I[0] * P.I[2] + P.m * (r @ (P.I * r))) ** -0.5


def _flat_K_sides(P, x):
    M, r = x[:3], flat_r(P, x)
    rho = flat_axisym_density(P, x)
    w = np.linalg.solve(contact_inertia(P, r), M)
    z, m, I1 = P.z, P.m, P.I[0]
    first = np.array([M @ r, w[2] / rho])
    second = np.array([M[0] * r[0] + M[1] * r[1] + M[2] * r[2],
                       (m * z * (M[0] * r[0] + M[1] * r[1]) + (I1 + m * z * z) * M[2]) * rho])
    return first, second


@formula("flat_axisym_K")
def flat_axisym_k(P, x):
    """After (3.21): K1 = (M, r), K2 = omega3/rho (first forms)."""
    return _flat_K_sides(P, x)[0]


@compares("flat_axisym_K")
def flat_axisym_k_forms(P, x, corrected=False):
    """The printed second forms: K1 = M1 r1 + M2 r2 + M3 r3, K2 = (m z (M1 r1 + M2 r2) +
    (I1 + m z^2) M3) / sqrt(I1 I3 + m (r, I r))."""
    return _flat_K_sides(P, x)
