"""How close to the compiled limit: time at matched error, side by side in one process.

Competitors, each traced over a range of tolerances (a work-precision front), its time at
a matched final-state error interpolated (log-log) on that front:
  limit        a DOP853 written by hand in numba (scipy's coefficients, loops over constant
               arrays), the field written by hand and inlined (inline='always'): the
               Chaplygin ball, the disk and the body with a flat base (the gyrostat
               term S x omega of the flat base is zero in this example and left out).
               It is the independent baseline and stays a step of its own, apart from
               the project's one Runge-Kutta step (the template solvers/kernels/step.py
               and the step control of control.py, from which the loop kernel and the
               small kernels are made): a reference that shared that code could not
               show its cost;
  lean-dop853  the same hand-written DOP853 on the generated field of the case
               (solvers/kernels/generate.py): what the generated field alone buys;
  ours         the project's integrate(): general rk_integrate kernel, general field;
  ours-generated  integrate(generated=True): on these plain runs the small kernel
               (solvers/kernels/small.py), what integrate() and simulate() run by default,
               through the Python entry;
  gen-loops    the loop kernel compiled against the case's generated field, inlined
               (field_modules.generated_integrator: what generated=True runs with a section or
               a projection), called directly (packed arrays reused: no entry);
  heyoka-lean  heyoka's Taylor integrator on the generated lean expressions;
  heyoka-gen   heyoka on the general expression system (solvers/integrate/taylor.py);
  scipy-scalar scipy DOP853 on the best plain-Python scalar field (math.sqrt, tuples);
  scipy-numpy  scipy DOP853 on the independent NumPy field (solvers/models/reference.py).
Errors: max-norm of the state at T against heyoka in long double (tol 1e-18). Timing:
per tolerance the competitors run interleaved (A B C A B C ...), best of REPEATS; scipy
once. On a loaded machine a best-of-5 can still be slowed: the "robust" column takes the
rhs calls at the matched error (deterministic) times the lowest cost per call on that
competitor's front (Runge-Kutta competitors only). A breakdown (ns per rhs call, steps,
the field alone) says where the time goes.

    PYTHONPATH=$PWD .venv/bin/python bench/limit.py [--quick] [--cases a,b]
        [--repeats N] [--batch MS] [--t-end T]
        many starts (many_starts below): ours (integrate()) against the scalar limit
        (make_scalar_dop853) and heyoka-lean over 20 random starts per case
        -> bench/results/limit_starts.txt (--quick: 5 starts, T <= 200,
        limit_starts_quick.txt, not kept). --repeats N: each time the best of N (default
        3); --batch MS: each measurement a batch of back-to-back calls filling MS ms,
        divided by their number (timeit's way); --t-end T: every case run to T instead of
        its own; --cases a,b: only these cases (the same starts as a whole run)
    PYTHONPATH=$PWD .venv/bin/python bench/limit.py --work
        the many-start mode's starts counted in rhs calls at matched error (no clock):
        ours, ours with the limit's controller, the limit, the limit on the generated field
        (work_split below) -> bench/results/limit_work.txt
    PYTHONPATH=$PWD .venv/bin/python bench/limit.py --extension
        the plane ball's field in three extensions off |gamma| = 1 (hand-written,
        generated, a ball of radius c |gamma|) in the limit's DOP853: rhs calls at matched
        error on five bodies (extension below) -> bench/results/limit_extension.txt
    PYTHONPATH=$PWD .venv/bin/python bench/limit.py --gap [--case plane/ellipsoid]
        where the gap lies on one case (gap below): steps, rhs calls and errors at equal
        tolerances, ns per rhs call with the small kernel called directly, and
        integrate()'s entry -> bench/results/limit_gap.txt
    PYTHONPATH=$PWD .venv/bin/python bench/limit.py --fronts [--quick]
        the one-start fronts described above -> bench/results/limit.txt (--quick:
        limit_quick.txt, not kept)
--fronts --quick: 5 tolerances (1e-6 ... 1e-12), best of 3, no scipy-numpy and no heyoka-gen
(~3 min once the kernels are compiled; a fresh cache first compiles the generated kernels,
~2 min a case).
"""

import itertools
import math
import os
import sys
import time
import timeit
from functools import partial
from pathlib import Path

import numba
import numpy as np
from scipy.integrate import solve_ivp
from scipy.integrate._ivp import dop853_coefficients as DC

from solvers.integrate.integrator import (
    _plain_atol,
    _plain_fopt,
    integrate,
    method_arrays,
    small_module,
)
from solvers.integrate.taylor import Taylor
from solvers.kernels import layout as L
from solvers.kernels.field_modules import generated, generated_integrator
from solvers.kernels.heyoka_field import heyoka_system
from solvers.models.cases import build, registry
from solvers.models.reference import field as ref_field

OUT = Path(__file__).with_name("results")
A = np.ascontiguousarray(DC.A[:12, :12])
B = np.ascontiguousarray(DC.B)
C = np.ascontiguousarray(DC.C[:12])
E3 = np.ascontiguousarray(DC.E3)
E5 = np.ascontiguousarray(DC.E5)


# --- the hand-written fields --------------------------------------------------------------
@numba.njit(inline="always")
def solve_sym3(a00, a01, a02, a11, a12, a22, M0, M1, M2):
    """omega = I_Q^-1 M for the symmetric I_Q by Cramer's rule (one division)."""
    c00 = a11 * a22 - a12 * a12
    c01 = a12 * a02 - a01 * a22
    c02 = a01 * a12 - a11 * a02
    inv = 1.0 / (a00 * c00 + a01 * c01 + a02 * c02)
    c11 = a00 * a22 - a02 * a02
    c12 = a01 * a02 - a00 * a12
    c22 = a00 * a11 - a01 * a01
    w0 = (c00 * M0 + c01 * M1 + c02 * M2) * inv
    w1 = (c01 * M0 + c11 * M1 + c12 * M2) * inv
    w2 = (c02 * M0 + c12 * M1 + c22 * M2) * inv
    return w0, w1, w2


@numba.njit(inline="always")
def ball_s(p, M0, M1, M2, g0, g1, g2):
    """Chaplygin ball on the plane as a user writes it for |gamma| = 1: r = R gamma,
    I_Q = I + m R^2 (E - gamma gamma^T), omega = I_Q^-1 M (Cramer), dgamma = gamma x omega,
    dr = R dgamma, dM = M x omega + m dr x (omega x r)."""
    mR2 = p[3] * p[16] * p[16]
    return ball_of_diagonal(p, M0, M1, M2, g0, g1, g2, mR2 * (1.0 - g0 * g0),
                            mR2 * (1.0 - g1 * g1), mR2 * (1.0 - g2 * g2))


@numba.njit(inline="always")
def ball_of_diagonal(p, M0, M1, M2, g0, g1, g2, e0, e1, e2):
    """ball_s with the diagonal of m (|r|^2 E - r r^T) given (e0, e1, e2), its other terms
    -m R^2 gamma_i gamma_j: r = R gamma (phys_s, --extension, gives another diagonal)."""
    I1, I2, I3, m, R = p[0], p[1], p[2], p[3], p[16]
    mR2 = m * R * R
    a00 = I1 + e0
    a11 = I2 + e1
    a22 = I3 + e2
    a01 = -mR2 * g0 * g1
    a02 = -mR2 * g0 * g2
    a12 = -mR2 * g1 * g2
    w0, w1, w2 = solve_sym3(a00, a01, a02, a11, a12, a22, M0, M1, M2)
    d0 = g1 * w2 - g2 * w1
    d1 = g2 * w0 - g0 * w2
    d2 = g0 * w1 - g1 * w0
    r0, r1, r2 = R * g0, R * g1, R * g2
    x0 = w1 * r2 - w2 * r1
    x1 = w2 * r0 - w0 * r2
    x2 = w0 * r1 - w1 * r0
    mR = m * R
    return (M1 * w2 - M2 * w1 + mR * (d1 * x2 - d2 * x1),
            M2 * w0 - M0 * w2 + mR * (d2 * x0 - d0 * x2),
            M0 * w1 - M1 * w0 + mR * (d0 * x1 - d1 * x0), d0, d1, d2)


@numba.njit(inline="always")
def ball_field(y, p, f):
    f[0], f[1], f[2], f[3], f[4], f[5] = ball_s(p, y[0], y[1], y[2], y[3], y[4], y[5])
    return 0


