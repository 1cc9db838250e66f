"""Adaptive explicit Runge-Kutta integration of `fields.rhs`, compiled; the method is data.

One kernel, `rk_integrate`, runs every method of `solvers.integrate.tableaux`: the tableau comes in
as arrays (A, c, b, error weights E, dense-output weights P), so all methods share one
numba specialization. What it does, in order, for each step (Hairer, Norsett & Wanner,
Solving ODEs I, Sec. II.4-II.6 and II.10):
  1. stages k_1..k_s (k_1 = f(t_n, y_n) carried over from the previous step); a stage
     whose rhs returns a singular status rejects the step and shrinks h by 4: a too-long
     trial step may leave the physical domain. Only if h underflows there (the trajectory
     itself reaches the singularity) does the run stop, with that rhs status.
  2. y_{n+1} = y_n + h sum b_i k_i, optionally with compensated (Kahan) summation.
  3. error: scaled RMS norm of h sum e_i k_i with sc = atol + rtol max(|y_n|, |y_{n+1}|);
     DOP853 uses Hairer's |err5|^2 / sqrt(|err5|^2 + 0.01 |err3|^2). Step control: the PI
     (Lund-stabilized) controller of Hairer's DOPRI5 with safety/min/max factors; after a
     rejection the next step may not grow. Fixed-step mode skips 1-3's error test.
  4. accepted: k_new = f(t_{n+1}, y_{n+1}) (the FSAL stage, or the extra stage `new`);
     optional projection onto known integrals (simplified Newton, gradient by complex
     step); outputs inside the step from the dense output; section crossings located by
     Henon's trick.
Output times: with dense output (every method we ship; vern9 uses Verner's 8th-order
interpolant, 4 extra stages) the steps run free and the samples are interpolated, the
weights in Chebyshev form on the step (`tableaux._chebyshev`); the extra dense stages are
evaluated only for steps holding a sample, so sampling never changes the steps. Without
dense output (a tableau without one, or dense_output=False) the steps are clipped to land
on each t_out. Samples strictly inside a step come from the interpolant of the
unprojected step; when projection is on they are projected too (whatever
project_every), so that every output lies on the integral manifold.

Fixed-step mode (fopt[F_H] > 0 with iopt[I_FIXED]) has no error control: it is for order
studies and will step over a singularity it does not land on.

What the step decides from its numbers (the starting step, the step's length, the error
norm, the controller, the compensated sums, the section's crossing test) is control.py's,
shared with the small kernels (small.py), which write the same step on scalars. The
projection (projection.py), the section's value and crossing tests (sections.py) and the
step control call no field: one compiled copy serves every field. The functions here call
the field; a case's generated field gets them bound to it (solvers/kernels/bind.py).

The kernel allocates its work arrays once per call; the step loop allocates nothing (the
model's rhs is another matter: see fields.py).
"""

import numpy as np

