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

# --- section codes s(y) = 0 (a nonlinear one is one more branch of `section_value`, with
# its gradient) --------------------------------------------------------------------------
SECTION_NONE = 0
SECTION_LINEAR = 1        # s(y) = coef[:n] . y - coef[n]
# SECTION_ANDOYER_G = 2: sin(g - g0) in Andoyer-Deprit variables (below)

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


@kernel
def section_value(code, y, coef, grad):
    """s(y) of section `code`; its gradient is written to grad."""
    n = y.shape[0]
    if code == SECTION_LINEAR:
        val = -coef[n]
        for i in range(n):
            val += coef[i] * y[i]
            grad[i] = coef[i]
        return val
    if code == SECTION_ANDOYER_G:
        return andoyer_g_value(y, coef, grad)
    for i in range(n):
        grad[i] = np.nan
    return np.nan


@kernel
def crossing_start(code, coef, y, f0, ynew, f1, h, grad, direction):
    """Where to locate the section crossing of the step (y, f0) -> (ynew, f1) of length
    h from: +1 its start, -1 its end, 0 no crossing in `direction`, 2 unresolved (halve
    the step). Henon's step from an end reaches the right crossing only if s runs
    monotonically from that end to it; the Hermite cubic of s through the ends (values and
    slopes ds/dt = grad s . f) shows a step whose ends alone mislead: s of one sign at
    both ends but crossing over inside, or coming nearer to the section than it swings in
    the step (a grazing pair), or a sign change with ds/dt of the wrong sign at both
    ends."""
    s0, d0 = section_slope(code, y, f0, coef, grad)
    s1, d1 = section_slope(code, ynew, f1, coef, grad)
    return crossing_kind(s0, d0, s1, d1, h, direction)


@kernel
def section_slope(code, y, f, coef, grad):
    """(s(y), ds/dt = grad s . f) of section `code` at y where the field is f."""
    s = section_value(code, y, coef, grad)
    d = 0.0
    for m in range(y.shape[0]):
        d += grad[m] * f[m]
    return s, d


@kernel
def crossing_kind(s0, d0, s1, d1, h, direction):
    """crossing_start's answer from the section's values and slopes at the step's ends
    (the small kernels carry them from step to step: solvers/kernels/small.py)."""
    if not (np.isfinite(s0) and np.isfinite(s1) and np.isfinite(d0) and np.isfinite(d1)):
        return 0
    up = s0 < 0.0 <= s1
    down = s0 > 0.0 >= s1
    if up or down:
        if (up and direction < 0) or (down and direction > 0):
            return 0
        sg = 1.0 if up else -1.0
        ok0 = sg * d0 > 0.0
        ok1 = sg * d1 > 0.0
        if ok0 and ok1:
            return 1 if abs(s0) <= abs(s1) else -1
        if ok0:
            return 1
        if ok1:
            return -1
        return 2
    if s0 * s1 <= 0.0:
        return 0
    # same sign at both ends: does the cubic a3 t^3 + a2 t^2 + a1 t + s0 cross over?
    a1 = h * d0
    a2 = -3.0 * s0 - 2.0 * h * d0 + 3.0 * s1 - h * d1
    a3 = 2.0 * s0 + h * d0 - 2.0 * s1 + h * d1
    qa = 3.0 * a3
    qb = 2.0 * a2
    for root in range(2):
        if qa == 0.0:
            if root == 1 or qb == 0.0:
                break
            th = -a1 / qb
        else:
            disc = qb * qb - 4.0 * qa * a1
            if disc < 0.0:
                break
            sq = np.sqrt(disc)
            th = (-qb + sq) / (2.0 * qa) if root == 0 else (-qb - sq) / (2.0 * qa)
        if 0.0 < th < 1.0:
            v = ((a3 * th + a2) * th + a1) * th + s0
            # across, or nearer to the section than its swing in the step (the cubic's own
            # error is below the swing): unresolved until the pieces are small enough
            if (s0 < 0.0 < v) or (s0 > 0.0 > v) or abs(v) <= max(abs(s0 - v), abs(s1 - v)):
                return 2
    return 0