@numba.njit(inline="always")
def disk_s(p, M0, M1, M2, g0, g1, g2):
    """Round disk (radius R, centre of mass at the centre) on the plane with gravity:
    r = R (g1, g2, 0)/s, s = sqrt(g1^2 + g2^2), J = R/s^3 [[g2^2, -g1 g2, 0], [-g1 g2,
    g1^2, 0], [0, 0, 0]], dM = M x omega + m dr x (omega x r) + m g gamma x r."""
    I1, I2, I3, m, grav, R = p[0], p[1], p[2], p[3], p[8], p[17]
    s2 = g0 * g0 + g1 * g1
    s = math.sqrt(s2)
    Rs = R / s
    r0, r1 = Rs * g0, Rs * g1
    # I_Q = I + m (R^2 E - r r^T), r2 = 0
    mR2 = m * R * R
    a00 = I1 + mR2 - m * r0 * r0
    a11 = I2 + mR2 - m * r1 * r1
    a22 = I3 + mR2
    a01 = -m * r0 * r1
    det2 = a00 * a11 - a01 * a01
    w0 = (a11 * M0 - a01 * M1) / det2
    w1 = (a00 * M1 - a01 * M0) / det2
    w2 = M2 / a22
    d0 = g1 * w2 - g2 * w1
    d1 = g2 * w0 - g0 * w2
    d2 = g0 * w1 - g1 * w0
    q = Rs / s2
    rd0 = q * (g1 * g1 * d0 - g0 * g1 * d1)
    rd1 = q * (g0 * g0 * d1 - g0 * g1 * d0)
    x0 = -w2 * r1
    x1 = w2 * r0
    x2 = w0 * r1 - w1 * r0
    mg = m * grav
    return (M1 * w2 - M2 * w1 + m * (rd1 * x2) + mg * (-g2 * r1),
            M2 * w0 - M0 * w2 + m * (-rd0 * x2) + mg * (g2 * r0),
            M0 * w1 - M1 * w0 + m * (rd0 * x1 - rd1 * x0) + mg * (g0 * r1 - g1 * r0),
            d0, d1, d2)


@numba.njit(inline="always")
def disk_field(y, p, f):
    f[0], f[1], f[2], f[3], f[4], f[5] = disk_s(p, y[0], y[1], y[2], y[3], y[4], y[5])
    return 0


@numba.njit(inline="always")
def flat_s(p, M0, M1, M2, r0, r1):
    """Body with a flat base on a sphere of curvature k (eq3.14-3.15) as a user writes it:
    state (M, r1, r2), r = (r1, r2, z) from the point of contact to the centre of mass,
    I_Q = I + m (r^2 E - r r^T), omega = I_Q^-1 M (Cramer), dr/dt = (omega2, -omega1, 0)/k,
    dM = M x omega + m dr x (omega x r)."""
    I1, I2, I3, m, k, z = p[0], p[1], p[2], p[3], p[4], p[21]
    rr = r0 * r0 + r1 * r1 + z * z
    a00 = I1 + m * (rr - r0 * r0)
    a11 = I2 + m * (rr - r1 * r1)
    a22 = I3 + m * (rr - z * z)
    a01 = -m * r0 * r1
    a02 = -m * r0 * z
    a12 = -m * r1 * z
    w0, w1, w2 = solve_sym3(a00, a01, a02, a11, a12, a22, M0, M1, M2)
    ik = 1.0 / k
    v0 = w1 * ik
    v1 = -w0 * ik
    x0 = w1 * z - w2 * r1
    x1 = w2 * r0 - w0 * z
    x2 = w0 * r1 - w1 * r0
    return (M1 * w2 - M2 * w1 + m * (v1 * x2), M2 * w0 - M0 * w2 - m * (v0 * x2),
            M0 * w1 - M1 * w0 + m * (v0 * x1 - v1 * x0), v0, v1)


@numba.njit(inline="always")
def flat_field(y, p, f):
    f[0], f[1], f[2], f[3], f[4] = flat_s(p, y[0], y[1], y[2], y[3], y[4])
    return 0


# --- a hand-written DOP853 (Hairer's error norm and step control) ------------------------
def make_dop853(field):
    @numba.njit(nogil=True)
    def run(y0, p, T, rtol, atol):
        n = y0.shape[0]
        K = np.empty((13, n))
        y = y0.copy()
        yt = np.empty(n)
        yn = np.empty(n)
        t = 0.0
        field(y, p, K[0])
        h = 1e-3
        nfev = 1
        steps = 0
        while t < T:
            if t + h > T:
                h = T - t
            for i in range(1, 12):
                for m in range(n):
                    acc = 0.0
                    for j in range(i):
                        acc += A[i, j] * K[j, m]
                    yt[m] = y[m] + h * acc
                field(yt, p, K[i])
            for m in range(n):
                acc = 0.0
                for j in range(12):
                    acc += B[j] * K[j, m]
                yn[m] = y[m] + h * acc
            field(yn, p, K[12])
            nfev += 12
            e5 = 0.0
            e3 = 0.0
            for m in range(n):
                sc = atol + rtol * max(abs(y[m]), abs(yn[m]))
                a5 = 0.0
                a3 = 0.0
                for j in range(13):
                    a5 += E5[j] * K[j, m]
                    a3 += E3[j] * K[j, m]
                e5 += (a5 / sc) ** 2
                e3 += (a3 / sc) ** 2
            den = e5 + 0.01 * e3
            err = 0.0 if den == 0.0 else abs(h) * e5 / math.sqrt(den * n)
            if err <= 1.0:
                t += h
                steps += 1
                for m in range(n):
                    y[m] = yn[m]
                    K[0, m] = K[12, m]
                fac = 10.0 if err == 0.0 else min(10.0, 0.9 * err ** (-1.0 / 8.0))
            else:
                fac = max(0.2, 0.9 * err ** (-1.0 / 8.0))
            h *= fac
        return y, steps, nfev

    return run


# --- plain-Python scalar fields for scipy ---------------------------------------------------
def ball_scalar(p):
    I1, I2, I3, m, R = (float(p[i]) for i in (0, 1, 2, 3, 16))
    mR2, mR = m * R * R, m * R

    def f(t, y):
        M0, M1, M2, g0, g1, g2 = y
        a00 = I1 + mR2 * (1.0 - g0 * g0)
        a11 = I2 + mR2 * (1.0 - g1 * g1)
        a22 = I3 + mR2 * (1.0 - g2 * g2)
        a01, a02, a12 = -mR2 * g0 * g1, -mR2 * g0 * g2, -mR2 * g1 * g2
        c00, c01, c02 = a11 * a22 - a12 * a12, a12 * a02 - a01 * a22, a01 * a12 - a11 * a02
        inv = 1.0 / (a00 * c00 + a01 * c01 + a02 * c02)
        c11, c12, c22 = a00 * a22 - a02 * a02, a01 * a02 - a00 * a12, a00 * a11 - a01 * a01
        w0 = (c00 * M0 + c01 * M1 + c02 * M2) * inv
        w1 = (c01 * M0 + c11 * M1 + c12 * M2) * inv
        w2 = (c02 * M0 + c12 * M1 + c22 * M2) * inv
        d0, d1, d2 = g1 * w2 - g2 * w1, g2 * w0 - g0 * w2, g0 * w1 - g1 * w0
        x0 = R * (w1 * g2 - w2 * g1)
        x1 = R * (w2 * g0 - w0 * g2)
        x2 = R * (w0 * g1 - w1 * g0)
        return [M1 * w2 - M2 * w1 + mR * (d1 * x2 - d2 * x1),
                M2 * w0 - M0 * w2 + mR * (d2 * x0 - d0 * x2),
                M0 * w1 - M1 * w0 + mR * (d0 * x1 - d1 * x0), d0, d1, d2]

    return f


def generic_scalar(model, p):
    """Cases without a hand-written scalar field: the generated numba field called from
    Python (a compiled scalar field; reported as such)."""
    mod = generated(model, p)
    pp = np.asarray(p, dtype=float)

    def f(t, y):
        d = np.empty_like(y)
        mod.field(pp, y, d)
        return d

    return f


# --- the front ------------------------------------------------------------------------------
def best_of(fn, repeats):
    best, out = math.inf, None
    for _ in range(repeats):
        t0 = time.perf_counter()
        out = fn()
        best = min(best, time.perf_counter() - t0)
    return best, out


def warm_best(f, *args, repeats=3, **kw):
    """(best wall time of `repeats`, the last result) of f(*args, **kw) after one warm call
    (the compile and first-use caches out of the timing): best_of."""
    run = partial(f, *args, **kw)
    run()
    return best_of(run, repeats)


def at_error(points, target):
    """log-log interpolation of time at `target` error on the front [(err, time)]."""
    pts = sorted((e, w) for e, w in points if e > 0 and math.isfinite(e))
    for (e1, w1), (e2, w2) in itertools.pairwise(pts):
        if e1 <= target <= e2:
            if e1 == e2:
                return min(w1, w2)
            s = (math.log(target) - math.log(e1)) / (math.log(e2) - math.log(e1))
            return math.exp(math.log(w1) + s * (math.log(w2) - math.log(w1)))
    return None


