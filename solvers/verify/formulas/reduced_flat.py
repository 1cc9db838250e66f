"""Section 3 b), axisymmetric body with a flat base on a sphere (I1 = I2, z != 0), in
(u, K1, K2): u = r1^2 + r2^2, K1 = (M, r), K2 = omega3/rho ((3.21)-(3.26), (3.23) .. (3.25)).

R is 1/k with the signed curvature of CONVENTIONS.md (k < 0: outside a fixed ball), the
reading under which (3.26) holds (solvers/models/reduced_systems.py). Abbreviation:
    sq(u) = sqrt(I3 (I1 + m z^2) + I1 m u) = sqrt(I1 I3 + m (r, I r)) = 1/rho.

Solutions (role `solution`) take x = (u, c1, c2) -- the independent variable and the
constants -- and return (K1, K2); the particular solution takes x = (u,).
"""

import numpy as np

from solvers.models import reduced_systems as rd
from solvers.verify.registry import corrected, formula


def _prm(P):
    I1, I3 = P.I[0], P.I[2]
    return I1, I3, P.m, P.z, 1.0 / P.k, P.S[2]


def sq(P, u):
    I1, I3, m, z, _, _ = _prm(P)
    return np.sqrt(I3 * (I1 + m * z * z) + I1 * m * u)


@formula("flat_axisym_linear")
def flat_axisym_linear(P, x):
    """(3.22) as printed: dK1/du = (I1 - I3) K2/(2R sq), dK2/du = +m K1/(2R sq)."""
    return rd.eq3_19_printed(P.p, x[0], x[1:3])


@corrected("flat_axisym_linear", "dK2/du = -m K1/(2R sq) (eq3.21 at s = 0; the sign of "
           "the product of the two coefficients does not depend on the sign convention of R)")
def flat_axisym_linear_corrected(P, x):
    return rd.eq3_19(P.p, x[0], x[1:3])


@formula("flat_axisym_gyro_linear")
def flat_axisym_gyro_linear(P, x):
    """(3.26): 2R dK1/du = (I1 - I3) K2/sq - s, 2R dK2/du = -m (K1 + z s)/sq."""
    return rd.eq3_21(P.p, x[0], x[1:3])


@formula("flat_axisym_solution")
def flat_axisym_solution(P, x):
    """(3.23): K1 = sqrt(I1 - I3)(-c1 cos phi + c2 sin phi), K2 = sqrt(m)(c1 sin phi +
    c2 cos phi), phi^2 = (I1 - I3)(I1 I3 + I3 m z^2 + I1 m u)/(I1^2 m R^2).

    Evaluated literally: for I1 < I3 (the case it is printed for) sqrt(I1 - I3) and phi are
    imaginary and so is the result (principal root). Only phi^2 is printed; the root is
    phi = sqrt(I1 - I3) sq(u)/(I1 sqrt(m) R) with the same sqrt(I1 - I3) and R = 1/k, the
    only one that can solve a system of the form of (3.22) (its sign is tied to that of
    R); written through sq(u), phi is analytic in u (no branch cut of sqrt(phi^2))."""
    I1, I3, m, _, R, _ = _prm(P)
    u, c1, c2 = x[0], x[1], x[2]
    beta = np.sqrt(complex(I1 - I3)) if I1 < I3 else np.sqrt(I1 - I3)
    phi = beta * sq(P, u) / (I1 * np.sqrt(m) * R)
    return np.array([beta * (-c1 * np.cos(phi) + c2 * np.sin(phi)),
                     np.sqrt(m) * (c1 * np.sin(phi) + c2 * np.cos(phi))])


@corrected("flat_axisym_solution", "with the corrected eq3.19 (dK2/du = -m K1/(2R sq)) the "
           "printed trigonometric form is the real solution for I1 > I3 (not I1 < I3); for "
           "I1 < I3 the real solutions are hyperbolic: K1 = sqrt(I3 - I1)(c1 ch psi - c2 sh "
           "psi), K2 = sqrt(m)(-c1 sh psi + c2 ch psi), psi = sqrt(I3 - I1) sq(u)/(I1 "
           "sqrt(m) R), psi^2 = (I3 - I1)(I1 I3 + I3 m z^2 + I1 m u)/(I1^2 m R^2)")
