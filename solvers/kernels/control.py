"""The step control of the explicit Runge-Kutta kernels, written once.

The loop kernel (rk.py, on arrays) and the small kernels (small.py, on scalars, generated
per structure and tableau) differ only in how they hold the state and evaluate the
stages: a loop over the tableau's arrays or its nonzero coefficients unrolled. What they
decide from those numbers is here, and both call it (Hairer, Norsett & Wanner, Solving
ODEs I, Sec. II.4):
  - Hairer's starting step (first_guess, first_step, first_step_singular);
  - the step's length before it is tried: the largest step, the landing on the target
    time and the underflow test (clip_step);
  - the error norm from its sums (error_norm; the loop kernel's sums: error_sums);
  - the step after a failed error test (shrink) and the PI controller after an accepted
    one (grow);
  - the new point with or without compensated (Kahan) summation (advance; the collocation
    kernel gauss.py uses it too), the step's end time and its compensation (step_end,
    time_compensation);
  - the section's crossing test and the grazing rule (crosses, halve);
  - the exit of a kernel (finish, shared with gauss.py).
Each is compiled with forceinline: typed once per process and inlined by LLVM at its call
sites, so a kernel's machine code is what it was with the lines written out in it, and the
operations, their operands and their order are the ones each kernel wrote itself before
(the same bits: tests/test_small.py, tests/test_generated_integrator.py).

Nothing here calls the field: one compiled copy serves every field and kernel.
"""

import numba
import numpy as np

from solvers.kernels.jit import kernel
from solvers.kernels.layout import EPS

# the kernels' options (jit.kernel), inlined by LLVM where they are called
inline = numba.njit(cache=True, error_model="numpy", nogil=True, forceinline=True)

# --- status codes added by the integrator (0..5 are the rhs codes of layout.py) --------
MAX_STEPS = 20
STEP_UNDERFLOW = 21
SECTION_TANGENT = 22
CROSSINGS_DONE = 24       # a success: the requested number of crossings was found

ERR_EMBEDDED, ERR_DOP853 = 0, 1
GRAZE_H = 1e-9            # grazing section crossings are resolved down to h = GRAZE_H |t|


@inline
def first_guess(q0, q1, n, span):
    """Hairer's first trial step from q0 = sum (y_m / sc_m)^2 and q1 = sum (f_m / sc_m)^2
    (sc = atol + rtol |y|): returns (h0, d1), d1 the RMS norm of f."""
    d0 = np.sqrt(q0 / n)
    d1 = np.sqrt(q1 / n)
    h0 = 1e-6 if (d0 < 1e-5 or d1 < 1e-5) else 0.01 * d0 / d1
    return min(h0, span), d1


@inline
def first_step(h0, d1, q2, n, expo, span, hmax):
    """Hairer's starting step from the trial step h0, q2 = sum ((f(y + h0 f) - f) / sc)^2
    and expo = 1 / (order + 1)."""
    d2 = np.sqrt(q2 / n) / h0
    if max(d1, d2) <= 1e-15:
        h1 = max(1e-6, h0 * 1e-3)
    else:
        h1 = (0.01 / max(d1, d2)) ** expo
    return min(100.0 * h0, h1, span, hmax)


@inline
def first_step_singular(h0, hmax):
    """The starting step when the field is singular at the trial point."""
    return min(h0 * 1e-3, hmax)


@inline
def clip_step(h, hmax, t, target):
    """(h, h_proposed, landing, ok): the step to try from t, at most hmax, stretched or
    cut to land on target when it would end within 1 % of it; ok is False when h is
    below 16 ulp(t) (step size underflow)."""
    h = min(h, hmax)
    h_proposed = h
    landing = t + 1.01 * h >= target
    if landing:
        return target - t, h_proposed, True, True
    return h, h_proposed, False, h > 16.0 * EPS * abs(t)


