"""Section 3, bodies on a sphere in the full variables (M, gamma): bodies of revolution (3.2),
(3.3), the disk, the Routh ball ((3.7)'s lambda and tau, (3.9), the gyrostatic Jellett
integral), the balanced nonsymmetric ball (3.10) and the Borisov-Fedorov case (3.11).

k is CONVENTIONS.md's signed curvature (+1/R0 inside a cavity, -1/R0 outside a fixed ball),
which is the reading under which (3.2)-(3.15) hold (solvers/models/reduced_systems.py);
(3.10)'s own k is
the factor R0/(R0 - a) = 1/(1 - k a) of that curvature.
"""

import numpy as np

from solvers.models.revolution import Profile, profile
from solvers.verify.formulas.chaplygin import chaplygin_omega
from solvers.verify.formulas.general import omega_of
from solvers.verify.registry import compares, corrected, formula


def _f(P, u):
    return profile(Profile.from_params(P.p), u)[:4]


def _rho0(P, g):
    """rho0 = (I1 I3 + m (r, I r))^(-1/2) ((3.2), first form)."""
    r = P.r(g)
    return (P.I[0] * P.I[2] + P.m * (r @ (P.I * r))) ** -0.5


@formula("sphere_revolution_density")
def sphere_revolution_density(P, x):
    """(3.2): rho = rho0 (1 - k f1)^3 (1 - k f2'), rho0 = (I1 I3 + m (r, I r))^(-1/2)."""
    g = x[3:6]
    f1, _, _, f2p = _f(P, g[2])
    return _rho0(P, g) * (1 - P.k * f1) ** 3 * (1 - P.k * f2p)


@corrected("sphere_revolution_density", "rho = rho0 (1 - k f1) (1 - k f2'): the printed cube "
           "on (1 - k f1) fails (exponent 1 is the only power of either sign of k that is "
           "invariant); rho0's second form must read ... + m I3 f2^2 (= m (r, I r), as eq2.2), "
           "not ... + m I3 f2^2 g3^2")
def sphere_revolution_density_corrected(P, x):
    g = x[3:6]
    f1, _, _, f2p = _f(P, g[2])
    return _rho0(P, g) * (1 - P.k * f1) * (1 - P.k * f2p)


@compares("sphere_revolution_density")
def sphere_revolution_density_forms(P, x, corrected=False):
    """(3.2)'s two printed forms of rho0^-2: I1 I3 + m (r, I r) and
    I1 I3 + m I1 f1^2 (1 - g3^2) + m I3 f2^2 g3^2 (corrected: f2^2 without g3^2)."""
    g = x[3:6]
    u = g[2]
    f1, f2 = _f(P, u)[:2]
    I1, I3, m = P.I[0], P.I[2], P.m
    last = I3 * m * f2**2 * (1.0 if corrected else u * u)
    return _rho0(P, g) ** -2, I1 * I3 + m * I1 * f1**2 * (1 - u * u) + last


@formula("sphere_revolution_density_table")
def sphere_revolution_density_table(P, x):
    """Table 2: (1 - k f1)^3 (1 - k (g3 f2)') / sqrt(I1 I3 + m (r, I r))."""
    g = x[3:6]
    u = g[2]
    f1, f2, _, f2p = _f(P, u)
    return (1 - P.k * f1) ** 3 * (1 - P.k * (f2 + u * f2p)) * _rho0(P, g)


@corrected("sphere_revolution_density_table", "(1 - k f1) (1 - k f2') / sqrt(I1 I3 + m (r, I r)) "
           "(eq3.2 corrected): the cube and (g3 f2)' both fail ((g3 f2)' = f2' + ... only "
           "differs by a constant factor for the disk, f2 = a)")
def sphere_revolution_density_table_corrected(P, x):
    return sphere_revolution_density_corrected(P, x)


@formula("sphere_revolution_K")
def sphere_revolution_k(P, x):
    """(3.3): K1 = (M, r)(1 - k f1)/f1, K2 = omega3/rho0."""
    M, g = x[:3], x[3:6]
    r = P.r(g)
    f1 = _f(P, g[2])[0]
    return np.array([(M @ r) * (1 - P.k * f1) / f1, omega_of(P, M, r)[2] / _rho0(P, g)])


@formula("sphere_disk_density")
def sphere_disk_density(P, x):
    """Disk on a sphere: rho = rho0 (1 - k R / sqrt(1 - g3^2))^3,
    rho0 = (I1 I3 + m (I1 R^2 + I3 a^2))^(-1/2)."""
    I1, I3, m, R, a = P.I[0], P.I[2], P.m, P.R, P.a[2]
    u = x[5]
    return (I1 * I3 + m * (I1 * R**2 + I3 * a**2)) ** -0.5 * (1 - P.k * R / np.sqrt(1 - u * u)) ** 3


