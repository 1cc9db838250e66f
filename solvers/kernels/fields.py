"""Vector fields of every model, dispatched on an integer model code.

`rhs(model, t, y, p, dydt) -> status` is the one function the integrator kernels call
(a module-level global, so numba's on-disk cache works: no function passed as argument).

Full model (CONVENTIONS.md), state (M, gamma):
  omega = I_Q^-1 M,  I_Q = I + m (r^2 E - r r^T)                          (1.6)
  (E - k J) dgamma/dt = gamma x omega,  dr/dt = J dgamma/dt                (1.2) / (1.3)
  dM/dt = (M + S) x omega + m dr/dt x (omega x r) + M_Q                   (1.1)
  M_Q = gamma x (E - k J^T)^-1 dU/dgamma,  U = m g (r, gamma) + eps/2 (I gamma, gamma)
  rubber (p[RUBBER] = 1): dM/dt gains lambda gamma, the reaction of (omega, gamma) = 0
Flat base on a sphere, state (M, r1, r2), gamma = e3 fixed, r = (r1, r2, z):
  0 = gamma x omega + k dr/dt  =>  dr/dt = (omega2, -omega1, 0) / k     (3.17)
  (the paper prints (3.17) with k = +1/R for the outside of the sphere, i.e. with gamma
  pointing out of the support; under CONVENTIONS.md the outside is k = -1/R0).

The hot path is scalar code on tuples (no array is allocated per call: allocating
many small arrays would be most of a call's cost); the array-filling functions
`full_kinematics`, `flat_kinematics`, `contact_inertia` keep their signatures for the
Python layer. Everything is complex-safe: the same source runs on complex128 states for
the complex-step checks.
"""

import numpy as np

from solvers.kernels import layout as L
from solvers.kernels.jit import kernel
from solvers.kernels.linalg import set_sym3
from solvers.kernels.reduced import rev_reduced
from solvers.kernels.support import support_s


@kernel
def contact_inertia(p, r, IQ):
    """I_Q = I + m (r^2 E - r r^T): tensor of inertia about the contact point."""
    m = p[L.MASS]
    r2 = r[0] * r[0] + r[1] * r[1] + r[2] * r[2]
    for i in range(3):
        for j in range(3):
            IQ[i, j] = -m * r[i] * r[j]
        IQ[i, i] += p[L.I1 + i] + m * r2


@kernel
def solve3_sym(a00, a01, a02, a11, a12, a22, b0, b1, b2):
    """Solve the symmetric system A x = b by the adjugate (Cramer): (det, x0, x1, x2);
    x = 0 when det == 0 (the caller reports the singularity)."""
    c00 = a11 * a22 - a12 * a12
    c01 = a12 * a02 - a01 * a22
    c02 = a01 * a12 - a11 * a02
    det = a00 * c00 + a01 * c01 + a02 * c02
    z = 0.0 * det * b0
    if det == 0:
        return det, z, z, z
    c11 = a00 * a22 - a02 * a02
    c12 = a01 * a02 - a00 * a12
    c22 = a00 * a11 - a01 * a01
    inv = 1.0 / det
    x0 = (c00 * b0 + c01 * b1 + c02 * b2) * inv + z
    x1 = (c01 * b0 + c11 * b1 + c12 * b2) * inv + z
    x2 = (c02 * b0 + c12 * b1 + c22 * b2) * inv + z
    return det, x0, x1, x2


@kernel
def omega_s(p, M0, M1, M2, r0, r1, r2):
    """omega = I_Q^-1 M (1.6), I_Q = I + m (r^2 E - r r^T): (det I_Q, w0, w1, w2)."""
    m = p[L.MASS]
    rr = m * (r0 * r0 + r1 * r1 + r2 * r2)
    return solve3_sym(p[L.I1] + rr - m * r0 * r0, -m * r0 * r1, -m * r0 * r2,
                      p[L.I2] + rr - m * r1 * r1, -m * r1 * r2,
                      p[L.I3] + rr - m * r2 * r2, M0, M1, M2)


