"""Reduced field of a body of revolution, state x = (gamma3, K1, K2, K3)   (2.6).

Reduced variables ((2.5) on the plane, (3.3) on the sphere; K3 as in (2.5) on both):
  K1 = (M, r) (1 - k f1) / f1,   K2 = omega3 / rho0,
  K3 = (M2 g1 - M1 g2) / sqrt((1 - g3^2)(I1 + m r^2)),
  rho0 = (I1 I3 + m (r, I r))^-1/2 = (I1 I3 + m I1 f1^2 (1-g3^2) + m I3 f2^2)^-1/2   (2.3)
with the profile r = (f1 g1, f1 g2, f2) of `solvers.models.revolution` (phi family of support.py).

Two paths:
* plane (k = 0): (2.6) in closed form, as printed (verified against the full field,
  tests/test_reduced.py), with kappa = sqrt((1 - g3^2)/(I1 + m r^2)) (the paper's "k").
  The gyrostat S = (0, 0, s) terms are the project's extension ((2.6) has none):
  K1' += -s kappa K3, K2' += -m rho f1 f2 s kappa K3 (2.32), K3' += s kappa omega1 / sigma
  (the torque S x omega), omega1 in the gauge gamma2 = 0.
* sphere (k != 0): no closed form is printed ("bulkiness", section 3). The field is the
  chain rule of the reduced map along the full field (1.1)/(1.3), written in the gauge
  gamma = (sigma, 0, g3) with the closed-form curvatures: on the tangent plane
  J = f1 e2 e2^T + f2' t t^T, t = (g3, 0, -sigma) (parallel and meridian radii).

U(g3) = m g phi(g3) + eps/2 (I1 (1-g3^2) + I3 g3^2) (gravity and Brun, as fields.py).
Status SING_REDUCED at g3^2 >= 1 (the reduced variables are undefined there).
"""

import numpy as np

from solvers.kernels import layout as L
from solvers.kernels.jit import kernel


@kernel
def rev_profile_s(p, u):
    """(phi, phi', f1, f2, f1', f2') at u = gamma3 for the support family
    sqrt(b1 (1-u^2) + b3 u^2) + c + d sqrt(1-u^2) + a u (solvers.models.revolution)."""
    b1 = p[L.B11]
    b3 = p[L.B33]
    c = p[L.BALL_C]
    d = p[L.DISK_D]
    a = p[L.A3]
    ph = c + a * u
    d1 = a + 0.0 * u
    d2 = 0.0 * u
    if b1 != 0.0 or b3 != 0.0:
        e = b3 - b1
        q = b1 + e * u * u
        sq = np.sqrt(q)
        ph += sq
        d1 += e * u / sq
        d2 += e * b1 / (q * sq)
    if d != 0.0:
        s = np.sqrt(1.0 - u * u)
        ph += d * s
        d1 -= d * u / s
        d2 -= d / (s * s * s)
    f1 = ph - u * d1
    return ph, d1, f1, u * ph + (1.0 - u * u) * d1, -u * d2, f1 + (1.0 - u * u) * d2


@kernel
def rev_profile(p, u, out):
    """rev_profile_s written into out (6,)."""
    out[0], out[1], out[2], out[3], out[4], out[5] = rev_profile_s(p, u)


@kernel
def _dU(p, u, dphi):
    """dU/dgamma3 on the sphere of directions: gravity m g phi' and the Brun field."""
    return (p[L.MASS] * p[L.GRAV] * dphi
            + p[L.BRUN] * (p[L.I3] - p[L.I1]) * u)


@kernel
def rev_reduced_plane(p, y, dydt):
    """(2.6) (closed form, plane) plus the project's axial-gyrostat terms."""
    u = y[0]
    K1 = y[1]
    K2 = y[2]
    K3 = y[3]
    _, dphi, f1, f2, f1p, f2p = rev_profile_s(p, u)
    I1 = p[L.I1]
    I3 = p[L.I3]
    m = p[L.MASS]
    s = p[L.S3]
    s2 = 1.0 - u * u
    sig = np.sqrt(s2)
    r2 = f1 * f1 * s2 + f2 * f2
    rho = 1.0 / np.sqrt(I1 * I3 + m * I1 * f1 * f1 * s2 + m * I3 * f2 * f2)
    kap = np.sqrt(s2 / (I1 + m * r2))
    qp = (f2p * f1 - f2 * f1p) / (f1 * f1)          # (f2/f1)'
    dU = _dU(p, u, dphi)
    g3d = kap * K3
    dydt[0] = g3d
    dydt[1] = g3d * (-rho * I3 * (1.0 - qp) * K2 - s)
    dydt[2] = g3d * (-m * rho * f1 * ((f1 - f2p) * K1 + f2 * s))
    k3 = (f2 * (f1 * s2 + u * f2) * (m * f1 * f1 * K1 * K1 + I3 * K2 * K2)
          + u * f1 * f1 * I1 * K1 * K1
          - f1 * (f1 * s2 + 2.0 * u * f2) * K1 * K2 / rho
          + m * f1 * f1 * rho * f2 * s2 * (u * f1 * I1 - f2 * I3) * K1 * K2)
    dydt[3] = -kap / (I1 * I1 * f1 * f1 * s2 * s2) * k3 - kap * dU
    if s != 0.0:
        # omega1 in the gauge gamma = (sigma, 0, u): block {1, 3} of I_Q^-1
        M3 = (K2 / rho - m * f1 * f2 * K1) / I1
        M1 = (K1 - f2 / f1 * M3) / sig
        w1 = rho * rho * ((I3 + m * f1 * f1 * s2) * M1 + m * f1 * sig * f2 * M3)
        dydt[3] += s * kap * w1 / sig
    return L.OK


