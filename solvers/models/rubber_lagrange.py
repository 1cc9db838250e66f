"""Rubber rolling, derivation (b): Lagrange-d'Alembert in the body frame, in (M, gamma).

With no slip substituted (v_G = r x omega), the kinetic energy is a quadratic form in omega
alone,  T = (1/2) (I omega, omega) + (1/2) m |r x omega|^2 = (1/2) (M, omega),  and its
momentum is the angular momentum about the contact point, M = dT/domega =
I omega + m r x (omega x r) (1.6). The Lagrange-d'Alembert principle for virtual rotations
delta theta (the contact point fixed) written in the moving frame gives the marble equation
(1.1) with the gyrostat S and the potential torque M_Q; the no-spin constraint
(omega, gamma) = 0 has the covector gamma, so its reaction adds lambda gamma:

    dM/dt = (M + S) x omega + m dr/dt x (omega x r) + M_Q + lambda gamma
    dgamma/dt = (E - k J)^-1 (gamma x omega),      dr/dt = J dgamma/dt
    M_Q = gamma x dU/dgamma = gamma x (m g r + eps I gamma)     (plane, U = m g (r, gamma)
                                                                 + eps (I gamma, gamma) / 2)

lambda is fixed by d/dt (omega, gamma) = 0 with omega = A M, A = (I + m(r^2 E - r r^T))^-1:

    lambda = -[(A gamma, N - dA^-1/dt omega) + (omega, dgamma/dt)] / (A gamma, gamma)

N the right-hand side without lambda gamma. r and J are the support function's gradient and
Hessian written by hand (RubberBody.support_grad_hess); derivation (a) in rubber_newton.py
uses the per-body formulas and complex step instead, and eliminates a contact force.

The field is defined on all of R^6 and keeps (omega, gamma) and gamma^2 as first integrals
there; the rubber motions are its restriction to N = {(omega, gamma) = 0, gamma^2 = 1}, a
4-dimensional invariant manifold, on which the energy H = (1/2)(M, omega) + U is conserved
(lambda gamma does no work when (omega, gamma) = 0).
"""

from __future__ import annotations

import numpy as np

from solvers.models.rubber_bodies import RubberBody


def _parts(b: RubberBody, y):
    M, g = y[:3], y[3:]
    r, J = b.support_grad_hess(g)
    It = np.diag(b.I) + b.m * ((r @ r) * np.eye(3) - np.outer(r, r))
    w = np.linalg.solve(It, M)
    gd = np.linalg.solve(np.eye(3) - b.k * J, np.cross(g, w))
    rd = J @ gd
    return M, g, r, J, It, w, gd, rd


def field_and_multiplier(b: RubberBody, y):
    """(d(M, gamma)/dt, lambda) at y = (M, gamma); complex-safe for complex-step checks."""
    y = np.asarray(y)
    M, g, r, _J, It, w, gd, rd = _parts(b, y)
    S = np.array(b.S)
    MQ = np.cross(g, b.m * b.g * r + b.eps * np.array(b.I) * g)
    N = np.cross(M + S, w) + b.m * np.cross(rd, np.cross(w, r)) + MQ
    It_dot_w = b.m * (2.0 * (r @ rd) * w - rd * (r @ w) - r * (rd @ w))
    Ag = np.linalg.solve(It, g)
    lam = -((Ag @ (N - It_dot_w)) + (w @ gd)) / (Ag @ g)
    return np.concatenate([N + lam * g, gd]), lam


def field(b: RubberBody, y):
    return field_and_multiplier(b, y)[0]


def omega(b: RubberBody, y):
    y = np.asarray(y)
    return _parts(b, y)[5]


def energy(b: RubberBody, y):
    """H = (1/2)(M, omega) + U."""
    y = np.asarray(y)
    M, g, r, *_ = _parts(b, y)
    w = omega(b, y)
    U = b.m * b.g * (r @ g) + 0.5 * b.eps * (np.array(b.I) * g) @ g
    return 0.5 * (M @ w) + U


def spin(b: RubberBody, y):
    """(omega, gamma): zero on rubber motions."""
    y = np.asarray(y)
    return omega(b, y) @ y[3:]


def state_on_manifold(b: RubberBody, w_seed, g_seed):
    """A state (M, gamma) on N from any seeds: gamma normalised, omega projected onto the
    tangent plane, M = I omega + m r x (omega x r)."""
    g = np.asarray(g_seed, dtype=float)
    n = np.linalg.norm(g)
    if not np.isfinite(n) or n == 0.0:
        raise ValueError(f"gamma seed {g_seed!r}: must be a non-zero finite vector")
    g = g / n
    w = np.asarray(w_seed, dtype=float)
    w = w - (w @ g) * g
    r, _ = b.support_grad_hess(g)
    It = np.diag(b.I) + b.m * ((r @ r) * np.eye(3) - np.outer(r, r))
    return np.concatenate([It @ w, g])