def kernel_runner(kern, model, p, y0, T, method="dop853"):
    """The compiled kernel called directly, its arrays packed once (what integrate() does,
    without the Python entry)."""
    A, c, b, E, P, meth = method_arrays(method)
    n = y0.size
    t_out = np.array([0.0, T])
    Y = np.empty((2, n))
    ct, cy, ys = np.empty(1), np.empty((1, n)), np.empty(n)
    st = np.zeros(5, dtype=np.int64)
    codes, vals, sec = np.zeros(0, dtype=np.int64), np.zeros(0), np.zeros(n + 1)
    iopt = np.array([10**8, 0, 1, 0, 1, 1, 0], dtype=np.int64)

    def run(rt):
        fopt = np.array([rt, 0.0, np.inf, 0.9, 0.2, 10.0, 0.04])
        atol = np.full(n, rt * 1e-3)
        kern(model, p, y0, t_out, A, c, b, E, P, meth, iopt, fopt, atol, codes, vals, sec, Y,
             ct, cy, ys, st)
        return Y[1].copy(), int(st[0]), int(st[2])

    return run


def front(case, params, y0, T, targets, limit_field, quick=False):
    model = build(case, params)
    p = np.array(model.p)
    y0 = np.asarray(y0, dtype=float)
    ref = Taylor(model.model, p, y0, tol=1e-18, fp="longdouble").run(y0, [0.0, T])[1][-1]
    ref = np.asarray(ref, dtype=float)
    repeats = 3 if quick else 5

    def err(y):
        return float(np.max(np.abs(np.asarray(y, dtype=float) - ref)))

    rtols = [10.0 ** -k for k in ((6, 8, 10, 11, 12) if quick else (6, 7, 8, 9, 10, 11, 12))]
    gen_field = generated(model.model, p).field

    @numba.njit(inline="always")
    def lean_field(y, p, f):      # the generated field takes (p, y, dydt)
        return gen_field(p, y, f)

    # each runner: rt -> (final state, steps, rhs calls)
    runners = {}
    if limit_field is not None:
        hand = make_dop853(limit_field)
        runners["limit"] = lambda rt, f=hand: f(y0, p, T, rt, rt * 1e-3)
    lean = make_dop853(lean_field)
    runners["lean-dop853"] = lambda rt: lean(y0, p, T, rt, rt * 1e-3)

    def ours(gen):
        def run(rt):
            r = integrate(model.model, p, y0, [0.0, T], rtol=rt, atol=rt * 1e-3,
                          generated=gen)
            return r.y[-1], r.steps, r.rhs_calls
        return run

    runners["ours"] = ours(False)
    runners["ours-generated"] = ours(True)
    loops = generated_integrator(model.model, p)
    runners["gen-loops"] = kernel_runner(loops.rk_integrate, model.model, p, y0, T)
    compile_s = {}
    for name, run in runners.items():
        t0 = time.perf_counter()
        run(1e-6)
        compile_s[name] = time.perf_counter() - t0
    best = {name: [math.inf] * len(rtols) for name in runners}
    outs = {name: [None] * len(rtols) for name in runners}
    for i, rt in enumerate(rtols):
        for _ in range(repeats):
            for name, run in runners.items():       # interleaved: A B C A B C ...
                t0 = time.perf_counter()
                o = run(rt)
                best[name][i] = min(best[name][i], time.perf_counter() - t0)
                outs[name][i] = o
    res = {name: [(err(outs[name][i][0]), best[name][i]) for i in range(len(rtols))]
           for name in runners}
    work = {name: [(int(o[1]), int(o[2])) for o in outs[name]] for name in runners}

    import heyoka as hy

    v, f, _ = heyoka_system(model.model, p, fold=True)
    hruns = {}
    for tol in (1e-5, 1e-6, 1e-7, 1e-9, 1e-11):
        ta = hy.taylor_adaptive(list(zip(v, f, strict=True)), y0, tol=tol)

        def go(ta=ta):
            ta.time = 0.0
            ta.state[:] = y0
            steps = ta.propagate_until(T)[3]
            return ta.state.copy(), steps
        hruns[("heyoka-lean", tol)] = go
        if not quick:
            tay = Taylor(model.model, p, y0, tol=tol)
            hruns[("heyoka-gen", tol)] = lambda tay=tay: (tay.run(y0, [0.0, T])[0][-1], 0)
    hbest = dict.fromkeys(hruns, math.inf)
    hout = {}
    for _ in range(repeats):
        for key, go in hruns.items():
            t0 = time.perf_counter()
            hout[key] = go()
            hbest[key] = min(hbest[key], time.perf_counter() - t0)
    for (name, tol), w in hbest.items():
        res.setdefault(name, [])
        res[name].append((err(hout[(name, tol)][0]), w))
    # robust to the load: rhs calls at the matched error times the lowest cost per call
    # seen on the front (a run slowed by another job only raises its cost per call; the
    # calls are deterministic). Not for heyoka: its cost per step grows with the order,
    # which its tolerance sets.
    work_pts = {name: [(res[name][i][0], outs[name][i][2], best[name][i])
                       for i in range(len(rtols))] for name in runners}
    robust = {}
    for name, pts in work_pts.items():
        unit = min(w / max(1, u) for _, u, w in pts)
        robust[name] = {}
        for t in targets:
            u = at_error([(e, u) for e, u, _ in pts], t)
            robust[name][f"{t:.0e}"] = None if u is None else u * unit
    scal = ball_scalar(p) if limit_field is ball_field else None
    for name, fun in (("scipy-scalar", scal), ("scipy-numpy", None)):
        if (name == "scipy-scalar" and fun is None) or (name == "scipy-numpy" and quick):
            continue
        if fun is None:
            def fun(t, y):
                return ref_field(model.model, p, y)
        pts = []
        # wide enough to reach 1e-8 error on the ball (scipy's error at rtol 1e-11 is
        # ~2e-8); scipy clips rtol at 2.2e-14
        grid = [1e-7, 1e-9, 1e-11, 1e-12] if name == "scipy-scalar" else [1e-8, 1e-10, 1e-12]
        for rt in grid:
            w, sol = best_of(lambda rt=rt, fun=fun: solve_ivp(
                fun, (0.0, T), y0, method="DOP853", rtol=rt, atol=rt * 1e-3), 1)
            pts.append((err(sol.y[:, -1]), w))
        res[name] = pts
    table = {name: {f"{t:.0e}": at_error(pts, t) for t in targets} for name, pts in res.items()}
    breakdown = {name: [{"rtol": rt, "time_s": best[name][i], "steps": work[name][i][0],
                         "rhs_calls": work[name][i][1],
                         "ns_per_rhs": best[name][i] / max(1, work[name][i][1]) * 1e9}
                        for i, rt in enumerate(rtols)] for name in runners}
    return res, table, breakdown, compile_s, robust


@numba.njit(nogil=True)
def _field_loop(field, y, p, d, N):
    """N field calls on slightly moving states (the result feeds the next state, so the
    calls are not hoisted): the field's cost alone, ns per call."""
    acc = 0.0
    for _ in range(N):
        y[0] += 1e-13 * acc
        field(y, p, d)
        acc = d[0]
    return acc


def field_cost(case, params, y0, limit_field):
    model = build(case, params)
    p = np.array(model.p)
    gen_field = generated(model.model, p).field

    @numba.njit(inline="always")
    def lean_field(y, p, f):
        return gen_field(p, y, f)

    out = {}
    for name, f in (("hand", limit_field), ("generated", lean_field)):
        if f is None:
            continue
        y, d = np.array(y0, dtype=float), np.empty(len(y0))
        _field_loop(f, y, p, d, 10)
        w, _ = best_of(lambda f=f, y=y, d=d: _field_loop(f, y, p, d, 200_000), 5)
        out[name] = w / 200_000 * 1e9
    return out