@kernel
def rev_reduced_general(p, y, dydt):
    """Chain rule of the reduced map ((3.3), K3 of (2.5)) along the full field, any k."""
    u = y[0]
    K1 = y[1]
    K2 = y[2]
    K3 = y[3]
    _, dphi, f1, f2, f1p, f2p = rev_profile_s(p, u)
    I1 = p[L.I1]
    I3 = p[L.I3]
    m = p[L.MASS]
    k = p[L.CURV]
    s = p[L.S3]
    s2 = 1.0 - u * u
    sig = np.sqrt(s2)
    a1 = 1.0 - k * f1            # parallel circle: 1 - k f1
    a2 = 1.0 - k * f2p           # meridian: 1 - k f2'
    if a1.real <= 0.0 or a2.real <= 0.0:
        return L.SING_FIT
    r2 = f1 * f1 * s2 + f2 * f2
    rho = 1.0 / np.sqrt(I1 * I3 + m * I1 * f1 * f1 * s2 + m * I3 * f2 * f2)
    # full state in the gauge gamma = (sig, 0, u), r = (f1 sig, 0, f2)
    Kp = K1 / a1
    M3 = (K2 / rho - m * f1 * f2 * Kp) / I1
    A = Kp - f2 / f1 * M3
    M1 = A / sig
    M2 = K3 * np.sqrt(I1 + m * r2)
    # omega = I_Q^-1 M (I_Q is block diagonal {1, 3} + {2} in this gauge)
    q11 = I1 + m * f2 * f2
    q33 = I3 + m * f1 * f1 * s2
    q13 = -m * f1 * sig * f2
    w1 = rho * rho * (q33 * M1 - q13 * M3)
    w3 = rho * rho * (q11 * M3 - q13 * M1)
    w2 = M2 / (I1 + m * r2)
    # (E - k J) gamma' = gamma x omega, split on t = (u, 0, -sig) and e2
    gt = -w2 / a2                 # (gamma', t)
    gd1 = gt * u
    gd2 = (u * w1 - sig * w3) / a1
    ud = -gt * sig                # gamma3'
    # r' = J gamma' = f2' (gamma', t) t + f1 gamma2' e2
    rd0 = f2p * gt * u
    rd1 = f1 * gd2
    rd2 = -f2p * gt * sig
    r0 = f1 * sig
    rr2 = f2
    # omega x r
    c0 = w2 * rr2 - w3 * 0.0
    c1 = w3 * r0 - w1 * rr2
    c2 = w1 * 0.0 - w2 * r0
    MQ2 = -sig * _dU(p, u, dphi) / a2
    Md1 = (M2 * w3 - M3 * w2 - s * w2) + m * (rd1 * c2 - rd2 * c1)
    Md2 = (M3 * w1 - M1 * w3 + s * w1) + m * (rd2 * c0 - rd0 * c2) + MQ2
    Md3 = (M1 * w2 - M2 * w1) + m * (rd0 * c1 - rd1 * c0)
    # chain rule, A = M1 g1 + M2 g2, B = M2 g1 - M1 g2, q = f2/f1
    Ad = Md1 * sig + M1 * gd1 + M2 * gd2
    Bd = Md2 * sig + M2 * gd1 - M1 * gd2
    q = f2 / f1
    qp = (f2p * f1 - f2 * f1p) / (f1 * f1)
    dydt[0] = ud
    dydt[1] = (Ad + q * Md3 + qp * ud * M3) * a1 - (A + q * M3) * k * f1p * ud
    drho = -rho * rho * rho * m * (I1 * f1 * (f1p * s2 - u * f1) + I3 * f2 * f2p)
    dydt[2] = drho * ud * K2 / rho + rho * (
        m * (f1p * f2 + f1 * f2p) * ud * A + m * f1 * f2 * Ad
        + 2.0 * m * f2 * f2p * ud * M3 + q11 * Md3)
    N = s2 * (I1 + m * r2)
    Np = -2.0 * u * (I1 + m * r2) + s2 * m * (2.0 * f1 * f1p * s2 - 2.0 * u * f1 * f1
                                               + 2.0 * f2 * f2p)
    sN = np.sqrt(N)
    dydt[3] = Bd / sN - 0.5 * (M2 * sig) * Np / (N * sN) * ud
    return L.OK


@kernel
def rev_reduced(p, y, dydt):
    """dx/dt of MODEL_REV_REDUCED: (2.6) on the plane, the chain-rule field on a sphere."""
    if y[0].real * y[0].real >= 1.0:
        return L.SING_REDUCED
    if p[L.CURV] == 0.0:
        return rev_reduced_plane(p, y, dydt)
    return rev_reduced_general(p, y, dydt)