def flat_axisym_solution_corrected(P, x):
    I1, I3, m, _, R, _ = _prm(P)
    if I1 > I3:
        return flat_axisym_solution(P, x)
    u, c1, c2 = x[0], x[1], x[2]
    al = np.sqrt(I3 - I1)
    psi = al * sq(P, u) / (I1 * np.sqrt(m) * R)
    return np.array([al * (c1 * np.cosh(psi) - c2 * np.sinh(psi)),
                     np.sqrt(m) * (-c1 * np.sinh(psi) + c2 * np.cosh(psi))])


def _particular(P, u, sign):
    I1, I3, _, z, R, s = _prm(P)
    K1 = s * z * (I3 + sign * I1 * (1 + R / z)) / (I1 - I3) + 0.0 * u
    return np.array([K1, s * sq(P, u) / (I1 - I3)])


@formula("flat_axisym_particular")
def flat_axisym_particular(P, x):
    """After (3.26): K1p = s z (I3 + I1 (1 + R/z))/(I1 - I3), K2p = s sq(u)/(I1 - I3)."""
    return _particular(P, x[0], +1.0)


@corrected("flat_axisym_particular", "K1p = s z (I3 - I1 (1 + R/z))/(I1 - I3) (minus before "
           "I1); with it both equations of eq3.21 hold")
def flat_axisym_particular_corrected(P, x):
    return _particular(P, x[0], -1.0)


@formula("flat_axisym_quadratic")
def flat_axisym_quadratic(P, x):
    """(3.24): F = m K1^2 + (I1 - I3) K2^2."""
    I1, I3, m = P.I[0], P.I[2], P.m
    return m * x[1] ** 2 + (I1 - I3) * x[2] ** 2


def _gyro_quadratic(P, x, part):
    I1, I3, m = P.I[0], P.I[2], P.m
    Kp = part(P, x[:1])
    return m * (x[1] - Kp[0]) ** 2 + (I1 - I3) * (x[2] - Kp[1]) ** 2


@formula("flat_axisym_gyro_quadratic")
def flat_axisym_gyro_quadratic(P, x):
    """F = m (K1 - K1p)^2 + (I1 - I3)(K2 - K2p)^2 with the printed particular solution."""
    return _gyro_quadratic(P, x, flat_axisym_particular)


@corrected("flat_axisym_gyro_quadratic", "with the corrected particular solution "
           "K1p = s z (I3 - I1 (1 + R/z))/(I1 - I3)")
def flat_axisym_gyro_quadratic_corrected(P, x):
    return _gyro_quadratic(P, x, flat_axisym_particular_corrected)


def _energy(P, x, printed):
    if len(x) < 4:
        raise LookupError("eq-***3 contains du/dt, which the variables (u, K1, K2) do not "
                          "carry; pass x = (u, K1, K2, du/dt) (checks/ode.py does)")
    I1, I3, m, z, R, _ = _prm(P)
    u, K1, K2, ud = x[:4]
    root = sq(P, u)
    kin = (I1 + m * z * z + m * u) / (8 * R * R * u) * ud * ud
    # printed cross term -z/(I1^2 u) sq K1 K2; from (M, omega)/2 it is -2 z sq K1 K2
    cross = z / (I1 * I1 * u) * root if printed else 2 * z * root
    return kin + ((I1 + m * z * z) * K1**2 + (I1 * u + I3 * z * z) * K2**2
                  - cross * K1 * K2) / (2 * I1 * I1 * u)


@formula("flat_axisym_energy")
def flat_axisym_energy(P, x):
    """(3.25) (U = 0 here): H = (I1 + m z^2 + m u) udot^2/(8 R^2 u) + ((I1 + m z^2) K1^2
    + (I1 u + I3 z^2) K2^2 - z/(I1^2 u) sq K1 K2)/(2 I1^2 u); x = (u, K1, K2, du/dt)."""
    return _energy(P, x, printed=True)


@corrected("flat_axisym_energy", "the K1 K2 term inside the bracket is -2 z sq K1 K2, not "
           "-z/(I1^2 u) sq K1 K2 (derived from (M, omega)/2 with omega3 = rho K2 and "
           "K1 = sqrt(u) I1 omega_rho + z I3 omega3; the K1^2, K2^2 and udot^2 terms are "
           "right as printed)")
def flat_axisym_energy_corrected(P, x):
    return _energy(P, x, printed=False)
