"""First integrals, compiled, dispatched on an integer code; float64 or complex128 states.

One source of truth for reporting drift, for projection inside the integrator, and for
the exact (complex-step) checks of the catalogue. Which integrals hold for which case and
under which conditions is decided by the Python layer (solvers/models/cases.yaml).
"""

import numpy as np

from solvers.kernels import layout as L
from solvers.kernels.fields import flat_kinematics_s, omega_s
from solvers.kernels.jit import kernel
from solvers.kernels.support import support_s

ENERGY = 0      # H = (M, omega)/2 + U                                     (1.7)
GEOM = 1        # gamma^2                                                  (1.7)
M2 = 2          # M^2                                     (2.24), (3.10) (U = 0)
AREA = 3        # (M, gamma)                                               (2.24)
UNBALANCED = 4  # M^2 - m r^2 (M, omega)                       (2.29), (3.13), (3.20)
JELLETT = 5     # (M, r)                                         (2.20) (K2 * R)
ROUTH = 6       # omega3 / rho, rho = (I1 I3 + m (r, I r))^-1/2         (2.20) (K1)
GYRO_M2 = 7     # (M + S)^2                                       (2.38) (Markeev)
GYRO_AREA = 8   # (M + S, gamma)                                  (2.38) (Markeev)
BORISOV_FEDOROV = 9  # (M, Abar gamma), Abar = E - 2 (I + D)/tr(I + D), D = m R^2   (3.11)
SPIN = 10       # (omega, gamma): the rubber constraint, zero on rubber motions
N_INTEGRAL_CODES = 11

NAMES = ("energy", "gamma2", "M2", "area", "unbalanced_F", "jellett", "routh",
         "gyro_M2", "gyro_area", "borisov_fedorov", "spin")


@kernel
def omega_r_s(model, y, p):
    """(status, w0, w1, w2, r0, r1, r2): omega and r of the state, allocation-free."""
    if model == L.MODEL_FLAT or model == L.MODEL_FLAT_SCENE:
        st, r0, r1, r2, w0, w1, w2 = flat_kinematics_s(p, y)
        return st, w0, w1, w2, r0, r1, r2
    s, r0, r1, r2 = support_s(p, y[3], y[4], y[5])[0:4]
    z = 0.0 * (r0 + y[0])
    if s == 0.0:
        return L.SING_EDGE, z, z, z, r0, r1, r2
    det, w0, w1, w2 = omega_s(p, y[0], y[1], y[2], r0, r1, r2)
    if det == 0:
        return L.SING_INERTIA, z, z, z, r0, r1, r2
    return L.OK, w0, w1, w2, r0, r1, r2


@kernel
def integral(code, model, y, p):
    """Value of integral `code` at state y (NaN if undefined there)."""
    st, w0, w1, w2, r0, r1, r2 = omega_r_s(model, y, p)
    if st != L.OK:
        return np.nan + 0.0 * y[0]
    return integral_at(code, model, y, p, w0, w1, w2, r0, r1, r2)


@kernel
def integrals_into(codes, model, y, p, out):
    """out[i] = integral(codes[i]) at y, sharing one evaluation of omega and r (the
    projection inside the integrator evaluates all integrals n + 1 times per step)."""
    st, w0, w1, w2, r0, r1, r2 = omega_r_s(model, y, p)
    for i in range(codes.shape[0]):
        if st != L.OK:
            out[i] = np.nan + 0.0 * y[0]
        else:
            out[i] = integral_at(codes[i], model, y, p, w0, w1, w2, r0, r1, r2)


@kernel
def integral_at(code, model, y, p, w0, w1, w2, r0, r1, r2):
    """Value of integral `code` at y, given omega and r there."""
    w = (w0, w1, w2)
    r = (r0, r1, r2)
    M0, M1, M2_ = y[0], y[1], y[2]
    m = p[L.MASS]
    Mw = M0 * w[0] + M1 * w[1] + M2_ * w[2]
    MM = M0 * M0 + M1 * M1 + M2_ * M2_
    if code == ENERGY:
        H = 0.5 * Mw
        if model == L.MODEL_FULL or model == L.MODEL_FULL_SCENE:
            g = y[3:6]
            H += m * p[L.GRAV] * (r[0] * g[0] + r[1] * g[1] + r[2] * g[2])
            H += 0.5 * p[L.BRUN] * (p[L.I1] * g[0] * g[0] + p[L.I2] * g[1] * g[1]
                                    + p[L.I3] * g[2] * g[2])
        return H
    if code == GEOM:
        return y[3] * y[3] + y[4] * y[4] + y[5] * y[5]
    if code == M2:
        return MM
    if code == AREA:
        return M0 * y[3] + M1 * y[4] + M2_ * y[5]
    if code == UNBALANCED:
        return MM - m * (r[0] * r[0] + r[1] * r[1] + r[2] * r[2]) * Mw
    if code == JELLETT:
        return M0 * r[0] + M1 * r[1] + M2_ * r[2]
    if code == ROUTH:
        rIr = p[L.I1] * r[0] * r[0] + p[L.I2] * r[1] * r[1] + p[L.I3] * r[2] * r[2]
        return w[2] * np.sqrt(p[L.I1] * p[L.I3] + m * rIr)
    if code == GYRO_M2:
        a0 = M0 + p[L.S1]
        a1 = M1 + p[L.S2]
        a2 = M2_ + p[L.S3]
        return a0 * a0 + a1 * a1 + a2 * a2
    if code == GYRO_AREA:
        return (M0 + p[L.S1]) * y[3] + (M1 + p[L.S2]) * y[4] + (M2_ + p[L.S3]) * y[5]
    if code == BORISOV_FEDOROV:
        D = m * p[L.BALL_C] * p[L.BALL_C]
        tr = p[L.I1] + p[L.I2] + p[L.I3] + 3.0 * D
        acc = 0.0 * y[0]
        for i in range(3):
            acc += y[i] * (1.0 - 2.0 * (p[L.I1 + i] + D) / tr) * y[3 + i]
        return acc
    if code == SPIN:
        return w[0] * y[3] + w[1] * y[4] + w[2] * y[5]
    return np.nan + 0.0 * y[0]


@kernel
def integral_series(code, model, Y, p, out):
    """integral(code) along the rows of Y."""
    for n in range(Y.shape[0]):
        out[n] = integral(code, model, Y[n], p)


@kernel
def integral_table(codes, model, Y, p, out, drift):
    """out[i, n] = integral(codes[i]) at Y[n] (one omega and r per row, integrals_into)
    and drift[i] = max_n |out[i, n] - out[i, 0]| / max(|out[i, 0]|, 1), NaN if a value
    is NaN: a run's invariants and their drift in one call (simulate's thin entry)."""
    k = codes.shape[0]
    m = Y.shape[0]
    row = np.empty(k)
    for n in range(m):
        integrals_into(codes, model, Y[n], p, row)
        for i in range(k):
            out[i, n] = row[i]
    for i in range(k):
        if m == 0:
            drift[i] = 0.0
            continue
        v0 = out[i, 0]
        d = 0.0
        for n in range(m):
            e = abs(out[i, n] - v0)
            if e != e:
                d = np.nan
                break
            if e > d:
                d = e
        drift[i] = d / max(abs(v0), 1.0)
