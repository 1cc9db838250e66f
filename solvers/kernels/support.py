"""The body's surface as a support function: r(gamma) = grad h, J = dr/dgamma = Hess h.

h(gamma) = sqrt(gamma.B gamma) + c |gamma| + d sqrt(g1^2 + g2^2) + (a, gamma)

covers the paper's bodies with one formula (CONVENTIONS.md, r(gamma)):
  ball of radius R, centre at a:       c = R                      r = R gamma + a   (eq-d*1)
  ellipsoid (r, B^-1 r) = 1:           B                          r = B g/sqrt(Bg.g) (eq2.28)
  disk of radius R, centre a e3:       d = R, a = (0, 0, a)       eq2.71
  Routh ball:                          c = R, a = (0, 0, a)       eq2-14*
  rounded ellipsoid (non-quadric):     B = diag(b1, b1, b3), c > 0  (offset surface)
  rattleback: B = Q diag(b) Q^T turned against the inertia axes, a = offset.
h is positively homogeneous of degree 1, so J gamma = 0 and (dr, gamma) = 0 for tangent
dgamma: the Gauss-map condition eq1.4, and for bodies of revolution eq2.1/2.
"""

import numpy as np

from solvers.kernels import layout as L
from solvers.kernels.jit import kernel

FLAT_DISK = 1e-8


@kernel
def support(p, g, r, J):
    """Fill r (3,) and J (3, 3) at gamma = g. Returns the disk's sin(theta) proxy s >= 0
    (1.0 when the body has no disk part) so callers can detect the flat disk."""
    for i in range(3):
        r[i] = p[L.A1 + i]
        for j in range(3):
            J[i, j] = 0.0 * g[0]
    b11 = p[L.B11]
    b22 = p[L.B22]
    b33 = p[L.B33]
    b12 = p[L.B12]
    b13 = p[L.B13]
    b23 = p[L.B23]
    if b11 != 0.0 or b22 != 0.0 or b33 != 0.0:
        bg0 = b11 * g[0] + b12 * g[1] + b13 * g[2]
        bg1 = b12 * g[0] + b22 * g[1] + b23 * g[2]
        bg2 = b13 * g[0] + b23 * g[1] + b33 * g[2]
        q = bg0 * g[0] + bg1 * g[1] + bg2 * g[2]
        sq = np.sqrt(q)
        iq = 1.0 / sq
        iq3 = iq * iq * iq
        r[0] += bg0 * iq
        r[1] += bg1 * iq
        r[2] += bg2 * iq
        J[0, 0] += b11 * iq - bg0 * bg0 * iq3
        J[1, 1] += b22 * iq - bg1 * bg1 * iq3
        J[2, 2] += b33 * iq - bg2 * bg2 * iq3
        J[0, 1] += b12 * iq - bg0 * bg1 * iq3
        J[0, 2] += b13 * iq - bg0 * bg2 * iq3
        J[1, 2] += b23 * iq - bg1 * bg2 * iq3
        J[1, 0] += b12 * iq - bg0 * bg1 * iq3
        J[2, 0] += b13 * iq - bg0 * bg2 * iq3
        J[2, 1] += b23 * iq - bg1 * bg2 * iq3
    c = p[L.BALL_C]
    if c != 0.0:
        n2 = g[0] * g[0] + g[1] * g[1] + g[2] * g[2]
        n = np.sqrt(n2)
        inv = 1.0 / n
        inv3 = inv * inv * inv
        for i in range(3):
            r[i] += c * g[i] * inv
            for j in range(3):
                J[i, j] -= c * g[i] * g[j] * inv3
            J[i, i] += c * inv
    d = p[L.DISK_D]
    s_out = 1.0
    if d != 0.0:
        s2 = g[0] * g[0] + g[1] * g[1]
        s = np.sqrt(s2)
        s_out = abs(s.real)
        # sin(theta) below FLAT_DISK: the contact point is undefined to within round-off
        # (r and J ~ 1/s); report the disk as flat rather than integrate through it
        if s_out < FLAT_DISK:
            return 0.0
        inv = 1.0 / s
        inv3 = inv * inv * inv
        for i in range(2):
            r[i] += d * g[i] * inv
            for j in range(2):
                J[i, j] -= d * g[i] * g[j] * inv3
            J[i, i] += d * inv
    return s_out
