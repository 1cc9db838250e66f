"""The rolling field as a heyoka expression system: Taylor integration and the reference.

An independent implementation of the same equations (CONVENTIONS.md, (1.1)-(1.3),
(3.16)-(3.17)) for heyoka's Taylor integrator (Biscani & Izzo, MNRAS 504 (2021) 2614):
the body enters only through its support function

    h(gamma) = sqrt(gamma.B gamma) + c |gamma| + d sqrt(g1^2 + g2^2) + (a, gamma),

r = grad h and J = Hess h are taken by heyoka's symbolic differentiation (`hy.diff`),
not from the hand-written Hessian of solvers/kernels/support.py, and the 3x3 solves are
Cramer's rule on expressions. heyoka compiles the system with LLVM for float64, long
double (80-bit here), real128 (quadruple, in software) or mpfr `real`; the work-precision
benchmark runs it in float64 as a competitor and in real128 as the high-precision
reference. tests/test_taylor.py checks it against the compiled field at random points.

heyoka is a development dependency (`pip install -e .[dev]`); this module imports it
lazily so the solver core does not need it.
"""

from __future__ import annotations

import time

import numpy as np

from solvers.kernels import layout as L


def _hy():
    import heyoka  # lazy: heyoka, an optional extra slow to import, only when it runs

    return heyoka


def _solve_sym(A, b):
    """x = A^-1 b for symmetric A given as (a00, a01, a02, a11, a12, a22), by Cramer."""
    a00, a01, a02, a11, a12, a22 = A
    c00 = a11 * a22 - a12 * a12
    c01 = a12 * a02 - a01 * a22
    c02 = a01 * a12 - a11 * a02
    c11 = a00 * a22 - a02 * a02
    c12 = a01 * a02 - a00 * a12
    c22 = a00 * a11 - a01 * a01
    det = a00 * c00 + a01 * c01 + a02 * c02
    return [(c00 * b[0] + c01 * b[1] + c02 * b[2]) / det,
            (c01 * b[0] + c11 * b[1] + c12 * b[2]) / det,
            (c02 * b[0] + c12 * b[1] + c22 * b[2]) / det]


def _cross(a, b):
    return [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]


def _num(x) -> float:
    return float(x)


def support_expression(p, g):
    """h(gamma) as an expression in the variables g (only the body's nonzero parts)."""
    hy = _hy()
    B = ((p[L.B11], p[L.B12], p[L.B13]), (p[L.B12], p[L.B22], p[L.B23]),
         (p[L.B13], p[L.B23], p[L.B33]))
    terms = []
    if any(p[s] != 0.0 for s in (L.B11, L.B22, L.B33)):
        q = sum(_num(B[i][j]) * g[i] * g[j] for i in range(3) for j in range(3)
                if B[i][j] != 0.0)
        terms.append(hy.sqrt(q))
    if p[L.BALL_C] != 0.0:
        terms.append(_num(p[L.BALL_C]) * hy.sqrt(g[0] * g[0] + g[1] * g[1] + g[2] * g[2]))
    if p[L.DISK_D] != 0.0:
        terms.append(_num(p[L.DISK_D]) * hy.sqrt(g[0] * g[0] + g[1] * g[1]))
    for i, slot in enumerate((L.A1, L.A2, L.A3)):
        if p[slot] != 0.0:
            terms.append(_num(p[slot]) * g[i])
    return sum(terms[1:], terms[0])


def _contact_inertia(p, r):
    m = _num(p[L.MASS])
    rr = m * (r[0] * r[0] + r[1] * r[1] + r[2] * r[2])
    return (_num(p[L.I1]) + rr - m * r[0] * r[0], -m * r[0] * r[1], -m * r[0] * r[2],
            _num(p[L.I2]) + rr - m * r[1] * r[1], -m * r[1] * r[2],
            _num(p[L.I3]) + rr - m * r[2] * r[2])


