"""An independent plain-NumPy right-hand side, for the scipy reference backend and tests.

It shares the conventions but not the code of solvers/kernels: r(gamma) is written per
body from the paper's own formulas ((2.28), (2.39), (2.15)) instead of one support
function, J = dr/dgamma is taken by complex step of that r instead of a hand-written
Hessian, omega comes from (1.6)'s explicit inverse (sign corrected, see below)
    omega = (A M + m r x (A r x A M)) / (1 - m (r, A r)),  A = (I + m r^2)^-1,
and linear solves go through numpy.linalg.

Finding: (1.6) is printed as omega = (A M - m r x (A r x A M)) / (1 - m (r, A r)). Inverting
M = (I + m r^2) omega - m r (r, omega) gives a PLUS sign; the printed minus does not invert
(1.6)'s own first half (tests/test_reference.py::test_eq1_6_printed_sign_is_a_misprint).
"""

import numpy as np

from solvers.kernels import layout as L


def _r_of_gamma(p, g):
    """Support point, summed from the per-body formulas the paper prints."""
    r = np.array([p[L.A1], p[L.A2], p[L.A3]], dtype=g.dtype)
    B = np.array([[p[L.B11], p[L.B12], p[L.B13]],
                  [p[L.B12], p[L.B22], p[L.B23]],
                  [p[L.B13], p[L.B23], p[L.B33]]])
    if np.any(B):
        Bg = B @ g
        r = r + Bg / np.sqrt(g @ Bg)                       # (2.39)
    if p[L.BALL_C]:
        r = r + p[L.BALL_C] * g / np.sqrt(g @ g)           # (2.28) (off the sphere: g/|g|)
    if p[L.DISK_D]:
        s = np.sqrt(g[0] ** 2 + g[1] ** 2)
        r = r + p[L.DISK_D] * np.array([g[0] / s, g[1] / s, 0.0 * s])   # (2.15)
    return r


def _jacobian(p, g, h=1e-30):
    J = np.empty((3, 3))
    for j in range(3):
        gc = g.astype(complex)
        gc[j] += 1j * h
        J[:, j] = _r_of_gamma(p, gc).imag / h
    return J


def omega_eq1_6(p, M, r, sign=+1.0):
    """(1.6)'s explicit inverse; sign=-1 is the form as printed (a misprint)."""
    m = p[L.MASS]
    I = np.diag(p[L.I1:L.I3 + 1])
    A = np.linalg.inv(I + m * (r @ r) * np.eye(3))
    AM, Ar = A @ M, A @ r
    return (AM + sign * m * np.cross(r, np.cross(Ar, AM))) / (1.0 - m * (r @ Ar))


def field(model, p, y):
    """dy/dt for MODEL_FULL (M, gamma) and MODEL_FLAT (M, r1, r2)."""
    m, k = p[L.MASS], p[L.CURV]
    S = np.array([p[L.S1], p[L.S2], p[L.S3]])
    M = y[:3]
    if model == L.MODEL_FLAT:
        r = np.array([y[3], y[4], p[L.FLAT_Z]])
        w = omega_eq1_6(p, M, r)
        rd = np.array([w[1], -w[0], 0.0]) / k                           # (3.17), k < 0
        Md = np.cross(M + S, w) + m * np.cross(rd, np.cross(w, r))
        return np.concatenate([Md, rd[:2]])
    g = y[3:]
    r = _r_of_gamma(p, g)
    J = _jacobian(p, g)
    w = omega_eq1_6(p, M, r)
    E = np.eye(3)
    gd = np.linalg.solve(E - k * J, np.cross(g, w))
    rd = J @ gd
    dU = m * p[L.GRAV] * (r + J.T @ g) + p[L.BRUN] * p[L.I1:L.I3 + 1] * g
    MQ = np.cross(g, np.linalg.solve(E - k * J.T, dU))
    Md = np.cross(M + S, w) + m * np.cross(rd, np.cross(w, r)) + MQ
    return np.concatenate([Md, gd])
