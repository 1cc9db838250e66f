"""Nonlinear Poincare sections for `rk.rk_integrate`: value, gradient and acceptance.

Section code SECTION_ANDOYER_G: the angle g of the Andoyer-Deprit variables (the paper's
(2.22)) equal to g0, state (M, gamma). Inverting (2.22): with
    m = M/G, u = (L/G sin l, L/G cos l, -sqrt(1 - (L/G)^2)), v = (cos l, -sin l, 0),
gamma = (H/G) m + sqrt(1 - (H/G)^2) (cos g u + sin g v), so (G = |M|, rho^2 = M1^2 + M2^2)
    G rho sqrt(1 - (H/G)^2) sin g = Sg = G (gamma1 M2 - gamma2 M1)
    G rho sqrt(1 - (H/G)^2) cos g = Cg = M3 (M1 gamma1 + M2 gamma2) - rho^2 gamma3
and g = atan2(Sg, Cg). The section function handed to the integrator is
    s(y) = sin(g - g0) = (Sg cos g0 - Cg sin g0) / N,   N = sqrt(Sg^2 + Cg^2),
smooth wherever g is defined (N > 0: M not along the body axis e3, gamma not along M).
s = 0 also on g = g0 + pi; a crossing found there is refused by `section_accept`
(cos(g - g0) < 0), so that the map sees g = g0 only, in the direction asked for:
with cos(g - g0) > 0, s increasing is g increasing. The gradient is exact:
    ds = cos(g - g0) dg,   dg = (Cg dSg - Sg dCg) / N^2.

Step control near the section: g turns fast where it is nearly undefined (M close to
the axis e3, gamma close to M), and a step that turns it by more than pi can step over a
crossing (or over two, unseen). `section_step_error` is one more term of the step's error
norm, (|change of g| / DG_MAX)^(q+1) with q the order of the error estimate, so that the
step-size controller keeps |change of g| <= DG_MAX in every step; then also the Henon step
that locates a crossing spans less than DG_MAX / 2 of s.

Packed section coefficients `coef` (length n + 1): coef[0] = cos g0, coef[1] = sin g0.
Everything runs on float64 or complex128 states (complex-step checks of the gradient).
"""

import numpy as np

from solvers.kernels.jit import kernel

SECTION_ANDOYER_G = 2     # the next code after rk.SECTION_NONE = 0, rk.SECTION_LINEAR = 1
DG_MAX = 0.5              # largest change of g in one step (radians)


@kernel
def andoyer_sc(y):
    """(Sg, Cg) of the module docstring at y = (M, gamma)."""
    M1, M2, M3 = y[0], y[1], y[2]
    G = np.sqrt(M1 * M1 + M2 * M2 + M3 * M3)
    Sg = G * (y[3] * M2 - y[4] * M1)
    Cg = M3 * (M1 * y[3] + M2 * y[4]) - (M1 * M1 + M2 * M2) * y[5]
    return Sg, Cg


@kernel
def andoyer_g_value(y, coef, grad):
    """s(y) = sin(g - g0) and its gradient (module docstring); NaN where g is undefined.
    Allocates nothing: it runs once per step of the integrator."""
    M1, M2, M3 = y[0], y[1], y[2]
    g1, g2, g3 = y[3], y[4], y[5]
    G = np.sqrt(M1 * M1 + M2 * M2 + M3 * M3)
    P = g1 * M2 - g2 * M1
    rho2 = M1 * M1 + M2 * M2
    q = M1 * g1 + M2 * g2
    Sg = G * P
    Cg = M3 * q - rho2 * g3
    N2 = Sg * Sg + Cg * Cg
    N = np.sqrt(N2)
    A = Sg * coef[0] - Cg * coef[1]        # N sin(g - g0)
    B = Sg * coef[1] + Cg * coef[0]        # N cos(g - g0)
    f = B / (N2 * N)
    iG = 1.0 / G
    # grad = f (Cg dSg - Sg dCg), component by component
    grad[0] = f * (Cg * (M1 * iG * P - G * g2) - Sg * (M3 * g1 - 2.0 * M1 * g3))
    grad[1] = f * (Cg * (M2 * iG * P + G * g1) - Sg * (M3 * g2 - 2.0 * M2 * g3))
    grad[2] = f * (Cg * (M3 * iG * P) - Sg * q)
    grad[3] = f * (Cg * (G * M2) - Sg * (M3 * M1))
    grad[4] = f * (Cg * (-G * M1) - Sg * (M3 * M2))
    grad[5] = f * (Sg * rho2)
    return A / N


@kernel
def section_accept(code, y, coef):
    """Whether a located crossing at y belongs to the section (False: the spurious
    branch g = g0 + pi of sin(g - g0) = 0). Linear sections accept every crossing."""
    if code != SECTION_ANDOYER_G:
        return True
    Sg, Cg = andoyer_sc(y)
    return Sg * coef[1] + Cg * coef[0] > 0.0


@kernel
def section_step_error(y, ynew, coef, q):
    """(|g(ynew) - g(y)| / DG_MAX)^(q+1), the change of g taken in (-pi, pi]; 0 where g
    is undefined at either end."""
    So, Co = andoyer_sc(y)
    Sn, Cn = andoyer_sc(ynew)
    dg = np.arctan2(Sn * Co - Cn * So, Cn * Co + Sn * So)
    if not np.isfinite(dg):
        return 0.0
    return (abs(dg) / DG_MAX) ** (q + 1)