def system(model: int, p) -> tuple[list, list]:
    """(state variables, right-hand sides) of MODEL_FULL (M, gamma) or MODEL_FLAT
    (M, r1, r2) with parameter vector p."""
    hy = _hy()
    p = np.asarray(p, dtype=float)
    m, k = _num(p[L.MASS]), _num(p[L.CURV])
    S = [_num(p[L.S1]), _num(p[L.S2]), _num(p[L.S3])]
    if model == L.MODEL_FLAT:
        M = list(hy.make_vars("M1", "M2", "M3"))
        r1, r2 = hy.make_vars("r1", "r2")
        r = [r1, r2, _num(p[L.FLAT_Z]) + 0.0 * r1]
        w = _solve_sym(_contact_inertia(p, r), M)
        rd = [w[1] / k, -w[0] / k, 0.0 * r1]                                 # (3.17)
        Md = [a + m * b for a, b in zip(_cross([M[i] + S[i] for i in range(3)], w),
                                        _cross(rd, _cross(w, r)), strict=True)]
        return [*M, r1, r2], [*Md, rd[0], rd[1]]
    if model != L.MODEL_FULL:
        raise ValueError(f"no heyoka system for model {model}")
    M = list(hy.make_vars("M1", "M2", "M3"))
    g = list(hy.make_vars("g1", "g2", "g3"))
    h = support_expression(p, g)
    r = [hy.diff(h, gi) for gi in g]                                 # r = grad h
    J = [[hy.diff(r[i], g[j]) for j in range(3)] for i in range(3)]  # J = Hess h
    Js = (J[0][0], J[0][1], J[0][2], J[1][1], J[1][2], J[2][2])
    w = _solve_sym(_contact_inertia(p, r), M)                        # (1.6)
    u = _cross(g, w)
    if k == 0.0:
        gd = u                                                       # (1.2)
    else:
        EkJ = tuple((1.0 if i in (0, 3, 5) else 0.0) - k * Js[i] for i in range(6))
        gd = _solve_sym(EkJ, u)                                      # (1.3)
    rd = [J[i][0] * gd[0] + J[i][1] * gd[1] + J[i][2] * gd[2] for i in range(3)]
    mg, eps = m * _num(p[L.GRAV]), _num(p[L.BRUN])
    Md = [a + m * b for a, b in zip(_cross([M[i] + S[i] for i in range(3)], w),
                                    _cross(rd, _cross(w, r)), strict=True)]
    if mg != 0.0 or eps != 0.0:
        Iv = (_num(p[L.I1]), _num(p[L.I2]), _num(p[L.I3]))
        dU = []
        for i in range(3):
            term = 0.0 * g[0]
            if mg != 0.0:   # U = m g (r, gamma): dU = m g (r + J^T gamma)
                term = term + mg * (r[i] + J[0][i] * g[0] + J[1][i] * g[1] + J[2][i] * g[2])
            if eps != 0.0:
                term = term + eps * Iv[i] * g[i]
            dU.append(term)
        if k != 0.0:
            dU = _solve_sym(tuple((1.0 if i in (0, 3, 5) else 0.0) - k * Js[i]
                                  for i in range(6)), dU)
        Md = [a + b for a, b in zip(Md, _cross(g, dU), strict=True)]
    if _num(p[L.RUBBER]) != 0.0:
        Md = _rubber_reaction(m, _contact_inertia(p, r), g, w, gd, r, rd, Md)
    return [*M, *g], [*Md, *gd]


def _rubber_reaction(m, IQ, g, w, gd, r, rd, N):
    """N + lambda gamma: the reaction of the rubber constraint (omega, gamma) = 0, lambda
    from d/dt (omega, gamma) = 0 with omega = I_Q^-1 M,
        lambda = -[(I_Q^-1 gamma, N - (dI_Q/dt) omega) + (omega, dgamma/dt)]
                 / (I_Q^-1 gamma, gamma),
    (dI_Q/dt) omega = m (2 (r, dr/dt) omega - dr/dt (r, omega) - r (dr/dt, omega))
    (the Newton-Euler derivation of solvers/models/rubber_lagrange.py), on the expressions
    of this module (r, dr/dt from heyoka's differentiation of the support function)."""
    Ag = _solve_sym(IQ, g)
    rrd = sum(r[i] * rd[i] for i in range(3))
    rw = sum(r[i] * w[i] for i in range(3))
    rdw = sum(rd[i] * w[i] for i in range(3))
    E = [N[i] - m * (2.0 * rrd * w[i] - rd[i] * rw - r[i] * rdw) for i in range(3)]
    num = sum(Ag[i] * E[i] for i in range(3)) + sum(w[i] * gd[i] for i in range(3))
    lam = -num / sum(Ag[i] * g[i] for i in range(3))
    return [N[i] + lam * g[i] for i in range(3)]


def field_function(model: int, p, fp_type=float):
    """A compiled `f(y) -> dy/dt` of the expression system (heyoka cfunc), for checks."""
    hy = _hy()
    vars_, rhs = system(model, p)
    cf = hy.cfunc(rhs, vars=vars_, fp_type=fp_type)
    return lambda y: cf(np.asarray(y, dtype=fp_type))


FP_TYPES = {"float64": float, "longdouble": np.longdouble, "real128": "real128"}


def _fp(name: str):
    if name == "real128":
        return _hy().real128
    return FP_TYPES[name]


class Taylor:
    """heyoka's adaptive Taylor integrator on the rolling system (built once: the LLVM
    compilation costs seconds; `compile_s` says how much)."""

    def __init__(self, model: int, p, y0, *, tol: float, fp: str = "float64",
                 compact_mode: bool = False):
        hy = _hy()
        self.fp = _fp(fp)
        pairs = list(zip(*system(model, p), strict=True))
        t0 = time.perf_counter()
        state = self._cast(y0)
        self.ta = hy.taylor_adaptive(pairs, state, tol=self._scalar(tol), fp_type=self.fp,
                                     compact_mode=compact_mode)
        self.compile_s = time.perf_counter() - t0
        self.order = self.ta.order

    def _scalar(self, x):
        return self.fp(x) if self.fp is not float else float(x)

    def _cast(self, y):
        if self.fp is float:
            return np.asarray(y, dtype=float)
        if self.fp is np.longdouble:
            return np.asarray(y, dtype=np.longdouble)
        return np.array([self.fp(v) if isinstance(v, str) else self.fp(float(v)) for v in y],
                        dtype=self.fp)

    def run(self, y0, t_grid):
        """States at t_grid (t_grid[0] is the start), the wall time and the step count.
        Returns (Y float64 array, Y in the native type, wall_s, steps, ok)."""
        ta = self.ta
        ta.time = self._scalar(t_grid[0])
        ta.state[:] = self._cast(y0)
        grid = np.array([self._scalar(t) for t in t_grid], dtype=self.fp) \
            if self.fp is not float else np.asarray(t_grid, dtype=float)
        t0 = time.perf_counter()
        res = ta.propagate_grid(grid)
        wall = time.perf_counter() - t0
        outcome, nsteps, Y = res[0], res[3], res[-1]
        ok = outcome == _hy().taylor_outcome.time_limit
        return np.asarray(Y, dtype=float), Y, wall, int(nsteps), ok