@inline
def error_norm(e1, e2, h, n, errkind):
    """The scaled RMS error of a step from e1 = sum (err_m / sc_m)^2 (and, for DOP853,
    e2 of its 3rd-order estimate: Hairer's |err5|^2 / sqrt(|err5|^2 + 0.01 |err3|^2))."""
    if errkind == ERR_DOP853:
        if e1 == 0.0 and e2 == 0.0:
            return 0.0
        return abs(h) * e1 / np.sqrt((e1 + 0.01 * e2) * n)
    return abs(h) * np.sqrt(e1 / n)


@kernel
def error_sums(E, K, s, h, y, ynew, atol, rtol, errkind):
    """error_norm of the stages K with the error weights E (the loop kernel's form: rows
    of E, sc = atol + rtol max(|y|, |ynew|))."""
    n = y.shape[0]
    e1 = 0.0
    e2 = 0.0
    for m in range(n):
        sc = atol[m] + rtol * max(abs(y[m]), abs(ynew[m]))
        a = 0.0
        for i in range(s):
            a += E[0, i] * K[i, m]
        e1 += (a / sc) ** 2
        if errkind == ERR_DOP853:
            a = 0.0
            for i in range(s):
                a += E[1, i] * K[i, m]
            e2 += (a / sc) ** 2
    return error_norm(e1, e2, h, n, errkind)


@inline
def shrink(h, err, rexpo, safety, facmin):
    """The step after a failed error test (or a NaN error), rexpo = -1 / (q + 1): never
    longer, never shorter than facmin h."""
    fac = safety * err ** rexpo if np.isfinite(err) else 0.0
    return h * min(1.0, max(facmin, fac))


@inline
def grow(h, err, err_old, expo, beta, safety, facmin, facmax, rejected_last, landing,
         h_proposed):
    """The PI (Lund-stabilized) controller of Hairer's DOPRI5 after an accepted step,
    expo = 1 / (q + 1) - 0.75 beta: (next h, err_old for the next step). After a
    rejection the step may not grow; a step cut to land on an output time says little of
    h, so the step proposed before the cut is kept if longer."""
    if err == 0.0:
        fac = facmax
    else:
        fac = safety * err ** (-expo) * err_old ** beta
        fac = min(facmax, max(facmin, fac))
    if rejected_last:
        fac = min(fac, 1.0)
    h = h * fac
    if landing and h < h_proposed:
        h = h_proposed
    return h, max(err, 1e-4)


@inline
def advance(y, d, c, compensated):
    """(y + d, its round-off) for one component; compensated: d first takes the carried
    compensation c (Kahan)."""
    if compensated:
        d += c
    yn = y + d
    return yn, d - (yn - y)


@inline
def step_end(t, h, t_comp, target, landing, compensated):
    """The time at the end of a step of h from t (the target itself when landing)."""
    if landing:
        return target
    return t + (h + t_comp if compensated else h)


@inline
def time_compensation(t, h, t_comp, t_new, landing, compensated):
    """The round-off of t_new = t + h carried to the next step (compensated sums)."""
    if compensated and not landing:
        return (h + t_comp) - (t_new - t)
    return 0.0


@inline
def crosses(s_old, s_new, direction):
    """Whether s crosses zero in the step, in `direction` (+1 up, -1 down, 0 both)."""
    return (direction >= 0 and s_old < 0.0 <= s_new) or \
        (direction <= 0 and s_old > 0.0 >= s_new)


@inline
def halve(from_start, h, t):
    """Whether a step whose ends misread the section (crossing_start's 2) is halved: down
    to GRAZE_H |t|, below which the grazing pair is at round-off distance."""
    return from_start == 2 and abs(h) > GRAZE_H * max(1.0, abs(t))


@inline
def finish(y, y_stop, status, t):
    """A kernel's exit: the state at the stop time into y_stop, (status, t_stop)."""
    y_stop[:] = y
    return status, t