@kernel
def kinematics_s(p, M0, M1, M2, g0, g1, g2):
    """r, J (symmetric: J00 J01 J02 J11 J12 J22), omega and dgamma/dt of the full model,
    as (status, r0, r1, r2, J.., w0, w1, w2, gd0, gd1, gd2)."""
    s, r0, r1, r2, J00, J01, J02, J11, J12, J22 = support_s(p, g0, g1, g2)
    z = 0.0 * (r0 + M0)
    if s == 0.0:
        return (L.SING_EDGE, r0, r1, r2, J00, J01, J02, J11, J12, J22, z, z, z, z, z, z)
    det, w0, w1, w2 = omega_s(p, M0, M1, M2, r0, r1, r2)
    if det == 0:
        return (L.SING_INERTIA, r0, r1, r2, J00, J01, J02, J11, J12, J22, z, z, z, z, z, z)
    u0 = g1 * w2 - g2 * w1
    u1 = g2 * w0 - g0 * w2
    u2 = g0 * w1 - g1 * w0
    k = p[L.CURV]
    if k == 0.0:
        return (L.OK, r0, r1, r2, J00, J01, J02, J11, J12, J22, w0, w1, w2,
                u0 + z, u1 + z, u2 + z)
    # (E - k J) dgamma/dt = gamma x omega; det(E - k J) changes sign where
    # 1 - k * (radius of curvature) crosses 0
    det, gd0, gd1, gd2 = solve3_sym(1.0 - k * J00, -k * J01, -k * J02, 1.0 - k * J11,
                                    -k * J12, 1.0 - k * J22, u0, u1, u2)
    st = L.OK if det.real > 0.0 else L.SING_FIT
    return (st, r0, r1, r2, J00, J01, J02, J11, J12, J22, w0, w1, w2, gd0, gd1, gd2)


@kernel
def full_kinematics(p, M, g, r, J, w, gd):
    """r, J, omega and dgamma/dt of the full model (arrays filled). Returns a status."""
    (st, r[0], r[1], r[2], J00, J01, J02, J11, J12, J22, w[0], w[1], w[2],
     gd[0], gd[1], gd[2]) = kinematics_s(p, M[0], M[1], M[2], g[0], g[1], g[2])
    set_sym3(J, J00, J01, J02, J11, J12, J22)
    return st


@kernel
def full_field(p, y, dydt):
    return full_field_wr(p, y, dydt)[0]


@kernel
def full_field_wr(p, y, dydt):
    """The full field into dydt[0:6]; returns (status, w0, w1, w2, r0, r1, r2)."""
    M0, M1, M2 = y[0], y[1], y[2]
    g0, g1, g2 = y[3], y[4], y[5]
    (st, r0, r1, r2, J00, J01, J02, J11, J12, J22, w0, w1, w2,
     gd0, gd1, gd2) = kinematics_s(p, M0, M1, M2, g0, g1, g2)
    if st != L.OK:
        return st, w0, w1, w2, r0, r1, r2
    m = p[L.MASS]
    k = p[L.CURV]
    # dr/dt = J dgamma/dt (1.3)
    rd0 = J00 * gd0 + J01 * gd1 + J02 * gd2
    rd1 = J01 * gd0 + J11 * gd1 + J12 * gd2
    rd2 = J02 * gd0 + J12 * gd1 + J22 * gd2
    # dU/dgamma for gravity U = m g (r, gamma) and the Brun field U = eps/2 (I gamma, gamma)
    mg = m * p[L.GRAV]
    eps = p[L.BRUN]
    dU0 = mg * (r0 + J00 * g0 + J01 * g1 + J02 * g2) + eps * p[L.I1] * g0
    dU1 = mg * (r1 + J01 * g0 + J11 * g1 + J12 * g2) + eps * p[L.I2] * g1
    dU2 = mg * (r2 + J02 * g0 + J12 * g1 + J22 * g2) + eps * p[L.I3] * g2
    if k != 0.0 and (mg != 0.0 or eps != 0.0):
        # M_Q = gamma x (E - k J^T)^-1 dU/dgamma (J symmetric)
        det, dU0, dU1, dU2 = solve3_sym(1.0 - k * J00, -k * J01, -k * J02, 1.0 - k * J11,
                                        -k * J12, 1.0 - k * J22, dU0, dU1, dU2)
        if det == 0:
            return L.SING_FIT, w0, w1, w2, r0, r1, r2
    a0 = M0 + p[L.S1]
    a1 = M1 + p[L.S2]
    a2 = M2 + p[L.S3]
    # omega x r
    c0 = w1 * r2 - w2 * r1
    c1 = w2 * r0 - w0 * r2
    c2 = w0 * r1 - w1 * r0
    # dM/dt = (M + S) x omega + m dr/dt x (omega x r) + gamma x dU   (1.1)
    dydt[0] = (a1 * w2 - a2 * w1) + m * (rd1 * c2 - rd2 * c1) + (g1 * dU2 - g2 * dU1)
    dydt[1] = (a2 * w0 - a0 * w2) + m * (rd2 * c0 - rd0 * c2) + (g2 * dU0 - g0 * dU2)
    dydt[2] = (a0 * w1 - a1 * w0) + m * (rd0 * c1 - rd1 * c0) + (g0 * dU1 - g1 * dU0)
    dydt[3] = gd0
    dydt[4] = gd1
    dydt[5] = gd2
    if p[L.RUBBER] != 0.0:
        if not rubber_reaction(p, y, dydt, w0, w1, w2, r0, r1, r2, rd0, rd1, rd2):
            return L.SING_INERTIA, w0, w1, w2, r0, r1, r2
    return L.OK, w0, w1, w2, r0, r1, r2


