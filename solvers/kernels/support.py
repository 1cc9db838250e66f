"""The body's surface as a support function: r(gamma) = grad h, J = dr/dgamma = Hess h.

h(gamma) = sqrt(gamma.B gamma) + c |gamma| + d sqrt(g1^2 + g2^2) + (a, gamma)

covers the paper's bodies with one formula (CONVENTIONS.md, r(gamma)):
  ball of radius R, centre at a:       c = R                      r = R gamma + a   (2.28)
  ellipsoid (r, B^-1 r) = 1:           B                          r = B g/sqrt(Bg.g) (2.39)
  disk of radius R, centre a e3:       d = R, a = (0, 0, a)       (2.15)
  Routh ball:                          c = R, a = (0, 0, a)       (2.18)
  rounded ellipsoid (non-quadric):     B = diag(b1, b1, b3), c > 0  (offset surface)
  rattleback: B = Q diag(b) Q^T turned against the inertia axes, a = offset.
h is positively homogeneous of degree 1, so J gamma = 0 and (dr, gamma) = 0 for tangent
dgamma: the Gauss-map condition (1.4), and for bodies of revolution (2.2).
"""

import numpy as np

from solvers.kernels import layout as L
from solvers.kernels.jit import kernel
from solvers.kernels.linalg import set_sym3

FLAT_DISK = 1e-8


@kernel
def support_s(p, g0, g1, g2):
    """The support map at gamma = (g0, g1, g2) as scalars, allocation-free (the hot path
    of the field): returns (s, r0, r1, r2, J00, J01, J02, J11, J12, J22), J = Hess h
    symmetric, s the disk's sin(theta) proxy (0.0: flat disk, r and J then unset; 1.0
    when the body has no disk part). Complex-safe: the type follows gamma."""
    z = 0.0 * g0
    r0 = p[L.A1] + z
    r1 = p[L.A2] + z
    r2 = p[L.A3] + z
    J00 = z
    J01 = z
    J02 = z
    J11 = z
    J12 = z
    J22 = z
    b11 = p[L.B11]
    b22 = p[L.B22]
    b33 = p[L.B33]
    b12 = p[L.B12]
    b13 = p[L.B13]
    b23 = p[L.B23]
    if b11 != 0.0 or b22 != 0.0 or b33 != 0.0:
        bg0 = b11 * g0 + b12 * g1 + b13 * g2
        bg1 = b12 * g0 + b22 * g1 + b23 * g2
        bg2 = b13 * g0 + b23 * g1 + b33 * g2
        q = bg0 * g0 + bg1 * g1 + bg2 * g2
        iq = 1.0 / np.sqrt(q)
        iq3 = iq * iq * iq
        r0 += bg0 * iq
        r1 += bg1 * iq
        r2 += bg2 * iq
        J00 += b11 * iq - bg0 * bg0 * iq3
        J11 += b22 * iq - bg1 * bg1 * iq3
        J22 += b33 * iq - bg2 * bg2 * iq3
        J01 += b12 * iq - bg0 * bg1 * iq3
        J02 += b13 * iq - bg0 * bg2 * iq3
        J12 += b23 * iq - bg1 * bg2 * iq3
    c = p[L.BALL_C]
    if c != 0.0:
        inv = 1.0 / np.sqrt(g0 * g0 + g1 * g1 + g2 * g2)
        ci = c * inv
        ci3 = ci * inv * inv
        r0 += ci * g0
        r1 += ci * g1
        r2 += ci * g2
        J00 += ci - ci3 * g0 * g0
        J11 += ci - ci3 * g1 * g1
        J22 += ci - ci3 * g2 * g2
        J01 -= ci3 * g0 * g1
        J02 -= ci3 * g0 * g2
        J12 -= ci3 * g1 * g2
    d = p[L.DISK_D]
    s_out = 1.0
    if d != 0.0:
        s = np.sqrt(g0 * g0 + g1 * g1)
        s_out = abs(s.real)
        # sin(theta) below FLAT_DISK: the contact point is undefined to within round-off
        # (r and J ~ 1/s); report the disk as flat rather than integrate through it
        if s_out < FLAT_DISK:
            return 0.0, r0, r1, r2, J00, J01, J02, J11, J12, J22
        di = d / s
        di3 = di / (s * s)
        r0 += di * g0
        r1 += di * g1
        J00 += di - di3 * g0 * g0
        J11 += di - di3 * g1 * g1
        J01 -= di3 * g0 * g1
    return s_out, r0, r1, r2, J00, J01, J02, J11, J12, J22


@kernel
def support(p, g, r, J):
    """Fill r (3,) and J (3, 3) at gamma = g. Returns the disk's sin(theta) proxy s >= 0
    (1.0 when the body has no disk part) so callers can detect the flat disk."""
    s, r[0], r[1], r[2], J00, J01, J02, J11, J12, J22 = support_s(p, g[0], g[1], g[2])
    set_sym3(J, J00, J01, J02, J11, J12, J22)
    return s
