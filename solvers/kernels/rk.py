"""The parts of the Runge-Kutta step that call the field, and the packed layouts of the
loop kernel's arguments.

The step itself is written once, as a template (solvers/kernels/step.py), from which the
loop kernel (loop_kernel.py, `rk_integrate`) and the small kernels (small.py) are
generated. What the step decides from its numbers is control.py's; the projection
(projection.py) and the section's value and crossing tests (sections.py) call no field.
The functions here call the field `rhs` (fields.py): the stages on work arrays, Hairer's
starting step (Solving ODEs I, Sec. II.4), and the location of a section crossing by
Henon's trick (Physica D 5 (1982) 412) with its Newton refinement. The loop kernel calls
all of them; the small kernels, which write the stages and the starting step on scalars,
call the crossing functions. A case's generated field gets them bound to it
(solvers/kernels/bind.py, field_modules.generated_integrator).

The status codes are control.py's (the integrator's) and layout.py's (the field's).
"""

import numpy as np

from solvers.kernels import layout as L
from solvers.kernels.control import (  # noqa: F401 (callers import these from here)
    CROSSINGS_DONE,
    ERR_DOP853,
    MAX_STEPS,
    SECTION_TANGENT,
    STEP_UNDERFLOW,
    first_guess,
    first_step,
    first_step_singular,
)
from solvers.kernels.fields import rhs
from solvers.kernels.jit import kernel
from solvers.kernels.layout import EPS
from solvers.kernels.projection import (  # noqa: F401 (callers import these from here)
    PROJECTION_FAILED,
    TEST_ANGMOM,
    TEST_ENERGY,
    model_integral,
)
from solvers.kernels.sections import (  # noqa: F401 (callers import these from here)
    SECTION_ANDOYER_G,
    SECTION_LINEAR,
    SECTION_NONE,
    section_value,
)

# --- what the integrator's status codes (control.py) say -------------------------------
STATUS_TEXT = {
    MAX_STEPS: "the step budget (max_steps attempts) ran out before the last output time",
    STEP_UNDERFLOW: "step size underflow: the error test cannot be met with h > 16 ulp(t)",
    SECTION_TANGENT: "ds/dt vanished while locating a section crossing (tangency)",
    PROJECTION_FAILED: "projection onto the integrals failed (undefined value or "
                       "singular gradient)",
    CROSSINGS_DONE: "stopped after the requested number of section crossings",
}
SUCCESS = (L.OK, CROSSINGS_DONE)

# --- packed arguments (indices) ----------------------------------------------------------
M_STAGES, M_NEW, M_ERRKIND, M_ORDER, M_ERRORDER = range(5)          # meth (int64)
I_MAX_STEPS, I_COMPENSATED, I_PROJECT_EVERY, I_SECTION, I_DIRECTION, I_MAX_CROSS, \
    I_FIXED = range(7)                                                 # iopt (int64)
F_RTOL, F_H, F_HMAX, F_SAFETY, F_FACMIN, F_FACMAX, F_BETA = range(7)   # fopt (float64)
S_ACCEPTED, S_REJECTED, S_RHS, S_SAMPLES, S_CROSSINGS = range(5)      # stats (int64)


@kernel
def stages(model, p, t, y, h, A, c, i0, i1, K, ytmp, stats):
    """k_i = f(t + c_i h, y + h sum_j a_ij k_j) for i0 <= i < i1; returns a status."""
    n = y.shape[0]
    for i in range(i0, i1):
        for m in range(n):
            acc = 0.0
            for j in range(i):
                acc += A[i, j] * K[j, m]
            ytmp[m] = y[m] + h * acc
        stats[S_RHS] += 1
        st = rhs(model, t + c[i] * h, ytmp, p, K[i])
        if st != L.OK:
            return st
    return L.OK


@kernel
def initial_step(model, p, t, y, f0, order, rtol, atol, span, hmax, y1, f1, stats):
    """Hairer's starting step (Solving ODEs I, Sec. II.4; control.py) from its sums."""
    n = y.shape[0]
    q0 = 0.0
    q1 = 0.0
    for m in range(n):
        sc = atol[m] + rtol * abs(y[m])
        q0 += (y[m] / sc) ** 2
        q1 += (f0[m] / sc) ** 2
    h0, d1 = first_guess(q0, q1, n, span)
    for m in range(n):
        y1[m] = y[m] + h0 * f0[m]
    stats[S_RHS] += 1
    if rhs(model, t + h0, y1, p, f1) != L.OK:
        return first_step_singular(h0, hmax)
    q2 = 0.0
    for m in range(n):
        sc = atol[m] + rtol * abs(y[m])
        q2 += ((f1[m] - f0[m]) / sc) ** 2
    return first_step(h0, d1, q2, n, 1.0 / (order + 1), span, hmax)