@kernel
def rubber_reaction(p, y, dydt, w0, w1, w2, r0, r1, r2, rd0, rd1, rd2):
    """Add the no-spin reaction lambda gamma to dM/dt = N in dydt[0:3] (rubber rolling,
    solvers/models/rubber_lagrange.py): lambda from d/dt (omega, gamma) = 0 with
    omega = I_Q^-1 M,
        lambda = -[(I_Q^-1 gamma, N - (dI_Q/dt) omega) + (omega, dgamma/dt)]
                 / (I_Q^-1 gamma, gamma),
    (dI_Q/dt) omega = m (2 (r, dr/dt) omega - dr/dt (r, omega) - r (dr/dt, omega)).
    False when I_Q is singular."""
    g0, g1, g2 = y[3], y[4], y[5]
    m = p[L.MASS]
    det, a0, a1, a2 = omega_s(p, g0, g1, g2, r0, r1, r2)   # I_Q^-1 gamma
    den = a0 * g0 + a1 * g1 + a2 * g2
    if det == 0 or den == 0:
        return False
    rrd = r0 * rd0 + r1 * rd1 + r2 * rd2
    rw = r0 * w0 + r1 * w1 + r2 * w2
    rdw = rd0 * w0 + rd1 * w1 + rd2 * w2
    e0 = dydt[0] - m * (2.0 * rrd * w0 - rd0 * rw - r0 * rdw)
    e1 = dydt[1] - m * (2.0 * rrd * w1 - rd1 * rw - r1 * rdw)
    e2 = dydt[2] - m * (2.0 * rrd * w2 - rd2 * rw - r2 * rdw)
    lam = -((a0 * e0 + a1 * e1 + a2 * e2) + (w0 * dydt[3] + w1 * dydt[4] + w2 * dydt[5])) \
        * (1.0 / den)
    dydt[0] = dydt[0] + lam * g0
    dydt[1] = dydt[1] + lam * g1
    dydt[2] = dydt[2] + lam * g2
    return True


@kernel
def flat_kinematics_s(p, y):
    """(status, r0, r1, r2, w0, w1, w2) of the flat-base model, r = (r1, r2, z)."""
    r0 = y[3]
    r1 = y[4]
    r2 = p[L.FLAT_Z] + 0.0 * y[3]
    det, w0, w1, w2 = omega_s(p, y[0], y[1], y[2], r0, r1, r2)
    st = L.OK if det != 0 else L.SING_INERTIA
    return st, r0, r1, r2, w0, w1, w2


@kernel
def flat_kinematics(p, y, r, w):
    """r = (r1, r2, z) and omega of the flat-base model. Returns a status code."""
    st, r[0], r[1], r[2], w[0], w[1], w[2] = flat_kinematics_s(p, y)
    return st


