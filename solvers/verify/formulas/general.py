"""Section 1 (equations of motion (1.1)-(1.7), (3.1)) and the integrals every (M, gamma)
model shares, plus the plain-NumPy mechanics the other formula modules build on.

Everything here is written from the paper's formulas and CONVENTIONS.md, independently of
the compiled kernels (solvers/kernels/fields.py), and is complex-safe: r(gamma) and
J = dr/dgamma come from the body's support function (Params.r, Params.J), omega from
(1.6) by a linear solve, dU/dgamma in closed form for the model's potential
U = m g (r, gamma) + eps/2 (I gamma, gamma).

A printed *partial* system (only dgamma/dt, or only dr/dt) is returned as a field on the
whole state: the missing dM/dt is (1.1) closed with the formula's own kinematics
(dr/dt = J dgamma/dt) and M = (1.6), so comparing it with the model's field tests exactly
the printed kinematic equation.
"""

import numpy as np

from solvers.kernels import layout as L
from solvers.verify.registry import corrected, formula

E3 = np.eye(3)


# --- mechanics shared by the formula modules ----------------------------------------------

def is_flat(P):
    return P.model.model == L.MODEL_FLAT


def flat_r(P, x):
    """r = (r1, r2, z) of a flat base (3.16), x = (M, r1, r2) or (omega, r1, r2)."""
    return np.array([x[3], x[4], P.z + 0.0 * x[3]])


def contact_inertia(P, r):
    """I_Q = I + m (r^2 E - r r^T) ((1.6) as a matrix: M = I_Q omega)."""
    return np.diag(P.I) + P.m * ((r @ r) * E3 - np.outer(r, r))


def omega_of(P, M, r):
    """omega from M = I omega + m r x (omega x r) (1.6) by a linear solve."""
    return np.linalg.solve(contact_inertia(P, r), M)


def dU(P, g):
    """dU/dgamma of U = m g (r(gamma), gamma) + eps/2 (I gamma, gamma)."""
    return P.m * P.g * (P.r(g) + P.J(g).T @ g) + P.eps * P.I * g


def U(P, g):
    return P.m * P.g * (P.r(g) @ g) + 0.5 * P.eps * (P.I * g @ g)


def gamma_dot(P, g, w):
    """dgamma/dt = (E - k J)^-1 gamma x omega: (1.2) (k = 0) and (1.3) with CONVENTIONS.md's
    signed curvature k."""
    if P.k == 0.0:
        return np.cross(g, w)
    return np.linalg.solve(E3 - P.k * P.J(g), np.cross(g, w))


def torque(P, g):
    """M_Q = gamma x (E - k J^T)^-1 dU/dgamma (section 1, cases a and b)."""
    d = dU(P, g)
    if P.k != 0.0:
        d = np.linalg.solve(E3 - P.k * P.J(g).T, d)
    return np.cross(g, d)


def moment_rate(P, M, w, r, rd, MQ, S=None):
    """(1.1) (gyrostat: M + S): dM/dt = (M + S) x omega + m dr/dt x (omega x r) + M_Q."""
    MS = M if S is None else M + S
    return np.cross(MS, w) + P.m * np.cross(rd, np.cross(w, r)) + MQ


def close_with(P, x, gd, S=None):
    """The full (M, gamma) field made of (1.1) + (1.6) and a printed dgamma/dt `gd`."""
    M, g = x[:3], x[3:6]
    w = omega_of(P, M, P.r(g))
    gdot = gd(w) if callable(gd) else gd
    rd = P.J(g) @ gdot
    return np.concatenate([moment_rate(P, M, w, P.r(g), rd, torque(P, g), S), gdot])


def flat_field(P, x, S=None, momentum=None, kin=None):
    """The flat-base field (M, r1, r2): (1.1) with r = (r1, r2, z), gamma = e3 fixed,
    dr/dt = -(1/k) gamma x omega = (omega2, -omega1, 0)/k (CONVENTIONS.md: 0 = gamma x omega
    + k dr/dt). `momentum` (r -> M(omega) matrix) and `kin` (omega -> dr/dt) replace (1.6)
    and that kinematics by a printed variant."""
    M, r = x[:3], flat_r(P, x)
    A = contact_inertia(P, r) if momentum is None else momentum(r)
    w = np.linalg.solve(A, M)
    rd = np.array([w[1], -w[0], 0.0 * w[0]]) / P.k if kin is None else kin(w)
    return np.concatenate([moment_rate(P, M, w, r, rd, 0.0 * M, S), rd[:2]])


def omega_full(P, x):
    """omega at a full state (M, gamma) or (M, r1, r2)."""
    r = flat_r(P, x) if is_flat(P) else P.r(x[3:6])
    return omega_of(P, x[:3], r)


def kinetic(P, x):
    return 0.5 * (x[:3] @ omega_full(P, x))


# --- (1.1)-(1.7) ----------------------------------------------------------------------------

@formula("full_dynamics")
def full_dynamics(P, x):
    """(1.1) closed by (1.2)/(1.3) (dr/dt = J dgamma/dt), (1.6) and the torque of section 1;
    (M, r1, r2) for a flat base. No gyrostat: (1.1) has none (gyrostat_dynamics has S)."""
    if is_flat(P):
        return flat_field(P, x)
    return close_with(P, x, lambda w: gamma_dot(P, x[3:6], w))