@corrected("sphere_disk_density", "rho0 (1 - k R / sqrt(1 - g3^2)): exponent 1, not 3 "
           "(eq3.2 corrected with f1 = R/sqrt(1 - g3^2), f2' = 0)")
def sphere_disk_density_corrected(P, x):
    I1, I3, m, R, a = P.I[0], P.I[2], P.m, P.R, P.a[2]
    return (I1 * I3 + m * (I1 * R**2 + I3 * a**2)) ** -0.5 * (1 - P.k * R / np.sqrt(1 - x[5] ** 2))


def _routh_q(P):
    """rho0^-2 of the ball (2.18) as c0 + c1 g3 + c2 g3^2."""
    I1, I3, m, R, a = P.I[0], P.I[2], P.m, P.R, P.a[2]
    return I1 * I3 + I1 * m * R**2 + I3 * m * a**2, 2 * I3 * m * R * a, m * R**2 * (I3 - I1)


@formula("sphere_routh_density")
def sphere_routh_density(P, x):
    """Ball on a sphere: rho = (I1 I3 + I1 m R^2 (1 - g3^2) + I3 m (R g3 + a)^2)^(-1/2)."""
    c0, c1, c2 = _routh_q(P)
    u = x[5]
    return (c0 + c1 * u + c2 * u * u) ** -0.5


@formula("sphere_jellett")
def sphere_jellett(P, x):
    """(3.9) (I1 = I3), right member: M1 g1 + M2 g2 + M3 (g3 + a/R) (= (M, r)/R; (3.3)'s K1
    is (M, r)(1 - k R)/R: constant factors apart)."""
    M, g = x[:3], x[3:6]
    return M @ g + M[2] * P.a[2] / P.R


@formula("sphere_gyro_jellett")
def sphere_gyro_jellett(P, x):
    """After (3.15) (I1 = I3), right member: (M/R + S (1 - k R), r)(1 - k R)."""
    M, g = x[:3], x[3:6]
    r = P.r(g)
    c = 1 - P.k * P.R
    return (M / P.R + P.S * c) @ r * c


@corrected("sphere_gyro_jellett", "F2 = K1 + s (1 - k R)^2 (g3 + a/R) = (M + S (1 - k R), r)"
           "(1 - k R)/R: the printed middle member lacks s, the right member has S where S/R "
           "is meant (both agree with this form only for s = 1, resp. R = 1)")
def sphere_gyro_jellett_corrected(P, x):
    M, g = x[:3], x[3:6]
    c = 1 - P.k * P.R
    return (M + P.S * c) @ P.r(g) * c / P.R


def sphere_gyro_jellett_middle(P, x):
    """After (3.15), middle member: K1 + (1 - k R)^2 (g3 + a/R), K1 = (M, r)(1 - k R)/R
    (3.3); it lacks s."""
    M, g = x[:3], x[3:6]
    c = 1 - P.k * P.R
    return (M @ P.r(g)) * c / P.R + c**2 * (g[2] + P.a[2] / P.R)


# --- balanced nonsymmetric ball on a sphere, (3.10)-(3.11) ------------------------------------

def factor_312(P):
    """(3.10)'s k = R0/(R0 - a) (a: ball radius, R0: fixed sphere) = 1/(1 - kappa a) with
    CONVENTIONS.md's signed curvature kappa; -1 in the Borisov-Fedorov case kappa = 2/a."""
    return 1.0 / (1.0 - P.k * P.R)


@formula("sphere_chaplygin_system")
def sphere_chaplygin_system(P, x):
    """(3.10): dM/dt = M x omega, dgamma/dt = k gamma x omega, M = (I + D) omega - D gamma
    (omega, gamma), D = m a^2, k = R0/(R0 - a)."""
    M, g = x[:3], x[3:6]
    w = chaplygin_omega(P, M, g)
    return np.concatenate([np.cross(M, w), factor_312(P) * np.cross(g, w)])


def bf_abar(P):
    """Abar = E - 2 (tr(I + D))^-1 (I + D) of (3.11) (diagonal)."""
    J = P.I + P.D
    return 1.0 - 2.0 * J / np.sum(J)


@formula("bf_integral")
def bf_integral(P, x):
    """(3.11): F = (M, Abar gamma)."""
    return x[:3] @ (bf_abar(P) * x[3:6])


@formula("bf_brun_potential")
def bf_brun_potential(P, x):
    """After (3.11): U = (I gamma, gamma)/2 (unit Brun constant)."""
    g = x[3:6]
    return 0.5 * (P.I * g @ g)


@formula("bf_transform")
def bf_transform(P, x):
    """After (3.11): (M~, gamma~) = (Abar M, gamma)."""
    return np.concatenate([bf_abar(P) * x[:3], x[3:6]])