# --- the limit: a scalar DOP853, its field inlined ----------------------------------------
def make_scalar_dop853(field, n, params=None):
    """The limit: DOP853 written for one state dimension n with the state, the
    stages and the error terms in scalar locals, the field a numba function of scalars
    returning the derivative as a tuple, inlined by LLVM. Written here, independently of
    the project's generators: scipy's coefficients (DC), Hairer's error norm, the plain
    controller (safety 0.9, factors in [0.2, 10], err^(-1/8)), Hairer's starting step, no
    dense output, no statuses (the final state at T only). params: for a field with the
    project's signature fs(slots..., y...) -> (status, dy...), the parameter slots it takes
    (read from p once); the limit drops the field's status (and LLVM the finite check that
    makes it), where the small kernel tests it after every call."""
    R = range(n)
    ys = [f"y{m}" for m in R]

    def lit(x):
        return repr(float(x))

    def comb(coef, names):
        t = [f"{lit(a)} * {nm}" for a, nm in zip(coef, names, strict=False) if a != 0.0]
        return " + ".join(t) if t else "0.0"

    if params is None:
        head = "    pv = p\n"
        call = "F(pv, {})"
    else:
        head = "".join(f"    q{i} = p[{s}]\n" for i, s in enumerate(params))
        call = "F(" + "".join(f"q{i}, " for i in range(len(params))) + "{})[1:]"
    src = ["def run(Y0, p, T, rtol, atol):", head.rstrip("\n")]
    src += [f"    y{m} = Y0[{m}]" for m in R]
    src.append(f"    {', '.join(f'k0_{m}' for m in R)} = " + call.format(", ".join(ys)))
    # Hairer's starting step (Solving ODEs I, II.4)
    src += ["    d0 = 0.0", "    d1 = 0.0"]
    for m in R:
        src += [f"    sc = atol + rtol * abs(y{m})", f"    d0 += (y{m} / sc) ** 2",
                f"    d1 += (k0_{m} / sc) ** 2"]
    src += [f"    d0 = math.sqrt(d0 / {n})", f"    d1 = math.sqrt(d1 / {n})",
            "    h0 = 1e-6 if (d0 < 1e-5 or d1 < 1e-5) else 0.01 * d0 / d1"]
    src += [f"    z{m} = y{m} + h0 * k0_{m}" for m in R]
    src.append(f"    {', '.join(f'f{m}' for m in R)} = "
               + call.format(", ".join(f"z{m}" for m in R)))
    src.append("    d2 = 0.0")
    for m in R:
        src += [f"    sc = atol + rtol * abs(y{m})", f"    d2 += ((f{m} - k0_{m}) / sc) ** 2"]
    src += [f"    d2 = math.sqrt(d2 / {n}) / h0",
            "    h1 = max(1e-6, h0 * 1e-3) if max(d1, d2) <= 1e-15 else "
            "(0.01 / max(d1, d2)) ** 0.125",
            "    h = min(100.0 * h0, h1, T)", "    t = 0.0", "    nfev = 2", "    steps = 0",
            "    while t < T:", "        if t + h > T:", "            h = T - t"]
    for i in range(1, 12):
        for m in R:
            ks = [f"k{j}_{m}" for j in range(i)]
            src.append(f"        z{m} = y{m} + h * ({comb(A[i, :i], ks)})")
        src.append(f"        {', '.join(f'k{i}_{m}' for m in R)} = "
                   + call.format(", ".join(f"z{m}" for m in R)))
    for m in R:
        src.append(f"        yn{m} = y{m} + h * ({comb(B, [f'k{j}_{m}' for j in range(12)])})")
    src.append(f"        {', '.join(f'k12_{m}' for m in R)} = "
               + call.format(", ".join(f"yn{m}" for m in R)))
    src += ["        nfev += 12", "        e5 = 0.0", "        e3 = 0.0"]
    for m in R:
        names = [f"k{j}_{m}" for j in range(13)]
        src += [f"        sc = atol + rtol * max(abs(y{m}), abs(yn{m}))",
                f"        a5 = {comb(E5, names)}", f"        a3 = {comb(E3, names)}",
                "        e5 += (a5 / sc) ** 2", "        e3 += (a3 / sc) ** 2"]
    src += ["        den = e5 + 0.01 * e3",
            f"        err = 0.0 if den == 0.0 else abs(h) * e5 / math.sqrt(den * {n})",
            "        if err <= 1.0:", "            t += h", "            steps += 1"]
    for m in R:
        src += [f"            y{m} = yn{m}", f"            k0_{m} = k12_{m}"]
    src += ["            fac = 10.0 if err == 0.0 else min(10.0, 0.9 * err ** -0.125)",
            "        else:", "            fac = max(0.2, 0.9 * err ** -0.125)",
            "        h *= fac",
            f"    return np.array([{', '.join(ys)}]), steps, nfev"]
    ns = {"F": field, "np": np, "math": math}
    exec("\n".join(src), ns)
    return numba.njit(nogil=True)(ns["run"])


def generated_scalar_field(model, p):
    """The project's generated field on scalars (small.py's `fs`, forceinline), for the
    cases without a hand-written field, and the parameter slots it takes."""
    from solvers.kernels.generate import SLOT_NAMES, field_body

    params = [SLOT_NAMES.index(x.name) for x in field_body(model, p)[0]]
    return small_module(model, p, "dop853").fs, params


# --- many starts ------------------------------------------------------------------------------
HAND = {"plane/chaplygin-ball": (ball_s, 6), "plane/round-disk": (disk_s, 6),
        "sphere/flat-base": (flat_s, 5)}


def _drawn(wp, rng, k=20):
    """A work-precision case's parameters, its k starts drawn from rng as the many-start
    mode draws them, its model and p."""
    _, prm, model = work_precision_case(wp.id)
    return prm, random_starts(wp.id, prm, k, rng), model, np.asarray(model.p, dtype=float)


def _gen_field(model, p):
    """make_scalar_dop853's arguments for the project's generated scalar field."""
    fs, slots = generated_scalar_field(model, p)
    return fs, L.STATE_DIM[model], slots


def scalar_limit(case_id, model, p):
    """The limit of a case and which field it runs: the scalar DOP853 on the case's
    hand-written field where there is one ("hand"), else on the project's generated scalar
    field ("generated")."""
    n = L.STATE_DIM[model.model]
    if case_id in HAND:
        return make_scalar_dop853(HAND[case_id][0], n), "hand"
    fs, slots = generated_scalar_field(model.model, p)
    return make_scalar_dop853(fs, n, slots), "generated"


def work_precision_case(case_id):
    """A case of bench/work_precision.py: (its entry in CASES, its parameters, the model)."""
    sys.path.insert(0, str(Path(__file__).parent))
    from work_precision import CASES

    wp = next(w for w in CASES if w.id == case_id)
    prm = {**registry()[wp.id].example, **wp.overrides}
    return wp, prm, build(wp.id, prm)


def random_starts(case_id, params, k, rng):
    """k starts of the case: M in a uniformly random direction with |M| spread
    log-uniformly over two decades around the example's |M| (x 0.1 ... x 10); gamma a
    uniformly random unit vector (the disk: its edge at least 0.3 from flat; gamma's
    component along the axis kept for the others); the flat base: (r1, r2) the example's
    times uniform factors in [-1.5, 1.5]."""
    from solvers.models.cases import initial_state

    c = registry()[case_id]
    model = build(case_id, params)
    y_ex = np.asarray(initial_state(model, c.state), dtype=float)
    m_ex = float(np.linalg.norm(y_ex[:3])) or 1.0
    out = []
    while len(out) < k:
        d = rng.normal(size=3)
        M = d / np.linalg.norm(d) * m_ex * 10.0 ** rng.uniform(-1.0, 1.0)
        if model.model == 3:   # flat base: state (M, r1, r2)
            r = y_ex[3:] * rng.uniform(-1.5, 1.5, size=2)
            out.append(np.concatenate([M, r]))
            continue
        g = rng.normal(size=3)
        g /= np.linalg.norm(g)
        if case_id.endswith("round-disk") and math.hypot(g[0], g[1]) < 0.3:
            continue
        out.append(np.concatenate([M, g]))
    return out


def matched(front_pts, target):
    """(time at the target error, log-log interpolated on the front), None outside."""
    return at_error(front_pts, target)


