"""Gauss-Legendre collocation (implicit Runge-Kutta, symmetric), fixed step, compiled.

The s-stage Gauss method has order 2s and is symmetric (time-reversible): the map
y_n -> y_{n+1} of step h is inverted by the step -h. Applied with a constant step to a
reversible system (the Chaplygin ball, the balanced and Routh balls, the disk: all
reversible under t -> -t, M -> -M) near an invariant torus, a symmetric method has no
secular drift of the first integrals: their error stays bounded, O(h^2s), over times
exponentially long in 1/h (Hairer, Lubich & Wanner, Geometric Numerical Integration, XI;
the reversible KAM theory). An adaptive explicit method drifts linearly in t instead.

Two things keep that property in floating point (GNI, VIII.5):
  - the stage equations are solved by fixed-point iteration *to round-off*: iterate
    until the update stops decreasing (or is zero), not to a tolerance;
  - the update y_{n+1} = y_n + h sum b_i k_i is summed with compensation (Kahan), so the
    round-off of the state is a random walk (Brouwer's law) and not a linear drift.
Starting values of the iteration come from the previous step's collocation polynomial,
extrapolated (GNI VIII.6, equal steps): usually 5-8 iterations per step at h where the
method's error is 1e-12.

The steps are equal inside each output interval [t_k, t_{k+1}] (m_k = ceil(dt / h)
steps of dt / m_k): a variable step would break the symmetry. Output times are step
endpoints, so no dense output is needed. There is no error control: the step is the
user's choice (`solvers.integrate.integrator.integrate(method="gauss8", h_fixed=...)`).
"""

import numpy as np

from solvers.kernels import layout as L
from solvers.kernels.control import MAX_STEPS, advance, finish
from solvers.kernels.fields import rhs
from solvers.kernels.jit import kernel

NO_CONVERGENCE = 25       # an integrator status (control.py holds 20..24)
STATUS_TEXT = {NO_CONVERGENCE: "the implicit stages could not be solved: their fixed-point "
                               "iteration stalled or diverged, or a stage value left the "
                               "field's domain (take a smaller step; if that persists, the "
                               "motion reaches a singularity of the field)"}
G_STEPS, G_RHS, G_ITER, G_SAMPLES = range(4)          # stats (int64)


@kernel
def gauss_integrate(model, p, y0, t_out, A, b, c, X, h_req, max_steps, max_iter, Y, y_stop,
                    stats):
    """Integrate from (t_out[0], y0) with the s-stage collocation method (A, b, c) and
    steps of at most h_req; Y[k] = y(t_out[k]). X[i, j]: weight of the previous step's
    stage derivative j in the starting value of stage i (extrapolated collocation
    polynomial, valid for an equal step). Returns (status, t_stop)."""
    n = y0.size
    s = b.size
    K = np.empty((s, n))          # stage derivatives k_i = f(t + c_i h, Y_i)
    Kold = np.empty((s, n))
    Ys = np.empty(n)
    y = y0.copy()
    comp = np.zeros(n)            # Kahan compensation of y
    f0 = np.empty(n)
    for j in range(n):
        Y[0, j] = y[j]
    stats[G_SAMPLES] = 1
    have_old = False
    h_old = 0.0
    t = t_out[0]
    for k in range(t_out.size - 1):
        span = t_out[k + 1] - t_out[k]
        m = int(np.ceil(span / h_req * (1.0 - 1e-14)))
        if m < 1:
            m = 1
        h = span / m
        if not (h == h_old):
            have_old = False
        for step in range(m):
            t = t_out[k] + step * h
            if stats[G_STEPS] >= max_steps:
                return finish(y, y_stop, MAX_STEPS, t)
            # starting values
            if have_old:
                for i in range(s):
                    for j in range(n):
                        acc = 0.0
                        for q in range(s):
                            acc += X[i, q] * Kold[q, j]
                        K[i, j] = acc
            else:
                st = rhs(model, t, y, p, f0)
                stats[G_RHS] += 1
                if st != L.OK:
                    return finish(y, y_stop, st, t)
                for i in range(s):
                    for j in range(n):
                        K[i, j] = f0[j]
            # fixed-point iteration to round-off
            prev = np.inf
            it = 0
            while True:
                it += 1
                dmax = 0.0
                ymax = 0.0
                for i in range(s):
                    for j in range(n):
                        acc = 0.0
                        for q in range(s):
                            acc += A[i, q] * K[q, j]
                        Ys[j] = y[j] + h * acc
                    st = rhs(model, t + c[i] * h, Ys, p, f0)
                    stats[G_RHS] += 1
                    if st != L.OK:        # a stage outside the field's domain
                        return finish(y, y_stop, NO_CONVERGENCE, t)
                    for j in range(n):
                        d = abs(f0[j] - K[i, j])
                        if d > dmax:
                            dmax = d
                        a = abs(f0[j])
                        if a > ymax:
                            ymax = a
                        K[i, j] = f0[j]
                stats[G_ITER] += 1
                if dmax == 0.0 or (dmax >= prev and dmax <= 1e-10 * (ymax + 1e-300)):
                    break             # converged: the update no longer decreases
                if it >= max_iter or (it >= 3 and dmax >= prev):   # stalled or diverging
                    return finish(y, y_stop, NO_CONVERGENCE, t)
                prev = dmax
            # update with compensated summation (control.advance)
            for j in range(n):
                acc = 0.0
                for i in range(s):
                    acc += b[i] * K[i, j]
                y[j], comp[j] = advance(y[j], h * acc, comp[j], True)
                if not np.isfinite(y[j]):
                    return finish(y, y_stop, L.SING_NONFINITE, t)
            for i in range(s):
                for j in range(n):
                    Kold[i, j] = K[i, j]
            have_old = True
            h_old = h
            stats[G_STEPS] += 1
        t = t_out[k + 1]
        for j in range(n):
            Y[k + 1, j] = y[j]
        stats[G_SAMPLES] += 1
    return finish(y, y_stop, L.OK, t)