@formula("gyrostat_dynamics")
def gyrostat_dynamics(P, x):
    """Section 2, gyrostatic generalizations: (1.1) with (M + S) x omega."""
    if is_flat(P):
        return flat_field(P, x, S=P.S)
    return close_with(P, x, lambda w: gamma_dot(P, x[3:6], w), S=P.S)


@formula("plane_kinematics")
def plane_kinematics(P, x):
    """(1.2): dgamma/dt = gamma x omega (closed with (1.1), (1.6))."""
    return close_with(P, x, lambda w: np.cross(x[3:6], w))


@formula("sphere_kinematics")
def sphere_kinematics(P, x):
    """(1.3): R0 (dgamma/dt + omega x gamma) = dr/dt = J dgamma/dt, i.e.
    (E - k J) dgamma/dt = gamma x omega with k = 1/R0 read as CONVENTIONS.md's signed
    curvature (+1/R0 inside a cavity, -1/R0 outside a fixed ball)."""
    g = x[3:6]
    return close_with(P, x, lambda w: np.linalg.solve(E3 - P.k * P.J(g), np.cross(g, w)))


def weingarten(P, g):
    """B = dgamma/dr = J^-1 on the tangent plane, 0 along gamma ((1.5)'s b_ij): for unit
    gamma, J gamma = 0 and (J + gamma gamma^T)^-1 = J_t^-1 + gamma gamma^T. Undefined where J
    is degenerate on the tangent plane (the sharp edge of a disk)."""
    gg = np.outer(g, g)
    return np.linalg.inv(P.J(g) + gg) - gg


@formula("sphere_kinematics_B")
def sphere_kinematics_b(P, x):
    """(1.5): dgamma/dt = (1 + k (B - k)^-1) gamma x omega, k signed (CONVENTIONS.md)."""
    g = x[3:6]
    if P.k == 0.0:
        return close_with(P, x, lambda w: np.cross(g, w))
    B = weingarten(P, g)
    T = E3 + P.k * np.linalg.inv(B - P.k * E3)
    return close_with(P, x, lambda w: T @ np.cross(g, w))


@formula("sphere_kinematics_signed")
def sphere_kinematics_signed(P, x):
    """(3.1) as printed: dgamma/dt = gamma x omega -+ k dr/dt, k = 1/R0, '-' for the interior.
    With CONVENTIONS.md's signed k (> 0 inside): dgamma/dt = gamma x omega - k dr/dt."""
    g = x[3:6]
    return close_with(P, x, lambda w: np.linalg.solve(E3 + P.k * P.J(g), np.cross(g, w)))


@corrected("sphere_kinematics_signed", "eq3.1's sign attached to the interior reversed: "
           "dgamma/dt = gamma x omega + k dr/dt with k = +1/R0 inside, -1/R0 outside "
           "(eq1.3, eq-d*-1 and eq3.12 of the paper itself follow this sign)")
def sphere_kinematics_signed_corrected(P, x):
    return sphere_kinematics(P, x)


@formula("momentum")
def momentum(P, x):
    """(1.6)'s explicit inverse as printed: omega = (A M - m r x (A r x A M))/(1 - m (r, A r)),
    A = (I + m r^2)^-1 (returns omega; the printed minus sign is a known misprint,
    solvers/models/reference.py)."""
    return _omega_explicit(P, x, -1.0)


@corrected("momentum", "eq1.6's inverse with + m r x (A r x A M): the printed minus does not "
           "invert M = I omega + m r x (omega x r)")
def momentum_corrected(P, x):
    return _omega_explicit(P, x, +1.0)


def _omega_explicit(P, x, sign):
    M, g = x[:3], x[3:6]
    r = P.r(g)
    A = 1.0 / (P.I + P.m * (r @ r))
    AM, Ar = A * M, A * r
    return (AM + sign * P.m * np.cross(r, np.cross(Ar, AM))) / (1.0 - P.m * (r @ Ar))


@formula("torque_plane")
def torque_plane(P, x):
    """Section 1 a): M_Q = gamma x dU/dgamma."""
    g = x[3:6]
    return np.cross(g, dU(P, g))


@formula("torque_sphere")
def torque_sphere(P, x):
    """Section 1 b): M_Q = gamma x (1 + k (B^T - k)^-1) dU/dgamma, B = J^-1 on the tangent
    plane (weingarten), k signed."""
    g = x[3:6]
    if P.k == 0.0:
        return np.cross(g, dU(P, g))
    B = weingarten(P, g)
    return np.cross(g, (E3 + P.k * np.linalg.inv(B.T - P.k * E3)) @ dU(P, g))


@formula("energy")
def energy(P, x):
    """(1.7): H = (M, omega)/2 + U, U = m g (r, gamma) + eps/2 (I gamma, gamma) (no field on
    a flat base, whose state is (M, r1, r2))."""
    if is_flat(P):
        return kinetic(P, x)
    return kinetic(P, x) + U(P, x[3:6])


@formula("geometric")
def geometric(P, x):
    return x[3:6] @ x[3:6]


@formula("area")
def area(P, x):
    return x[:3] @ x[3:6]


@formula("M2")
def m2(P, x):
    return x[:3] @ x[:3]
