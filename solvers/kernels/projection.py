"""Projection onto the levels of first integrals, for the Runge-Kutta kernels (the loop
kernel and the small kernels with projection, solvers/kernels/small.py).

`project` moves a state onto {F(y) = F0} by simplified Newton iterations,
y <- y - G^T (G G^T)^-1 (F(y) - F0), with G = dF/dy taken once at the unprojected y by
complex step (Hairer, Lubich & Wanner, Geometric Numerical Integration, IV.4), until the
residuals are at round-off (at most four iterations). The integrals are the body models'
(solvers/kernels/integrals.py) or, for the test problems, those below. Nothing here calls
the vector field: the same compiled code serves every field.
"""

import numpy as np

from solvers.kernels import layout as L
from solvers.kernels.integrals import integral, integrals_into
from solvers.kernels.jit import kernel

PROJECTION_FAILED = 23    # an integrator status (rk.py holds the others, 20..24)

# --- integrals of the test problems (the body models use integrals.integral) -----------
TEST_ENERGY = 0           # oscillator (y0^2 + y1^2)/2; Kepler |v|^2/2 - 1/|x|
TEST_ANGMOM = 1           # Kepler x vy - y vx

CSTEP = 1e-30             # complex-step increment: the derivative is exact to round-off


@kernel
def model_integral(code, model, y, p):
    """First integral `code` of `model` at y (float64 or complex128)."""
    if model == L.MODEL_TEST_OSC:
        if code == TEST_ENERGY:
            return 0.5 * (y[0] * y[0] + y[1] * y[1])
        return np.nan + 0.0 * y[0]
    if model == L.MODEL_TEST_KEPLER:
        if code == TEST_ENERGY:
            return 0.5 * (y[2] * y[2] + y[3] * y[3]) - 1.0 / np.sqrt(y[0] * y[0] + y[1] * y[1])
        if code == TEST_ANGMOM:
            return y[0] * y[3] - y[1] * y[2]
        return np.nan + 0.0 * y[0]
    return integral(code, model, y, p)


@kernel
def model_integrals(codes, model, y, p, out):
    """out[i] = model_integral(codes[i], model, y, p), the body models' kinematics shared."""
    if model == L.MODEL_TEST_OSC or model == L.MODEL_TEST_KEPLER:
        for i in range(codes.shape[0]):
            out[i] = model_integral(codes[i], model, y, p)
    else:
        integrals_into(codes, model, y, p, out)


@kernel
def solve_small(M, r, x):
    """x = M^-1 r by Gaussian elimination with partial pivoting (M, r overwritten).
    Returns False if M is singular."""
    m = r.shape[0]
    for k in range(m):
        piv = k
        for i in range(k + 1, m):
            if abs(M[i, k]) > abs(M[piv, k]):
                piv = i
        if M[piv, k] == 0.0 or not np.isfinite(M[piv, k]):
            return False
        if piv != k:
            for j in range(m):
                M[k, j], M[piv, j] = M[piv, j], M[k, j]
            r[k], r[piv] = r[piv], r[k]
        for i in range(k + 1, m):
            f = M[i, k] / M[k, k]
            for j in range(k, m):
                M[i, j] -= f * M[k, j]
            r[i] -= f * r[k]
    for k in range(m - 1, -1, -1):
        acc = r[k]
        for j in range(k + 1, m):
            acc -= M[k, j] * x[j]
        x[k] = acc / M[k, k]
    return True


@kernel
def project(model, p, y, codes, vals, G, M, r, lam, yc):
    """Move y onto {F(y) = vals}: simplified Newton y <- y - G^T (G G^T)^-1 (F(y) - F0),
    G = dF/dy at the unprojected y by complex step (Hairer-Lubich-Wanner GNI IV.4)."""
    n = y.shape[0]
    m = codes.shape[0]
    vc = np.empty(m, dtype=np.complex128)
    for j in range(n):
        for i in range(n):
            yc[i] = y[i]
        yc[j] = y[j] + 1j * CSTEP
        model_integrals(codes, model, yc, p, vc)
        for k in range(m):
            G[k, j] = vc[k].imag / CSTEP
    for it in range(4):
        done = True
        model_integrals(codes, model, y, p, r)
        for k in range(m):
            r[k] -= vals[k]
            if not np.isfinite(r[k]):
                return PROJECTION_FAILED
            if abs(r[k]) > 2.0 * L.EPS * max(1.0, abs(vals[k])):
                done = False
        if done or it == 3:
            return L.OK
        for k in range(m):
            for q in range(m):
                acc = 0.0
                for j in range(n):
                    acc += G[k, j] * G[q, j]
                M[k, q] = acc
        if not solve_small(M, r, lam):
            return PROJECTION_FAILED
        for j in range(n):
            for k in range(m):
                y[j] -= G[k, j] * lam[k]
    return L.OK
