"""Rubber rolling, derivation (a): Newton-Euler about the centre of mass, with multipliers.

Unknowns: the contact force F (body axes), the no-spin reaction torque lambda gamma, and
the angular acceleration. Everything in body axes, G the centre of mass:

    m (dv/dt + omega x v) = F + F_ext          Newton, v the velocity of G
    I domega/dt + omega x (I omega + S) = r x F + lambda gamma + T_couple
                                               Euler about G, gyrostat S
    v = r x omega                              no slip: v + omega x r = 0 at the contact
    (omega, gamma) = 0                         no spin about the normal

with dgamma/dt = (E - k J)^-1 (gamma x omega) and dr/dt = J dgamma/dt (CONVENTIONS.md).
Gravity is the force F_ext = m g gamma at G (gamma points down into the plane); the Brun
field is the couple T_couple = gamma x eps I gamma. Eliminating F with Newton's law gives
one linear system for (domega/dt, lambda):

    [ I - m [r]x[r]x   -gamma ] [domega/dt]   [ -omega x (I omega + S)
    [ gamma^T            0    ] [ lambda  ] = [   + m r x (dr/dt x omega + omega x (r x omega))
                                                 - r x F_ext + T_couple ;  -(omega, dgamma/dt) ]

The second row differentiates the constraint, so off the constraint manifold (omega, gamma)
is kept at its value: it is a first integral of this field on all of R^6. The state is
(M, gamma) with M = I omega + m r x (omega x r) (1.6), the paper's variables; dM/dt follows
by differentiating (1.6). r(gamma) comes from the paper's per-body formulas and J by complex
step (rubber_bodies.RubberBody.r_paper), not from the support function used by
derivation (b).
"""

from __future__ import annotations

import numpy as np

from solvers.models.rubber_bodies import RubberBody


def hat(x):
    return np.array([[0.0, -x[2], x[1]], [x[2], 0.0, -x[0]], [-x[1], x[0], 0.0]])


def inertia_contact(b: RubberBody, r):
    """I + m (r^2 E - r r^T): M = this times omega (1.6)."""
    return np.diag(b.I) + b.m * ((r @ r) * np.eye(3) - np.outer(r, r))


def solve(b: RubberBody, y):
    """(omega, domega/dt, lambda, dgamma/dt, r, dr/dt) at the state y = (M, gamma)."""
    y = np.asarray(y, dtype=float)
    M, g = y[:3], y[3:]
    r = b.r_paper(g)
    J = b.jacobian_cs(g)
    w = np.linalg.solve(inertia_contact(b, r), M)
    gd = np.linalg.solve(np.eye(3) - b.k * J, np.cross(g, w))
    rd = J @ gd
    I = np.diag(b.I)
    S = np.array(b.S)
    F_ext = b.m * b.g * g
    T_c = np.cross(g, b.eps * (I @ g))
    rhs_w = (-np.cross(w, I @ w + S)
             + b.m * np.cross(r, np.cross(rd, w) + np.cross(w, np.cross(r, w)))
             - np.cross(r, F_ext) + T_c)
    R = hat(r)
    A = np.zeros((4, 4))
    A[:3, :3] = I - b.m * R @ R
    A[:3, 3] = -g
    A[3, :3] = g
    x = np.linalg.solve(A, np.concatenate([rhs_w, [-(w @ gd)]]))
    return w, x[:3], x[3], gd, r, rd


def field(b: RubberBody, y):
    """d(M, gamma)/dt of the rubber body, from Newton-Euler."""
    w, wd, _lam, gd, r, rd = solve(b, y)
    Itd_w = b.m * (2.0 * (r @ rd) * w - rd * (r @ w) - r * (rd @ w))
    Md = inertia_contact(b, r) @ wd + Itd_w
    return np.concatenate([Md, gd])


def multiplier(b: RubberBody, y) -> float:
    """lambda: the no-spin reaction torque's component along gamma."""
    return float(solve(b, y)[2])


def contact_force(b: RubberBody, y):
    """F, the reaction force at the contact point (body axes), from Newton's law."""
    w, wd, _lam, _gd, r, rd = solve(b, y)
    v_dot = np.cross(rd, w) + np.cross(r, wd)
    v = np.cross(r, w)
    return b.m * (v_dot + np.cross(w, v)) - b.m * b.g * np.asarray(y[3:], dtype=float)