def many_starts(quick=False, only=None, repeats=3, batch_ms=None, t_end=None):
    """For each of the six work-precision cases, random starts (20; --quick 5 over at most
    T = 200): the time at matched final-state errors 1e-6 and 1e-10 of ours (integrate(),
    the default route: the small kernel), the limit (the scalar DOP853 above; where its
    field is hand-written, also the same DOP853 on the generated field, limit-gen) and
    heyoka on the lean equations; median and worst ratio over the starts. The table is written after
    every case (a partial run keeps what it measured). only: case ids to run. repeats: each
    run's time is the best of this many.
    batch_ms: each timed measurement is a batch of back-to-back calls of the same run,
    as many as fill batch_ms milliseconds (counted once per run from one timed call, at
    least one call), its time divided by their number (timeit's way: a run of ~50 us alone
    is at the mercy of the machine's hiccups, which a best of 3 does not filter: start 8 of
    the plane ball measured 41 us at rtol 1e-4 and 72 us at the next rtol with about the
    same steps); None: one call per measurement. t_end: every case run to this T
    instead of its own (the disk's DOP853 fronts at T = 1000 end above 1e-10 in double, so
    that error is matched at a shorter T). The table's head states the options."""
    sys.path.insert(0, str(Path(__file__).parent))
    from work_precision import CASES

    n_starts = 5 if quick else 20
    targets = (1e-6, 1e-10)
    rtols = [10.0 ** (-k / 2) for k in range(8, 29)]      # 1e-4 ... 1e-14, half decades
    htols = [10.0 ** -k for k in range(4, 16)]
    rng = np.random.default_rng(19)
    import heyoka as hy

    load0 = os.getloadavg()
    batch = ("" if batch_ms is None else
             f" Each measurement is a batch of back-to-back calls of the same run filling "
             f"{batch_ms:g} ms (at least one call), timed as a whole and divided by the "
             "number of calls; the number is fixed per run and competitor from one timed "
             "call before the repeats.")
    lines = [f"bench/limit.py{' --quick' if quick else ''}: many starts. Per case {n_starts} "
             "random starts, |M| log-uniform over two decades (0.1x ... 10x the example's), "
             "gamma uniform on the sphere; final-state error (max-norm / max(1, |y|)) at T "
             "against heyoka long double tol 1e-18; time at matched error 1e-6 and 1e-10 "
             "interpolated log-log on each front (rtol = atol 1e-4 ... 1e-14 every half "
             f"decade; heyoka tol 1e-4 ... 1e-15), best of {repeats} interleaved, each run timed "
             f"on the wall clock and on the process's CPU time.{batch}",
             "  ours  = integrate() by default (dop853, the small kernel of the structure)",
             "  kernel = that small kernel called directly, its option arrays built before "
             "the timed call (ours without integrate()'s Python entry: the same steps and "
             "bits)",
             "  limit = a scalar DOP853 written in bench/limit.py (state and stages in "
             "locals), its field inlined: written by hand for the ball, the disk and the "
             "flat base, the project's generated scalar field for the others",
             "  heyoka = heyoka's Taylor integrator on the lean generated equations",
             "  limit-gen = where the limit's field is hand-written, the same scalar DOP853 "
             "on the project's generated field (which agrees with the hand-written one on "
             "|gamma| = 1 and differs off it: bench/limit.py --work)",
             f"load average at the start: {load0[0]:.2f} {load0[1]:.2f} {load0[2]:.2f} "
             f"({os.cpu_count()} cores)"]
    out = {"quick": quick, "starts": n_starts, "repeats": repeats, "batch_ms": batch_ms,
           "t_end": t_end,
           "load_start": load0,
           "cases": {},
           "date": time.strftime("%Y-%m-%d %H:%M UTC", time.gmtime())}
    summary = []
    for wp in CASES:
        c = registry()[wp.id]
        prm = {**c.example, **wp.overrides}
        if only and wp.id not in only:
            # the same starts as a whole run: draw this case's starts all the same
            random_starts(wp.id, prm, n_starts, rng)
            continue
        model = build(wp.id, prm)
        p = np.asarray(model.p, dtype=float)
        T = t_end if t_end is not None else min(wp.t_end, 200.0) if quick else wp.t_end
        limit, limit_kind = scalar_limit(wp.id, model, p)
        # where the limit's field is hand-written, the same DOP853 on the project's
        # generated field too ("limit-gen"): the field's form off |gamma| = 1 apart
        limit_gen = (make_scalar_dop853(*_gen_field(model.model, p)) if limit_kind == "hand"
                     else None)
        # the small kernel as integrate() calls it: a writable p (a read-only one is another
        # numba specialization), the option arrays integrate() memoizes for its default
        # step control
        p_w = np.array(p)
        small_run = small_module(model.model, p_w, "dop853").run
        control = integrate.__kwdefaults__["control"]
        small_opts = {rt: (_plain_fopt(rt, control), _plain_atol(rt, L.STATE_DIM[model.model]))
                      for rt in rtols}
        t_span = np.array([0.0, T])
        v, f, _ = heyoka_system(model.model, p, fold=True)
        sys_h = list(zip(v, f, strict=True))
        # one compiled Taylor integrator per tolerance, reused for every start
        y_any = random_starts(wp.id, prm, 1, np.random.default_rng(0))[0]
        tas = {tol: hy.taylor_adaptive(sys_h, y_any, tol=tol) for tol in htols}
        rows = []
        for y0 in random_starts(wp.id, prm, n_starts, rng):
            ref = Taylor(model.model, p, y0, tol=1e-18, fp="longdouble").run(y0, [0.0, T])[1][-1]
            ref = np.asarray(ref, dtype=float)

            def err(y, ref=ref):
                return float(np.max(np.abs(np.asarray(y, dtype=float) - ref))
                             / max(1.0, float(np.max(np.abs(ref)))))

            def ours(rt, y0=y0, model=model, p=p, T=T):
                r = integrate(model.model, p, y0, [0.0, T], rtol=rt, atol=rt)
                return r.y[-1], r.success

            def lim(rt, y0=y0, limit=limit, p=p, T=T):
                y, _, _ = limit(y0, p, T, rt, rt)
                return y, True

            def kern(rt, y0=y0, run=small_run, opts=small_opts, t_out=t_span, p_w=p_w):
                fopt, atol_v = opts[rt]
                n = y0.size
                Y, y_stop, stats = np.empty((2, n)), np.empty(n), np.zeros(5, dtype=np.int64)
                status, _ = run(p_w, y0, t_out, 10_000_000, False, fopt, atol_v, Y, y_stop,
                                stats)
                return Y[1], status == L.OK

            def hey(tol, y0=y0, tas=tas, T=T):
                ta = tas[tol]
                ta.time = 0.0
                ta.state[:] = y0
                o = ta.propagate_until(T)
                return ta.state.copy(), str(o[0]).endswith("time_limit")

            comp = {"ours": (ours, rtols), "limit": (lim, rtols), "heyoka": (hey, htols),
                    "kernel": (kern, rtols)}
            if limit_gen is not None:
                comp["limit-gen"] = (partial(lim, limit=limit_gen), rtols)
            for fn, grid in comp.values():     # compile / warm
                fn(grid[0])
            # two clocks per run, the same for every competitor: the wall clock (as timed)
            # and the process's CPU time, which a run preempted by the machine's other jobs
            # does not count (at load 13 on 2 cores a best of 3 still caught 10x outliers
            # on the wall clock); the CPU clock includes ~1 us of its own reading
            # calls per measurement: 1, or (--batch) as many as fill batch_ms
            n_calls = {k: [1] * len(g) for k, (_, g) in comp.items()}
            if batch_ms is not None:
                for k, (fn, grid) in comp.items():
                    for i, x in enumerate(grid):
                        t0 = time.perf_counter()
                        fn(x)
                        w = time.perf_counter() - t0
                        n_calls[k][i] = max(1, math.ceil(batch_ms * 1e-3 / max(w, 1e-7)))
            best = {k: [math.inf] * len(g) for k, (_, g) in comp.items()}
            cpu = {k: [math.inf] * len(g) for k, (_, g) in comp.items()}
            errs = {k: [None] * len(g) for k, (_, g) in comp.items()}
            for _ in range(repeats):
                for i in range(max(len(g) for _, g in comp.values())):
                    for k, (fn, grid) in comp.items():    # interleaved
                        if i >= len(grid):
                            continue
                        n = n_calls[k][i]
                        c0 = time.process_time()
                        t0 = time.perf_counter()
                        for _ in range(n):
                            y, ok = fn(grid[i])
                        w = (time.perf_counter() - t0) / n
                        c = (time.process_time() - c0) / n
                        best[k][i] = min(best[k][i], w)
                        cpu[k][i] = min(cpu[k][i], c)
                        errs[k][i] = err(y) if ok else math.nan
            row = {"y0": [float(x) for x in y0], "M": float(np.linalg.norm(y0[:3]))}
            for k in comp:
                for suffix, times in (("", best), ("_cpu", cpu)):
                    front_k = list(zip(errs[k], times[k], strict=True))
                    row[k + suffix] = {f"{t:.0e}": matched(front_k, t) for t in targets}
                    row[k + suffix + "_front"] = front_k
            rows.append(row)
        res = {}
        for t in targets:
            key = f"{t:.0e}"
            ratios = {}
            for suffix in ("", "_cpu"):
                for mine, other in (("ours", "limit"), ("ours", "heyoka"),
                                    ("kernel", "limit"), ("ours", "limit-gen")):
                    a, b = mine + suffix, other + suffix
                    ratios[mine + other + suffix] = [r[a][key] / r[b][key] for r in rows
                                                     if r[a][key] and r[b][key]] \
                        if b in rows[0] else None
            res[key] = {"vs_limit": ratios["ourslimit"], "vs_heyoka": ratios["oursheyoka"],
                        "vs_limit_cpu": ratios["ourslimit_cpu"],
                        "vs_heyoka_cpu": ratios["oursheyoka_cpu"],
                        "kernel_vs_limit": ratios["kernellimit"],
                        "kernel_vs_limit_cpu": ratios["kernellimit_cpu"],
                        "vs_limit_gen": ratios["ourslimit-gen"],
                        "vs_limit_gen_cpu": ratios["ourslimit-gen_cpu"]}
        out["cases"][wp.id] = {"T": T, "params": prm, "limit_field": limit_kind,
                               "rows": rows, "ratios": res, "measured": out["date"]}
        summary += _summary_of(wp.id, out["cases"][wp.id])
        print(f"{wp.id} done (load {os.getloadavg()[0]:.2f})", flush=True)
        _write_starts(quick, lines, summary, out)


def _summary_of(cid, case) -> list:
    """The table's rows of a case (one per matched error) from its stored results."""
    return [(cid, key, case["limit_field"],
             {"limit": r["vs_limit"], "heyoka": r["vs_heyoka"],
              "limit_cpu": r["vs_limit_cpu"], "heyoka_cpu": r["vs_heyoka_cpu"],
              # the kernel alone (rows kept from a run before this column have none)
              "kernel": r.get("kernel_vs_limit"), "kernel_cpu": r.get("kernel_vs_limit_cpu"),
              "limit-gen": r.get("vs_limit_gen"), "limit-gen_cpu": r.get("vs_limit_gen_cpu")},
             len(case["rows"])) for key, r in case["ratios"].items()]