@kernel
def flat_field(p, y, dydt):
    return flat_field_wr(p, y, dydt)[0]


@kernel
def flat_field_wr(p, y, dydt):
    """The flat-base field into dydt[0:5]; returns (status, w0, w1, w2, r0, r1, r2)."""
    st, r0, r1, r2, w0, w1, w2 = flat_kinematics_s(p, y)
    if st != L.OK:
        return st, w0, w1, w2, r0, r1, r2
    m = p[L.MASS]
    k = p[L.CURV]
    rd0 = w1 / k
    rd1 = -w0 / k
    a0 = y[0] + p[L.S1]
    a1 = y[1] + p[L.S2]
    a2 = y[2] + p[L.S3]
    c0 = w1 * r2 - w2 * r1
    c1 = w2 * r0 - w0 * r2
    c2 = w0 * r1 - w1 * r0
    # dM/dt = (M + S) x omega + m dr/dt x (omega x r), dr/dt = (rd0, rd1, 0)
    dydt[0] = (a1 * w2 - a2 * w1) + m * (rd1 * c2)
    dydt[1] = (a2 * w0 - a0 * w2) + m * (-rd0 * c2)
    dydt[2] = (a0 * w1 - a1 * w0) + m * (rd0 * c1 - rd1 * c0)
    dydt[3] = rd0
    dydt[4] = rd1
    return L.OK, w0, w1, w2, r0, r1, r2


@kernel
def scene_field(model, p, y, dydt):
    """MODEL_FULL_SCENE / MODEL_FLAT_SCENE: the body's field plus the orientation and the
    centre of mass (solvers/models/kinematics.py): each row q of Q obeys dq/dt = q x omega
    (dQ/dt = Q [omega]x), and dx_G/dt = Q (r x omega) (the contact point does not slide)."""
    if model == L.MODEL_FULL_SCENE:
        st, w0, w1, w2, r0, r1, r2 = full_field_wr(p, y, dydt)
        n = 6
    else:
        st, w0, w1, w2, r0, r1, r2 = flat_field_wr(p, y, dydt)
        n = 5
    if st != L.OK:
        return st
    v0 = r1 * w2 - r2 * w1
    v1 = r2 * w0 - r0 * w2
    v2 = r0 * w1 - r1 * w0
    for i in range(3):
        q0 = y[n + 3 * i]
        q1 = y[n + 3 * i + 1]
        q2 = y[n + 3 * i + 2]
        dydt[n + 3 * i] = q1 * w2 - q2 * w1
        dydt[n + 3 * i + 1] = q2 * w0 - q0 * w2
        dydt[n + 3 * i + 2] = q0 * w1 - q1 * w0
        dydt[n + 9 + i] = q0 * v0 + q1 * v1 + q2 * v2
    return L.OK


@kernel
def test_field(model, y, dydt):
    if model == L.MODEL_TEST_OSC:
        dydt[0] = y[1]
        dydt[1] = -y[0]
    else:  # planar Kepler
        r2 = y[0] * y[0] + y[1] * y[1]
        r3 = r2 * np.sqrt(r2)
        dydt[0] = y[2]
        dydt[1] = y[3]
        dydt[2] = -y[0] / r3
        dydt[3] = -y[1] / r3
    return L.OK


@kernel
def rhs(model, t, y, p, dydt):
    """dy/dt of `model` at (t, y) with parameters p, written into dydt. Returns a status."""
    if model == L.MODEL_FULL:
        st = full_field(p, y, dydt)
    elif model == L.MODEL_FLAT:
        st = flat_field(p, y, dydt)
    elif model == L.MODEL_REV_REDUCED:
        st = rev_reduced(p, y, dydt)  # (2.6), solvers.kernels.reduced
    elif model == L.MODEL_FULL_SCENE or model == L.MODEL_FLAT_SCENE:
        st = scene_field(model, p, y, dydt)
    else:
        st = test_field(model, y, dydt)
    if st == L.OK:
        for i in range(dydt.shape[0]):
            if not np.isfinite(dydt[i]):
                return L.SING_NONFINITE
    return st