@kernel
def henon_step(model, p, z0, f0, ds, A, c, b, s, code, coef, KH, z, ztmp, yb, fb, grad,
                stats):
    """One RK step of length ds in the independent variable s (Henon, Physica D 5 (1982)
    412): d(y, t)/ds = (f, 1) / (ds/dt), ds/dt = grad s . f, from z0 = (y, t) with
    f0 = f(t, y). The end (y, t) goes to z. Returns a status."""
    n = fb.shape[0]
    for i in range(s):
        if i == 0:
            for m in range(n):
                yb[m] = z0[m]
                fb[m] = f0[m]
        else:
            for m in range(n + 1):
                acc = 0.0
                for j in range(i):
                    acc += A[i, j] * KH[j, m]
                ztmp[m] = z0[m] + ds * acc
            for m in range(n):
                yb[m] = ztmp[m]
            stats[S_RHS] += 1
            st = rhs(model, ztmp[n], yb, p, fb)
            if st != L.OK:
                return st
        section_value(code, yb, coef, grad)
        sdot = 0.0
        for m in range(n):
            sdot += grad[m] * fb[m]
        if sdot == 0.0 or not np.isfinite(1.0 / sdot):
            return SECTION_TANGENT
        for m in range(n):
            KH[i, m] = fb[m] / sdot
        KH[i, n] = 1.0 / sdot
    for m in range(n + 1):
        acc = 0.0
        for i in range(s):
            acc += b[i] * KH[i, m]
        z[m] = z0[m] + ds * acc
    return L.OK


@kernel
def locate_crossing(model, p, t0, y0, f0, s0, A, c, b, s, code, coef, KH, z0, z, ztmp, yb,
                     fb, grad, stats):
    """Crossing of s = 0 from (t0, y0) with s(y0) = s0: a Henon step of length -s0, then
    up to two more from the result until s is at round-off. Result (y, t) in z."""
    n = y0.shape[0]
    for m in range(n):
        z0[m] = y0[m]
        fb[m] = f0[m]
    z0[n] = t0
    ds = -s0
    for it in range(3):
        st = henon_step(model, p, z0, fb, ds, A, c, b, s, code, coef, KH, z, ztmp, yb, fb,
                         grad, stats)
        if st != L.OK:
            return st
        for m in range(n):
            yb[m] = z[m]
        val = section_value(code, yb, coef, grad)
        scale = abs(coef[n])
        for m in range(n):
            scale += abs(coef[m] * yb[m])
        if code == SECTION_ANDOYER_G:
            scale = 1.0       # s = sin(g - g0) is O(1)
        if abs(val) <= 4.0 * EPS * scale or it == 2:
            return L.OK
        for m in range(n + 1):
            z0[m] = z[m]
        stats[S_RHS] += 1
        st = rhs(model, z[n], yb, p, fb)
        if st != L.OK:
            return st
        ds = -val
    return L.OK


@kernel
def refine_crossing(model, p, t, y, t_new, A, c, b, s, code, coef, K, ytmp, KH, z0, z, ztmp,
                     grad, stats):
    """Newton on the crossing time with full RK steps from (t, y): Henon's step (one RK
    step in s, no error control) is only as accurate as 1/(ds/dt) is smooth over it, so
    its time z[n] is corrected by tc <- tc - s(y(tc)) / (ds/dt), y(tc) a step of length
    tc - t from the start of the accepted step (a shorter step than an accepted one: within
    the tolerance), and the converged point is put on s = 0 by a Henon step of length -s
    (round-off). K[1:] is overwritten; z is left as it is unless this converges inside
    the step. Runs once per crossing (two small work vectors)."""
    n = y.shape[0]
    yc = np.empty(n)
    fb = np.empty(n)
    tc = z[n]
    for it in range(5):
        hc = tc - t
        st = stages(model, p, t, y, hc, A, c, 1, s, K, ytmp, stats)
        if st != L.OK:
            return
        for m in range(n):
            acc = 0.0
            for i in range(s):
                acc += b[i] * K[i, m]
            yc[m] = y[m] + hc * acc
        sv = section_value(code, yc, coef, grad)
        stats[S_RHS] += 1
        if rhs(model, tc, yc, p, fb) != L.OK:
            return
        sdot = 0.0
        for m in range(n):
            sdot += grad[m] * fb[m]
        if sdot == 0.0 or not np.isfinite(sv / sdot):
            return
        dt = -sv / sdot
        # converged to round-off (near tangency s's round-off over a small ds/dt keeps
        # |dt| above 4 eps |t|: the fifth iterate is taken if it moved by < 1e-6 h)
        if abs(dt) <= 4.0 * EPS * max(1.0, abs(tc)) or \
                (it == 4 and abs(dt) <= 1e-6 * abs(t_new - t)):
            if t <= tc <= t_new:
                locate_crossing(model, p, tc, yc, fb, sv, A, c, b, s, code, coef, KH, z0,
                                 z, ztmp, ytmp, fb, grad, stats)
            return
        tc += dt
        if not (t <= tc <= t_new):
            return