def _write_starts(quick, head, summary, out):
    lines = list(head)
    lines.append("")
    def fmt(v, f):
        return f"{f(v):.2f}" if v else "-"

    for title, suffix in (("wall clock (as timed)", ""),
                          ("CPU time of the process (preemption by other jobs not counted)",
                           "_cpu")):
        lines.append(f"{title}:")
        lines.append(f"{'case':28s} {'error':6s} {'limit':9s} {'ours/limit median':>17s} "
                     f"{'worst':>6s} {'ours/heyoka median':>18s} {'worst':>6s}  "
                     f"{'kernel/limit median':>19s} {'worst':>6s}  "
                     f"{'ours/limit-gen median':>21s} {'worst':>6s}  starts matched")
        for cid, key, kind, ratios, n in summary:
            rl, rh = ratios["limit" + suffix], ratios["heyoka" + suffix]
            rk_ = ratios["kernel" + suffix]
            rg = ratios.get("limit-gen" + suffix)
            lines.append(f"{cid:28s} {key:6s} {kind:9s} {fmt(rl, np.median):>17s} "
                         f"{fmt(rl, max):>6s} {fmt(rh, np.median):>18s} {fmt(rh, max):>6s}  "
                         f"{fmt(rk_, np.median):>19s} {fmt(rk_, max):>6s}  "
                         f"{fmt(rg, np.median):>21s} {fmt(rg, max):>6s}  "
                         f"{len(rl)}/{n}, {len(rh)}/{n}")
        lines.append("")
    load1 = os.getloadavg()
    ts = ", ".join(f"{k} {v['T']:g}" for k, v in out["cases"].items())
    dates = sorted({v.get("measured", "?") for v in out["cases"].values()})
    if len(dates) > 1:   # a --cases run: which rows were measured when
        for d in dates:
            lines.append(f"measured {d}: " + ", ".join(
                k for k, v in out["cases"].items() if v.get("measured", "?") == d))
    lines.append(f"A start counts where both fronts reach the error (else it is outside a "
                 f"front and left out). T: {ts}"
                 f"\nload average at the end: {load1[0]:.2f} {load1[1]:.2f} {load1[2]:.2f}")
    out["load_end"] = load1
    text = "\n".join(lines) + "\n"
    print(text, flush=True)
    OUT.mkdir(exist_ok=True)
    (OUT / ("limit_starts_quick.txt" if quick else "limit_starts.txt")).write_text(text)


# --- the work at matched error, without a clock -------------------------------------------
def work_split(targets=(1e-6, 1e-10)):
    """Where the many-start mode's worst starts come from, with no clock: on the same 20
    starts per case (the same draws), each competitor's front in right-hand-side calls (a
    count, which the machine's load does not change) and ours / the limit in calls at
    matched error, median and worst over the starts. The competitors:
      ours      integrate() by default (the small kernel; Hairer's DOPRI5 PI controller,
                beta = 0.04, StepControl's default)
      ours-I    integrate() with beta = 0: the limit's controller (Hairer's DOP853 and
                scipy's: fac = 0.9 err^(-1/8))
      limit     the many-start mode's limit (a hand-written field for the ball, the disk and
                the flat base; the project's generated field for the others)
      limit-gen for the three hand-written cases, the same scalar DOP853 on the project's
                generated field, which agrees with the hand-written one on the invariant
                manifold (|gamma| = 1) and differs off it
    ours-I against limit-gen is one algorithm against itself on one field: the calls
    differ only in the first step and the landing on T. Written to
    bench/results/limit_work.txt."""
    from solvers.integrate.integrator import StepControl

    sys.path.insert(0, str(Path(__file__).parent))
    from work_precision import CASES

    rng = np.random.default_rng(19)
    rtols = [10.0 ** (-k / 2) for k in range(8, 29)]
    pairs = (("ours", "limit"), ("ours-I", "limit"), ("ours", "limit-gen"),
             ("ours-I", "limit-gen"), ("limit", "limit-gen"))
    lines = ["bench/limit.py --work: right-hand-side calls at matched final-state error "
             "(log-log on each front, rtol = atol 1e-4 ... 1e-14 every half decade), the "
             "many-start mode's 20 starts per case and its error measure; no clock. "
             "ours-I: integrate() with beta = 0 (the limit's controller); limit-gen: the "
             "limit's DOP853 on the project's generated field (hand-written cases only).",
             "",
             f"{'case':22s} {'error':6s} " + " ".join(f"{a + '/' + b:>17s}" for a, b in pairs)
             + "   (median worst, starts matched)"]
    out = {"targets": targets, "cases": {}}
    for wp in CASES:
        prm, starts, model, p = _drawn(wp, rng)
        limit, kind = scalar_limit(wp.id, model, p)
        comp = {"limit": limit}
        if kind == "hand":
            comp["limit-gen"] = make_scalar_dop853(*_gen_field(model.model, p))
        rows = []
        for y0 in starts:
            ref = np.asarray(Taylor(model.model, p, y0, tol=1e-18, fp="longdouble").run(
                y0, [0.0, wp.t_end])[1][-1], dtype=float)
            scale = max(1.0, float(np.max(np.abs(ref))))
            fronts = {k: [] for k in ("ours", "ours-I", *comp)}
            for rt in rtols:
                for k, ctl in (("ours", StepControl()), ("ours-I", StepControl(beta=0.0))):
                    r = integrate(model.model, p, y0, [0.0, wp.t_end], rtol=rt, atol=rt,
                                  control=ctl)
                    e = float(np.max(np.abs(r.y[-1] - ref))) / scale if r.success \
                        else math.nan
                    fronts[k].append((e, r.rhs_calls))
                for k, fn in comp.items():
                    y, _, nfev = fn(y0, p, wp.t_end, rt, rt)
                    fronts[k].append((float(np.max(np.abs(y - ref))) / scale, int(nfev)))
            rows.append({"y0": [float(v) for v in y0], "fronts": fronts})
        ratios = {}
        for t in targets:
            key = f"{t:.0e}"
            for a, b in pairs:
                if b not in comp:      # limit-gen: hand-written cases only
                    continue
                at = [(at_error(r["fronts"][a], t), at_error(r["fronts"][b], t))
                      for r in rows]
                ratios[f"{a}/{b} {key}"] = [x / y for x, y in at if x and y]
            cells = []
            for a, b in pairs:
                v = ratios.get(f"{a}/{b} {key}")
                cells.append(f"{np.median(v):.3f} {max(v):.3f} {len(v):2d}" if v else
                             ("-" if v is None else "none matched"))
            lines.append(f"{wp.id:22s} {key:6s} " + " ".join(f"{x:>17s}" for x in cells))
        out["cases"][wp.id] = {"T": wp.t_end, "params": prm, "limit_field": kind,
                               "rows": rows, "ratios": ratios}
        print("\n".join(lines[-len(targets):]), flush=True)
    text = "\n".join(lines) + "\n"
    OUT.mkdir(exist_ok=True)
    (OUT / "limit_work.txt").write_text(text)
    print(text)