from solvers.kernels import layout as L
from solvers.kernels.control import (  # noqa: F401 (callers import these from here)
    CROSSINGS_DONE,
    ERR_DOP853,
    ERR_EMBEDDED,
    GRAZE_H,
    MAX_STEPS,
    SECTION_TANGENT,
    STEP_UNDERFLOW,
    advance,
    clip_step,
    crosses,
    error_sums,
    finish,
    first_guess,
    first_step,
    first_step_singular,
    grow,
    halve,
    shrink,
    step_end,
    time_compensation,
)
from solvers.kernels.fields import rhs
from solvers.kernels.jit import kernel
from solvers.kernels.layout import EPS
from solvers.kernels.projection import (  # noqa: F401 (callers import these from here)
    PROJECTION_FAILED,
    TEST_ANGMOM,
    TEST_ENERGY,
    model_integral,
    project,
)
from solvers.kernels.sections import (  # noqa: F401 (callers import these from here)
    SECTION_ANDOYER_G,
    SECTION_LINEAR,
    SECTION_NONE,
    crossing_start,
    section_accept,
    section_step_error,
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
def _stages(model, p, t, y, h, A, c, i0, i1, K, ytmp, stats):
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
def _initial_step(model, p, t, y, f0, order, rtol, atol, span, hmax, y1, f1, stats):
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
def _henon_step(model, p, z0, f0, ds, A, c, b, s, code, coef, KH, z, ztmp, yb, fb, grad,
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
        st = _henon_step(model, p, z0, fb, ds, A, c, b, s, code, coef, KH, z, ztmp, yb, fb,
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
        st = _stages(model, p, t, y, hc, A, c, 1, s, K, ytmp, stats)
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


@kernel
def rk_integrate(model, p, y0, t_out, A, c, b, E, P, meth, iopt, fopt, atol, proj_codes,
                 proj_vals, sec_coef, Y, cross_t, cross_y, y_stop, stats):
    """Integrate from (t_out[0], y0) through the increasing output times t_out.

    Fills Y[j] for the output times reached (stats[S_SAMPLES] of them), cross_t/cross_y
    with the section crossings, y_stop with the state at the returned stop time and
    stats; returns (status, t_stop).
    """
    n = y0.shape[0]
    S = A.shape[0]
    s = meth[M_STAGES]
    new = meth[M_NEW]
    errkind = meth[M_ERRKIND]
    q = meth[M_ERRORDER]
    has_dense = P.shape[0] > 0
    ncheb = P.shape[1]
    fixed = iopt[I_FIXED] != 0
    compensated = iopt[I_COMPENSATED] != 0
    project_every = iopt[I_PROJECT_EVERY]
    code = iopt[I_SECTION]
    direction = iopt[I_DIRECTION]
    max_cross = iopt[I_MAX_CROSS]
    rtol = fopt[F_RTOL]
    hmax = fopt[F_HMAX]
    safety = fopt[F_SAFETY]
    beta = fopt[F_BETA]
    expo = 1.0 / (q + 1) - 0.75 * beta
    nproj = proj_codes.shape[0]

    K = np.zeros((S, n))
    y = y0.copy()
    ynew = np.empty(n)
    ytmp = np.empty(n)
    fnew = np.empty(n)
    comp = np.zeros(n)
    comp_new = np.zeros(n)
    w = np.empty(S)
    G = np.empty((nproj, n))
    Mw = np.empty((nproj, nproj))
    rw = np.empty(nproj)
    lam = np.empty(nproj)
    yc = np.empty(n, dtype=np.complex128)
    KH = np.empty((s, n + 1))
    z0 = np.empty(n + 1)
    z = np.empty(n + 1)
    ztmp = np.empty(n + 1)
    grad = np.empty(n)
    fb = np.empty(n)
    for i in range(stats.shape[0]):
        stats[i] = 0

    N = t_out.shape[0]
    t = t_out[0]
    t_end = t_out[N - 1]
    Y[0, :] = y
    stats[S_SAMPLES] = 1
    stats[S_RHS] = 1
    status = rhs(model, t, y, p, K[0])
    if status != L.OK or N == 1:
        return finish(y, y_stop, status, t)
    if fixed or fopt[F_H] > 0.0:
        h = fopt[F_H]
    else:
        h = _initial_step(model, p, t, y, K[0], meth[M_ORDER], rtol, atol, t_end - t, hmax,
                          ytmp, K[1], stats)
    s_old = section_value(code, y, sec_coef, grad) if code != SECTION_NONE else 0.0
    err_old = 1e-4
    rejected_last = False
    t_comp = 0.0
    j = 1
    attempts = 0
    while j < N:
        if attempts >= iopt[I_MAX_STEPS]:
            status = MAX_STEPS
            break
        attempts += 1
        target = t_end if has_dense else t_out[j]
        h, h_proposed, landing, ok = clip_step(h, hmax, t, target)
        if not ok:
            status = STEP_UNDERFLOW if status == L.OK else status
            break
        status = L.OK
        # 1.-2. stages and the new point
        st = _stages(model, p, t, y, h, A, c, 1, s, K, ytmp, stats)
        err = 0.0
        if st == L.OK:
            for m in range(n):
                acc = 0.0
                for i in range(s):
                    acc += b[i] * K[i, m]
                ynew[m], comp_new[m] = advance(y[m], h * acc, comp[m], compensated)
            # 3. error test
            if not fixed:
                err = error_sums(E, K, s, h, y, ynew, atol, rtol, errkind)
                if code == SECTION_ANDOYER_G:   # step control near the section (sections.py)
                    err = max(err, section_step_error(y, ynew, sec_coef, q))
            if err <= 1.0:
                t_new = step_end(t, h, t_comp, target, landing, compensated)
                if new >= s:
                    stats[S_RHS] += 1
                    st = rhs(model, t_new, ynew, p, K[new])
        if st != L.OK:            # singular stage: shrink; stop only if h underflows
            status = st
            if fixed:
                break
            stats[S_REJECTED] += 1
            rejected_last = True
            h = 0.25 * h
            continue
        if not (err <= 1.0):      # error test failed (or NaN)
            stats[S_REJECTED] += 1
            rejected_last = True
            h = shrink(h, err, -1.0 / (q + 1), safety, fopt[F_FACMIN])
            continue
        # a step whose ends misread the section (a grazing pair of crossings inside, or s
        # not monotone towards its crossing) is halved until they do; below GRAZE_H the
        # pair is at round-off distance and left unresolved
        from_start = 0
        if code != SECTION_NONE:
            from_start = crossing_start(code, sec_coef, y, K[0], ynew, K[new], h, grad,
                                         direction)
            if not fixed and halve(from_start, h, t):
                stats[S_REJECTED] += 1
                rejected_last = True
                h = 0.5 * h
                continue
        # 4. accepted
        stats[S_ACCEPTED] += 1
        t_comp = time_compensation(t, h, t_comp, t_new, landing, compensated)
        projected = nproj > 0 and stats[S_ACCEPTED] % project_every == 0
        if projected:
            status = project(model, p, ynew, proj_codes, proj_vals, G, Mw, rw, lam, yc)
            if status != L.OK:
                break
            for m in range(n):
                comp_new[m] = 0.0
            stats[S_RHS] += 1
            status = rhs(model, t_new, ynew, p, fnew)
            if status != L.OK:
                break
        else:
            for m in range(n):
                fnew[m] = K[new, m]
        # outputs inside (t, t_new]
        extra_done = False
        while j < N and t_out[j] <= t_new:
            if t_out[j] == t_new:
                Y[j, :] = ynew
                if nproj > 0 and not projected:
                    status = project(model, p, Y[j], proj_codes, proj_vals, G, Mw, rw, lam,
                                      yc)
                    if status != L.OK:
                        break
            else:
                if not extra_done:
                    status = _stages(model, p, t, y, h, A, c, max(s, new + 1), S, K, ytmp,
                                     stats)
                    if status != L.OK:
                        break
                    extra_done = True
                x = 2.0 * (t_out[j] - t) / h - 1.0
                for i in range(S):      # Clenshaw: w_i = sum_k P[i, k] T_k(x)
                    b1 = 0.0
                    b2 = 0.0
                    for k in range(ncheb - 1, 0, -1):
                        b1, b2 = P[i, k] + 2.0 * x * b1 - b2, b1
                    w[i] = P[i, 0] + x * b1 - b2
                for m in range(n):
                    acc = 0.0
                    for i in range(S):
                        acc += w[i] * K[i, m]
                    Y[j, m] = y[m] + h * acc
                if nproj > 0:   # interpolated samples join the projected trajectory
                    status = project(model, p, Y[j], proj_codes, proj_vals, G, Mw, rw, lam,
                                      yc)
                    if status != L.OK:
                        break
            j += 1
        stats[S_SAMPLES] = j
        if status != L.OK:
            break
        # section crossing between (t, y) and (t_new, ynew)
        if code != SECTION_NONE:
            s_new = section_value(code, ynew, sec_coef, grad)
            if crosses(s_old, s_new, direction):
                k = stats[S_CROSSINGS]
                if from_start != -1:    # the end s runs monotonically from (see above)
                    status = locate_crossing(model, p, t, y, K[0], s_old, A, c, b, s, code,
                                              sec_coef, KH, z0, z, ztmp, ytmp, fb, grad, stats)
                else:
                    status = locate_crossing(model, p, t_new, ynew, fnew, s_new, A, c, b, s,
                                              code, sec_coef, KH, z0, z, ztmp, ytmp, fb, grad,
                                              stats)
                if status != L.OK:
                    break
                refine_crossing(model, p, t, y, t_new, A, c, b, s, code, sec_coef, K, ytmp,
                                 KH, z0, z, ztmp, grad, stats)
                if section_accept(code, z, sec_coef):   # refuses g = g0 + pi (sections.py)
                    cross_t[k] = z[n]
                    cross_y[k, :] = z[:n]
                    stats[S_CROSSINGS] = k + 1
            s_old = s_new
        # commit the step
        t = t_new
        for m in range(n):
            y[m] = ynew[m]
            comp[m] = comp_new[m]
            K[0, m] = fnew[m]
        if code != SECTION_NONE and stats[S_CROSSINGS] >= max_cross:
            status = CROSSINGS_DONE
            break
        # next step size
        if fixed:
            h = fopt[F_H]
        else:
            h, err_old = grow(h, err, err_old, expo, beta, safety, fopt[F_FACMIN],
                              fopt[F_FACMAX], rejected_last, landing, h_proposed)
        rejected_last = False
    return finish(y, y_stop, status, t)