# --- where the gap lies -------------------------------------------------------------------
def gap(case_id="plane/chaplygin-ball", n_starts=5, T=200.0, repeats=7):
    """Where ours loses against the limit on one case, measured part by part, same process,
    interleaved, best of `repeats`, on the many-start mode's first starts (same seed):
      (a) the work at a given tolerance: accepted and rejected steps and rhs calls, and the
          final-state error, of the limit (hand field where there is one), the limit on
          the generated field (small.py's `fs`), and ours (the small kernel);
      (b) the cost per rhs call of each, the small kernel called directly (its packed
          arrays reused: no Python entry);
      (c) integrate()'s entry (validation, allocation, dispatch, the result): the time of
          integrate() minus the direct call of the same kernel, per run and as a fraction
          of the run at T;
      (d) the entry in a tight loop (a one-step run, caches warm): its floor."""
    from solvers.integrate.integrator import StepControl, small_module
    from solvers.kernels import rk

    wp, prm, model = work_precision_case(case_id)
    # a writable copy, as integrate() passes it: a read-only p is another numba
    # specialization of the kernel (other machine code, a few % apart on long runs)
    p = np.array(model.p, dtype=float)
    n = L.STATE_DIM[model.model]
    lims = {"limit-gen": make_scalar_dop853(*_gen_field(model.model, p))}
    if wp.id in HAND:
        lims["limit-hand"] = make_scalar_dop853(HAND[wp.id][0], n)
    run = small_module(model.model, p, "dop853").run
    t_out = np.array([0.0, T])
    sc = StepControl()
    Y, ys, st = np.empty((2, n)), np.empty(n), np.zeros(5, dtype=np.int64)

    def packed(rt):         # rk.py's option vectors, built outside the timed call
        fopt = np.zeros(7)
        fopt[[rk.F_RTOL, rk.F_H, rk.F_HMAX, rk.F_SAFETY, rk.F_FACMIN, rk.F_FACMAX,
              rk.F_BETA]] = (rt, sc.h0, sc.h_max, sc.safety, sc.fac_min, sc.fac_max, sc.beta)
        return fopt, np.full(n, rt)

    def direct(y0, fopt, atol):
        run(p, y0, t_out, 10**7, False, fopt, atol, Y, ys, st)
        return Y[1], st[rk.S_ACCEPTED], st[rk.S_REJECTED], st[rk.S_RHS]

    load0 = os.getloadavg()
    lines = [f"bench/limit.py --gap: {wp.id}, T = {T:g}, the first {n_starts} starts of the "
             f"many-start mode (seed 19), rtol = atol; best of {repeats}, interleaved; "
             f"load average at the start: {load0[0]:.2f} {load0[1]:.2f} {load0[2]:.2f}",
             "  per rtol: steps accepted+rejected, rhs calls, final-state error (relative "
             "max-norm), time, ns per rhs call",
             "  ours-direct = the small kernel called directly; ours = integrate(); entry = "
             "ours - ours-direct; (cpu ...): the same on the process's CPU time"]
    out = {"case": wp.id, "T": T, "load_start": load0, "starts": []}
    starts = random_starts(wp.id, prm, n_starts, np.random.default_rng(19))
    for y0 in starts:
        y0 = np.asarray(y0, dtype=float)
        ref = Taylor(model.model, p, y0, tol=1e-18, fp="longdouble").run(y0, [0.0, T])[1][-1]
        ref = np.asarray(ref, dtype=float)

        def err(y, ref=ref):
            return float(np.max(np.abs(np.asarray(y) - ref)) / max(1.0, np.max(np.abs(ref))))

        lines.append(f"\nstart |M| = {np.linalg.norm(y0[:3]):.3g}, y0 = "
                     f"{np.round(y0, 4).tolist()}")
        rows = []
        for rt in (1e-6, 1e-8, 1e-10, 1e-12):
            fns = {k: (lambda f=f, rt=rt, y0=y0: f(y0, p, T, rt, rt)) for k, f in lims.items()}
            opts = packed(rt)
            fns["ours-direct"] = lambda o=opts, y0=y0: direct(y0, *o)
            fns["ours"] = lambda rt=rt, y0=y0: integrate(model.model, p, y0, [0.0, T],
                                                         rtol=rt, atol=rt)
            for f in fns.values():
                f()
            best, cpu, res = dict.fromkeys(fns, math.inf), dict.fromkeys(fns, math.inf), {}
            for _ in range(repeats):
                for k, f in fns.items():
                    c0 = time.process_time()
                    t0 = time.perf_counter()
                    res[k] = f()
                    best[k] = min(best[k], time.perf_counter() - t0)
                    cpu[k] = min(cpu[k], time.process_time() - c0)
            row = {"rtol": rt}
            for k, o in res.items():
                if k == "ours":
                    acc, rej, calls, y = o.steps, o.rejected, o.rhs_calls, o.y[-1]
                elif k == "ours-direct":
                    y, acc, rej, calls = o[0].copy(), int(o[1]), int(o[2]), int(o[3])
                else:       # the limit counts 12 calls per attempt: rejected = the rest
                    y, acc, calls = o
                    rej = (calls - 2 - 12 * acc) // 12
                row[k] = {"accepted": acc, "rejected": rej, "rhs_calls": calls,
                          "error": err(y), "time_s": best[k], "cpu_s": cpu[k],
                          "ns_per_rhs": best[k] / calls * 1e9,
                          "cpu_ns_per_rhs": cpu[k] / calls * 1e9}
            row["entry_s"] = best["ours"] - best["ours-direct"]
            row["entry_cpu_s"] = cpu["ours"] - cpu["ours-direct"]
            rows.append(row)
            lines.append(f"  rtol {rt:.0e}: " + " | ".join(
                f"{k} {v['accepted']}+{v['rejected']} st {v['rhs_calls']} calls "
                f"err {v['error']:.1e} {v['time_s'] * 1e3:.3f} ms {v['ns_per_rhs']:.1f} ns "
                f"(cpu {v['cpu_ns_per_rhs']:.1f} ns)"
                for k, v in row.items() if isinstance(v, dict)))
            lines.append(f"      entry {row['entry_s'] * 1e6:.1f} us = "
                         f"{row['entry_s'] / best['ours'] * 100:.0f}% of ours (cpu "
                         f"{row['entry_cpu_s'] * 1e6:.1f} us = "
                         f"{row['entry_cpu_s'] / cpu['ours'] * 100:.0f}%); ours/limit "
                         + ", ".join(f"{k} {best['ours'] / best[k]:.2f} (cpu "
                                     f"{cpu['ours'] / cpu[k]:.2f})" for k in lims))
        out["starts"].append({"y0": y0.tolist(), "rows": rows})
    # (d) the entry in a tight loop: a run of one step (t = 0 ... 1e-3 from the first
    # start, rtol 1e-4), integrate() against the direct call, each timed by timeit over
    # 20000 calls, best of 5 rounds of 5 (caches warm: the entry's floor)
    y0 = np.asarray(starts[0], dtype=float)
    t_short = np.array([0.0, 1e-3])
    opts = packed(1e-4)

    def one_direct(y0=y0, fopt=opts[0], atol=opts[1]):
        run(p, y0, t_short, 10**7, False, fopt, atol, np.empty((2, n)), np.empty(n),
            np.zeros(5, dtype=np.int64))

    def one_ours(y0=y0):
        integrate(model.model, p, y0, [0.0, 1e-3], rtol=1e-4, atol=1e-4)

    tight = {}
    for name, fn in (("ours", one_ours), ("direct", one_direct)):
        fn()
        tight[name] = min(min(timeit.repeat(fn, number=20000, repeat=5)) / 20000
                          for _ in range(5))
    out["tight_loop"] = {"ours_s": tight["ours"], "direct_s": tight["direct"],
                         "entry_s": tight["ours"] - tight["direct"],
                         "steps": integrate(model.model, p, y0, [0.0, 1e-3], rtol=1e-4,
                                            atol=1e-4).steps}
    lines.append(f"\nentry in a tight loop (a one-step run, t = 0 ... 1e-3, timeit, best "
                 f"of 25 x 20000 calls): integrate() {tight['ours'] * 1e6:.2f} us, the "
                 f"kernel called directly (its three output arrays allocated) "
                 f"{tight['direct'] * 1e6:.2f} us: entry "
                 f"{(tight['ours'] - tight['direct']) * 1e6:.2f} us")
    load1 = os.getloadavg()
    lines.append(f"\nload average at the end: {load1[0]:.2f} {load1[1]:.2f} {load1[2]:.2f}")
    out["load_end"] = load1
    text = "\n".join(lines) + "\n"
    print(text, flush=True)
    OUT.mkdir(exist_ok=True)
    (OUT / "limit_gap.txt").write_text(text)



# --- the plane ball's field off |gamma| = 1 ------------------------------------------------------
EXT_CASE = "plane/chaplygin-ball"
EXT_BODIES = ((1.0, 2.0, 3.0), (0.01, 0.02, 0.025), (0.1, 0.2, 0.25), (1.0, 1.2, 1.5),
              (10.0, 20.0, 25.0))      # I1, I2, I3 with m = c = 1 (the first: the example)


@numba.njit(inline="always")
def phys_s(p, M0, M1, M2, g0, g1, g2):
    """A ball of radius c |gamma|: I_Q = I + m c^2 (|gamma|^2 E - gamma gamma^T), r = c
    gamma: the hand-written field (ball_s) with |r|^2 = c^2 |gamma|^2 in place of c^2."""
    mc2 = p[3] * p[16] * p[16]
    return ball_of_diagonal(p, M0, M1, M2, g0, g1, g2, mc2 * (g1 * g1 + g2 * g2),
                            mc2 * (g0 * g0 + g2 * g2), mc2 * (g0 * g0 + g1 * g1))


def extension(n_starts=12, T=1000.0, targets=(1e-6, 1e-10)):
    """Which extension of the plane Chaplygin ball's field off |gamma| = 1 integrates with
    the smaller error. The equations hold on |gamma| = 1; an integrator's stages leave it,
    so every field is some extension of them, and the extensions agree on the manifold and
    differ off it. Three, each in the limit's scalar DOP853 (the same integrator, the same
    controller):
      hand  the limit's hand-written field: r = c gamma, I_Q = I + m c^2 (E - gamma
            gamma^T) (|r|^2 taken as c^2), dr = c dgamma;
      gen   the project's generated field (from the support function h = c |gamma|): r = c
            gamma / |gamma|, I_Q = I + m (|r|^2 E - r r^T);
      phys  a ball of radius c |gamma| (phys_s): r = c gamma, I_Q = I + m (|r|^2 E - r r^T).
    Per body (EXT_BODIES), random starts (gamma uniform on the sphere, |M| = (mean I + m
    c^2) * 0.25 * 10^U(-1, 1)), rtol = atol from 1e-5 to 1e-14 every half decade; the
    final-state error (max-norm / max(1, |y|)) against heyoka's Taylor integrator in long
    double (tol 1e-18; every extension's exact flow is the same from a start on the
    manifold). Reported: the right-hand-side calls at matched errors (log-log interpolation
    on each front) of gen and phys over hand, median and range over the starts: no clock,
    so the figures do not depend on the machine's load. -> bench/results/limit_extension.txt"""
    from solvers.integrate.taylor import Taylor

    c = registry()[EXT_CASE]
    rng = np.random.default_rng(23)
    rtols = [10.0 ** (-k / 2) for k in range(10, 29)]
    hand = make_scalar_dop853(HAND[EXT_CASE][0], 6)
    phys = make_scalar_dop853(phys_s, 6)
    load0 = os.getloadavg()
    lines = [f"bench/limit.py --extension: {EXT_CASE}, three extensions of its field off "
             "|gamma| = 1 in the limit's scalar DOP853 (extension()'s doc); calls at matched "
             f"error over hand's, median [min, max] over {n_starts} starts per body, T = "
             f"{T:g}; load average at the start: {load0[0]:.2f} {load0[1]:.2f} "
             f"{load0[2]:.2f} (calls do not depend on it)"]
    for I in EXT_BODIES:
        prm = {**c.example, "I1": I[0], "I2": I[1], "I3": I[2]}
        model = build(EXT_CASE, prm)
        p = np.asarray(model.p, dtype=float)
        gen = make_scalar_dop853(*_gen_field(model.model, p))
        scale = (sum(I) / 3.0 + float(prm["m"]) * float(p[16]) ** 2) * 0.25
        ratios = {k: {t: [] for t in targets} for k in ("gen", "phys")}
        err_ratio = {k: [] for k in ("gen", "phys")}
        for _ in range(n_starts):
            d, g = rng.normal(size=3), rng.normal(size=3)
            y0 = np.concatenate([d / np.linalg.norm(d) * scale * 10.0 ** rng.uniform(-1, 1),
                                 g / np.linalg.norm(g)])
            ref = np.asarray(Taylor(model.model, p, y0, tol=1e-18, fp="longdouble")
                             .run(y0, [0.0, T])[1][-1], dtype=float)
            fronts = {}
            for k, f in (("hand", hand), ("gen", gen), ("phys", phys)):
                pts = []
                for rt in rtols:
                    y, _, calls = f(y0, p, T, rt, rt)
                    pts.append((float(np.max(np.abs(y - ref)) / max(1.0, np.max(np.abs(ref)))),
                                float(calls)))
                fronts[k] = pts
            for k in ("gen", "phys"):
                err_ratio[k] += [a[0] / b[0] for a, b in zip(fronts[k], fronts["hand"],
                                                              strict=True) if b[0] > 0]
                for t in targets:
                    a, b = at_error(fronts[k], t), at_error(fronts["hand"], t)
                    if a and b:
                        ratios[k][t].append(a / b)
        parts = []
        for k in ("gen", "phys"):
            for t in targets:
                v = ratios[k][t]
                parts.append(f"{k} {t:.0e}: " + (f"{np.median(v):.3f} [{min(v):.3f}, "
                                                 f"{max(v):.3f}] ({len(v)} matched)"
                                                 if v else "none matched"))
            parts.append(f"{k} error / hand's at the same rtol: median "
                         f"{np.median(err_ratio[k]):.2f}")
        lines.append(f"I = {I}: " + "; ".join(parts))
        print(lines[-1], flush=True)
    load1 = os.getloadavg()
    lines.append(f"load average at the end: {load1[0]:.2f} {load1[1]:.2f} {load1[2]:.2f}")
    OUT.mkdir(exist_ok=True)
    (OUT / "limit_extension.txt").write_text("\n".join(lines) + "\n")


def main():
    if "--help" in sys.argv or "-h" in sys.argv:
        print(__doc__)
        return
    quick = "--quick" in sys.argv
    if "--work" in sys.argv:
        work_split()
        return
    if "--extension" in sys.argv:
        extension()
        return
    if "--gap" in sys.argv:
        gap(sys.argv[sys.argv.index("--case") + 1] if "--case" in sys.argv
            else "plane/chaplygin-ball")
        return
    if "--fronts" not in sys.argv:
        def opt(flag, kind, default=None):     # `flag VALUE` on the command line
            return kind(sys.argv[sys.argv.index(flag) + 1]) if flag in sys.argv else default

        many_starts(quick, opt("--cases", lambda v: v.split(",")), opt("--repeats", int, 3),
                    opt("--batch", float), opt("--t-end", float))
        return
    cases = [
        ("plane/chaplygin-ball", {"I1": 1.0, "I2": 2.0, "I3": 3.0, "m": 1.0, "R": 1.0},
         [1.2, -0.7, 1.6, *(np.array([0.3, -0.5, 0.8]) / np.linalg.norm([0.3, -0.5, 0.8]))],
         1000.0, (1e-6, 1e-8), ball_field),
        ("plane/round-disk", registry()["plane/round-disk"].example,
         registry()["plane/round-disk"].state, 1000.0, (1e-8,), disk_field),
        ("sphere/flat-base", registry()["sphere/flat-base"].example,
         registry()["sphere/flat-base"].state, 1000.0, (1e-8,), flat_field),
    ]
    load0 = os.getloadavg()
    lines = [f"bench/limit.py{' --quick' if quick else ''}: time at matched final-state error "
             "(log-log interpolation on each front); per tolerance the competitors run "
             f"interleaved, best of {3 if quick else 5} (scipy: 1 run); one process; error vs "
             "heyoka long double tol 1e-18.",
             f"load average at the start: {load0[0]:.2f} {load0[1]:.2f} {load0[2]:.2f} "
             f"({os.cpu_count()} cores)"]
    out = {"quick": quick, "load_start": load0}
    for case, prm, y0, T, targets, lf in cases:
        res, table, breakdown, compile_s, robust = front(case, prm, y0, T, targets, lf,
                                                         quick)
        fc = field_cost(case, prm, y0, lf)
        out[case] = {"T": T, "state": [float(v) for v in y0], "params": prm,
                     "fronts": res, "at_error": table, "at_error_robust": robust,
                     "breakdown": breakdown,
                     "first_call_s": compile_s, "field_ns_per_call": fc,
                     "load": os.getloadavg()}
        lines.append(f"\n{case}, T = {T:g}, y0 = {np.round(np.asarray(y0, float), 6).tolist()}"
                     f"  (load {os.getloadavg()[0]:.2f})")
        for name, pts in res.items():
            lines.append(f"  front {name:14s} " + "  ".join(f"({e:.1e}, {w * 1e3:.2f} ms)"
                                                           for e, w in pts))
        for t in targets:
            key = f"{t:.0e}"
            lim = (table.get("limit") or {}).get(key)
            hey = table["heyoka-lean"][key]
            rlim = (robust.get("limit") or {}).get(key)
            lines.append(f"  at error {key}: time, x the limit, x heyoka-lean | robust: rhs "
                         "calls at that error x best cost per call, x limit (robust), x heyoka")
            for name in table:
                v = table[name][key]
                if v is None:
                    lines.append(f"    {name:14s}  outside its front")
                    continue
                rl = f"{v / lim:6.2f}" if lim else "     -"
                rh = f"{v / hey:6.2f}" if hey else "     -"
                line = f"    {name:14s} {v * 1e3:9.2f} ms {rl} x limit {rh} x heyoka"
                r = (robust.get(name) or {}).get(key)
                if r is not None:
                    a = f"{r / rlim:6.2f}" if rlim else "     -"
                    b = f"{r / hey:6.2f}" if hey else "     -"
                    line += f" | {r * 1e3:8.2f} ms {a} x limit {b} x heyoka"
                lines.append(line)
        lines.append("  where the time goes (per tolerance: ns per rhs call = (stepper + "
                     "field) / calls; steps):")
        for name, rows in breakdown.items():
            lines.append(f"    {name:14s} " + "  ".join(
                f"{r['rtol']:.0e}: {r['ns_per_rhs']:5.1f} ns {r['steps']:6d} st"
                for r in rows))
        lines.append("  field alone, ns per call (a loop of dependent calls): "
                     + ", ".join(f"{k} {v:.1f}" for k, v in fc.items()))
        lines.append("  first call (compile or cache load), s: "
                     + ", ".join(f"{k} {v:.1f}" for k, v in compile_s.items()))
    load1 = os.getloadavg()
    lines.append(f"\nload average at the end: {load1[0]:.2f} {load1[1]:.2f} {load1[2]:.2f}")
    out["load_end"] = load1
    text = "\n".join(lines) + "\n"
    OUT.mkdir(exist_ok=True)
    print(text)
    (OUT / ("limit_quick.txt" if quick else "limit.txt")).write_text(text)


if __name__ == "__main__":
    main()
