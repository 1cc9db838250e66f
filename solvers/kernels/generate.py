"""Per-case fields, generated: the equations written once in sympy for the case's structure,
with common subexpressions eliminated, emitted as numba source and as heyoka expressions.

The general field (solvers/kernels/fields.py) evaluates every term of (1.1)-(1.3) for any
body: a square root and a full Hessian per support part, a general 3x3 solve, gravity,
Brun and gyrostat terms whose parameters may be zero. Here the same equations
(CONVENTIONS.md) are written symbolically for one *structure*: the set of parameter slots
of the vector p (solvers/kernels/layout.py) that are nonzero. A zero slot is the number 0,
so sympy drops every term it multiplies; the others are read from p at run time (one
compiled module serves every parameter value of the structure), or, with fold=True,
written into the code as literals (constant folding, for a run that fixes them).

What is derived here, not copied from fields.py:
  h(gamma)  the support function, only its nonzero parts (support.py's formula);
  r = grad h, J = Hess h by sympy's differentiation; |gamma| = 1 is never assumed
            (the field is also evaluated off the sphere, by the checks' complex steps);
  omega = I_Q^-1 M (1.6), (E - k J) dgamma/dt = gamma x omega ((1.2)/(1.3)) by the
            adjugate (Cramer), k = 0: dgamma/dt = gamma x omega without a solve;
  a ball    (h = c |gamma| + (a, gamma), no ellipsoid or disk part): J = lam (E - gamma
            gamma^T / |gamma|^2), lam = c / |gamma|, written out instead of differentiated.
            Since (gamma, gamma x omega) = 0 identically, J dgamma/dt = lam dgamma/dt and
            (E - k J) dgamma/dt = gamma x omega is dgamma/dt = gamma x omega / (1 - k lam)
            (det(E - k J) = (1 - k lam)^2): no Hessian, no solve; gamma x dU loses r's
            part lam gamma. A centred ball (a = 0) needs no square root on the way to
            omega: m (r^2 E - r r^T) = (m c^2 / |gamma|^2) (|gamma|^2 E - gamma gamma^T),
            so I_Q = diag(I_i + m c^2) - (m c^2 / |gamma|^2) gamma gamma^T, a rank-one
            change of a constant diagonal: omega by Sherman-Morrison, not a 3x3 solve.
            All of it holds for any gamma (complex ones too): |gamma| = 1 is not assumed;
  a disk    (h = d |(g1, g2)|, centred, on the plane): r = (d/s) rho, rho = (g1, g2, 0),
            J = (d/s^3) t t^T with the edge's tangent t = (-g2, g1, 0); as for the ball,
            omega needs no square root (only gravity's torque takes d/s);
  dU/dgamma = m g r + eps I gamma: the term m g J^T gamma of fields.py is dropped, since h
            is positively homogeneous of degree 1 and so Hess h . gamma = 0 identically
            (Euler), for any gamma, not only |gamma| = 1;
  M_Q = gamma x (E - k J)^-1 dU (J symmetric), (1.1);
  flat base: r = (r1, r2, z), dr/dt = (omega2, -omega1, 0) / k (3.17), (3.16).
The generated code returns the general field's status codes (layout.py) at the same
places: the flat disk (sin theta < FLAT_DISK), a singular I_Q, det(E - k J) <= 0, and a
non-finite derivative. tests/test_generated.py compares every case with the general
field and the independent NumPy field (solvers/models/reference.py) to round-off.

The modules made from this text are written to the kernel cache and loaded from it by
solvers/kernels/field_modules.py (named by the structure and the content hash of the
sources of solvers/kernels: module_cache.py).
"""

from __future__ import annotations

import numpy as np

from solvers.kernels import layout as L
from solvers.kernels.rubber_field import rubber_reaction
from solvers.kernels.support import FLAT_DISK

SLOT_NAMES = ("I1", "I2", "I3", "m", "k", "S1", "S2", "S3", "g", "eps", "B11", "B22", "B33",
              "B12", "B13", "B23", "c", "d", "a1", "a2", "a3", "z", "rubber")
assert len(SLOT_NAMES) == L.N_PARAMS
GENERATED_MODELS = (L.MODEL_FULL, L.MODEL_FLAT)


def structure(model: int, p, fold: bool = False) -> tuple:
    """What a generated field depends on: the model, its nonzero slots, and with fold the
    values (as exact float reprs)."""
    p = np.asarray(p, dtype=float)
    nz = tuple(int(i) for i in np.flatnonzero(p != 0.0))
    vals = tuple(repr(float(p[i])) for i in nz) if fold else ()
    return (int(model), nz, vals)


# --- the equations ------------------------------------------------------------------------

class Program:
    """Straight-line code as (symbol, sympy expression) assignments, written stage by stage
    like the hand-written field (support, I_Q, omega, ...), so that sympy never expands
    one stage into the next. `let` binds an expression to a fresh symbol, unless it is a
    number or a symbol already: a zero parameter makes whole stages vanish."""

    def __init__(self):
        self.assign: list = []
        self.seen: dict = {}
        self.n = 0

    def let(self, expr):
        import sympy as sp  # lazy: sympy, not at server start

        expr = sp.sympify(expr)
        if expr.is_Number or expr.is_Symbol:
            return expr
        if expr in self.seen:          # the same expression twice (e.g. E - k J solved
            return self.seen[expr]     # for dgamma/dt and for M_Q): computed once
        sym = sp.Symbol(f"v{self.n}")
        self.n += 1
        self.assign.append((sym, expr))
        self.seen[expr] = sym
        return sym

    def let_all(self, exprs):
        """Common subexpressions of several expressions first (sympy's cse), then each."""
        import sympy as sp  # lazy: sympy, not at server start

        reps, red = sp.cse(list(exprs), symbols=sp.numbered_symbols(f"u{self.n}_"),
                           optimizations="basic")
        sub = {}
        for s, e in reps:
            sub[s] = self.let(e.xreplace(sub))
        return [self.let(e.xreplace(sub)) for e in red]


def _cross(a, b):
    return [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]


def _solve_sym(P, A, b, refine=False):
    """(det, x) with A x = b, A symmetric as (a00, a01, a02, a11, a12, a22), by the
    adjugate: the det is returned so the code can report a singular A. refine: one step
    of iterative refinement, x += A^-1 (b - A x): the adjugate alone loses digits like
    cond(A)^2 where E - k J is nearly singular (a body that just fits its sphere, 1 - kR
    -> 0; tests/test_generated.py::test_extremes_agree measures it)."""
    a00, a01, a02, a11, a12, a22 = A
    c00 = P.let(a11 * a22 - a12 * a12)
    c01 = P.let(a12 * a02 - a01 * a22)
    c02 = P.let(a01 * a12 - a11 * a02)
    c11 = P.let(a00 * a22 - a02 * a02)
    c12 = P.let(a01 * a02 - a00 * a12)
    c22 = P.let(a00 * a11 - a01 * a01)
    det = P.let(a00 * c00 + a01 * c01 + a02 * c02)
    inv = P.let(1 / det)

    def apply(v):
        return [P.let((c00 * v[0] + c01 * v[1] + c02 * v[2]) * inv),
                P.let((c01 * v[0] + c11 * v[1] + c12 * v[2]) * inv),
                P.let((c02 * v[0] + c12 * v[1] + c22 * v[2]) * inv)]

    x = apply(b)
    if refine:
        res = [P.let(b[0] - (a00 * x[0] + a01 * x[1] + a02 * x[2])),
               P.let(b[1] - (a01 * x[0] + a11 * x[1] + a12 * x[2])),
               P.let(b[2] - (a02 * x[0] + a12 * x[1] + a22 * x[2]))]
        x = [P.let(xi + di) for xi, di in zip(x, apply(res), strict=True)]
    return det, x


def equations(model: int, p, fold: bool = False):
    """The case's field as a Program: (program, state symbols, parameter symbols used,
    outputs dy/dt, checks). checks: named expressions the code tests for singularities
    ("iq": det I_Q, "fit": det(E - k J), "edge": sin theta of the disk)."""
    import sympy as sp  # lazy: sympy, not at server start

    p = np.asarray(p, dtype=float)
    P = []
    for i, name in enumerate(SLOT_NAMES):
        if p[i] == 0.0:
            P.append(sp.Integer(0))
        elif fold:
            P.append(sp.Float(float(p[i]), 17) if float(p[i]) != 1.0 else sp.Integer(1))
        else:
            P.append(sp.Symbol(name, real=True))
    # the rubber slot is a flag of the structure (the reaction is added or not), no value
    # the equations read
    P[L.RUBBER] = sp.Integer(0)
    prog = Program()
    m, k = P[L.MASS], P[L.CURV]
    S = P[L.S1:L.S3 + 1]
    Iv = P[L.I1:L.I3 + 1]
    checks = {}
    M = list(sp.symbols("y0 y1 y2"))
    if model == L.MODEL_FLAT:
        r = [sp.Symbol("y3"), sp.Symbol("y4"), P[L.FLAT_Z]]
        state = [*M, r[0], r[1]]
    elif model == L.MODEL_FULL:
        g = list(sp.symbols("y3 y4 y5"))
        state = [*M, *g]
        B = ((P[L.B11], P[L.B12], P[L.B13]), (P[L.B12], P[L.B22], P[L.B23]),
             (P[L.B13], P[L.B23], P[L.B33]))
        h = sp.Integer(0)
        ellipsoid = any(p[s] != 0.0 for s in (L.B11, L.B22, L.B33))
        if ellipsoid:                                             # ellipsoid, (2.39)
            h += sp.sqrt(sum(B[i][j] * g[i] * g[j] for i in range(3) for j in range(3)))
        h += P[L.BALL_C] * sp.sqrt(g[0] ** 2 + g[1] ** 2 + g[2] ** 2)   # ball, (2.28)
        if p[L.DISK_D] != 0.0:                                    # disk, (2.15)
            checks["edge"] = sp.sqrt(g[0] ** 2 + g[1] ** 2)
            h += P[L.DISK_D] * checks["edge"]
        h += P[L.A1] * g[0] + P[L.A2] * g[1] + P[L.A3] * g[2]
        sphere = not ellipsoid and p[L.DISK_D] == 0.0
        offset = any(p[s] != 0.0 for s in (L.A1, L.A2, L.A3))
        centred = sphere and not offset
        # a sharp-edged disk alone, centred, on the plane: h = d s, s = |(g1, g2)|
        disk = (not ellipsoid and p[L.DISK_D] != 0.0 and p[L.BALL_C] == 0.0 and not offset
                and k == 0)
        if disk:
            rho = [g[0], g[1], sp.Integer(0)]
            is2 = prog.let(1 / prog.let(g[0] ** 2 + g[1] ** 2))
            r = rho
        elif sphere:     # h = c |gamma| + (a, gamma): J = lam (E - gamma gamma^T / |gamma|^2)
            ig = prog.let(1 / prog.let(g[0] ** 2 + g[1] ** 2 + g[2] ** 2))
            lam = prog.let(P[L.BALL_C] * sp.sqrt(ig))
            r = [prog.let(lam * g[i] + P[L.A1 + i]) for i in range(3)]    # r = grad h
        else:
            r = [sp.diff(h, gi) for gi in g]                          # r = grad h
            Jf = [[sp.diff(r[i], g[j]) for j in range(3)] for i in range(3)]   # J = Hess h
            rJ = prog.let_all([*r, Jf[0][0], Jf[0][1], Jf[0][2], Jf[1][1], Jf[1][2],
                               Jf[2][2]])
            r, Js = rJ[:3], tuple(rJ[3:])
            J = [[Js[0], Js[1], Js[2]], [Js[1], Js[3], Js[4]], [Js[2], Js[4], Js[5]]]
    else:
        raise ValueError(f"no generated field for model {model}")
    if model == L.MODEL_FULL and disk:
        # r = (d/s) rho, rho = (g1, g2, 0): m (r^2 E - r r^T) = sg (s^2 E - rho rho^T),
        # sg = m d^2 / s^2: no square root on the way to omega
        sg = prog.let(m * P[L.DISK_D] ** 2 * is2)
        mr = [prog.let(sg * g[0]), prog.let(sg * g[1]), sp.Integer(0)]
        IQ = (Iv[0] + sg * g[1] ** 2, -mr[0] * g[1], 0, Iv[1] + sg * g[0] ** 2, 0,
              Iv[2] + m * P[L.DISK_D] ** 2)
    elif model == L.MODEL_FULL and centred:
        # r = lam gamma: m (r^2 E - r r^T) = s (|gamma|^2 E - gamma gamma^T), s = m lam^2 =
        # m c^2 / |gamma|^2, and s |gamma|^2 = m c^2, so I_Q = D - s gamma gamma^T with the
        # constant D = diag(I_i + m c^2): a rank-one change of a diagonal, solved by
        # Sherman-Morrison instead of a 3x3 adjugate (with the adjugate the plane's
        # Chaplygin ball was much slower than the scalar limit, whose field has this form:
        # bench/limit.py, docs/performance.md). Exact for any gamma
        # (complex ones too), no square root:
        #   omega = u + (m c^2 (gamma, u) / q) v,   u = D^-1 M,   v = D^-1 gamma,
        #   q = sum_i I_i gamma_i v_i = |gamma|^2 (1 - s (gamma, v)),
        # det I_Q = D_1 D_2 D_3 q / |gamma|^2. q is a sum of terms of one sign, not
        # 1 - (nearly 1): a tiny I under a heavy ball, where omega's component along
        # gamma rests on q, keeps its digits
        mc2 = m * P[L.BALL_C] ** 2
        sg = prog.let(mc2 * ig)
        dinv = [prog.let(1 / prog.let(Iv[i] + mc2)) for i in range(3)]
        uD = [prog.let(dinv[i] * M[i]) for i in range(3)]
        vD = [prog.let(dinv[i] * g[i]) for i in range(3)]
        q = prog.let(Iv[0] * g[0] * vD[0] + Iv[1] * g[1] * vD[1] + Iv[2] * g[2] * vD[2])
        # times 1 / q, not divided by q: a quotient by a complex number (the checks'
        # complex steps) is not the real quotient even for a zero imaginary part
        # (NumPy's complex division scales by a reciprocal), a reciprocal is
        coef = prog.let(mc2 * (g[0] * uD[0] + g[1] * uD[1] + g[2] * uD[2])
                        * prog.let(1 / q))
        w = [prog.let(uD[i] + coef * vD[i]) for i in range(3)]
        checks["iq"] = q
        IQ = None
        r = g
    else:
        mr = [prog.let(m * ri) for ri in r]
        rr = prog.let(mr[0] * r[0] + mr[1] * r[1] + mr[2] * r[2])
        IQ = (Iv[0] + rr - mr[0] * r[0], -mr[0] * r[1], -mr[0] * r[2],
              Iv[1] + rr - mr[1] * r[1], -mr[1] * r[2], Iv[2] + rr - mr[2] * r[2])
    if IQ is not None:
        checks["iq"], w = _solve_sym(prog, [prog.let(a) for a in IQ], M)   # (1.6)
    a = [M[i] + S[i] for i in range(3)]
    if model == L.MODEL_FLAT:
        ik = prog.let(1 / k)
        rd = [prog.let(w[1] * ik), prog.let(-w[0] * ik), sp.Integer(0)]   # (3.17)
        wr = [prog.let(e) for e in _cross(w, r)]
        Md = [x + m * y for x, y in zip(_cross(a, w), _cross(rd, wr), strict=True)]
        return prog, state, _used(P), [*Md, rd[0], rd[1]], checks
    u = [prog.let(e) for e in _cross(g, w)]
    if sphere:
        # (gamma, gamma x omega) = 0 identically (for any gamma, complex ones too), so
        # J u = lam u, and E - k J has the eigenvalues 1 - k lam on the plane normal to
        # gamma and 1 along it: no solve, det(E - k J) = (1 - k lam)^2 ((1.2)/(1.3))
        if k == 0:
            gd = u
        else:
            fk = prog.let(1 - k * lam)
            checks["fit"] = prog.let(fk * fk)
            fi = prog.let(1 / fk)
            gd = [prog.let(ui * fi) for ui in u]
        # dr/dt = J dgamma/dt = lam dgamma/dt; centred: m dr x (omega x r) is
        # (m lam^2) dgamma/dt x (omega x gamma), m lam^2 = sg
        rd = [prog.let(sg * gi) for gi in gd] if centred else [prog.let(lam * gi) for gi in gd]
    elif k == 0:
        gd = u                                                    # (1.2)
        if disk:
            # J = (d/s) (P - rho rho^T / s^2) = (d/s^3) t t^T, P = diag(1, 1, 0), t = (-g2,
            # g1, 0) (the edge's tangent: no difference of near-equal vectors), so
            # m dr x (omega x r) = sg (t (t, dgamma) / s^2) x (omega x rho)
            tq = prog.let(sg * (rho[0] * gd[1] - rho[1] * gd[0]) * is2)
            rd = [prog.let(-rho[1] * tq), prog.let(rho[0] * tq), sp.Integer(0)]
    else:
        EkJ = tuple(prog.let((1 if i in (0, 3, 5) else 0) - k * Js[i]) for i in range(6))
        checks["fit"], gd = _solve_sym(prog, EkJ, u, True)             # (1.3)
    if not sphere and not disk:
        rd = [prog.let(J[i][0] * gd[0] + J[i][1] * gd[1] + J[i][2] * gd[2])
              for i in range(3)]
    if sphere and centred:   # r = gamma: omega x r = -(gamma x omega) = -u, bit for bit
        wr = [-ui for ui in u]
    else:
        wr = [prog.let(e) for e in _cross(w, r)]
    mrd = 1 if (sphere and centred) or disk else m
    Md = [x + mrd * y for x, y in zip(_cross(a, w), _cross(rd, wr), strict=True)]
    mg, eps = m * P[L.GRAV], P[L.BRUN]
    # dU/dgamma = m g r + eps I gamma (Hess h . gamma = 0); only gamma x dU enters, and
    # for a sphere gamma x (lam gamma) = 0: r's part lam gamma is dropped, r -> a
    if sphere:
        rU = [P[L.A1 + i] for i in range(3)]
    elif disk:         # r = (d/s) rho: the one square root, off the way to omega
        lam_d = prog.let(P[L.DISK_D] * sp.sqrt(is2))
        rU = [lam_d * x for x in rho]
    else:
        rU = r
    if (mg != 0 and any(x != 0 for x in rU)) or eps != 0:
        dU = [prog.let(mg * rU[i] + eps * Iv[i] * g[i]) for i in range(3)]
        if k != 0 and sphere:   # gamma x (E - k J)^-1 dU = gamma x dU / (1 - k lam)
            dU = [prog.let(x * fi) for x in dU]
        elif k != 0:
            dU = _solve_sym(prog, EkJ, dU, True)[1]                 # (E - k J^T)^-1 dU
        Md = [x + y for x, y in zip(Md, _cross(g, dU), strict=True)]
    if p[L.RUBBER] != 0.0:
        def inverse_gamma():   # I_Q^-1 gamma, where rubber_reaction's order of lets needs it
            if IQ is None:      # centred ball (Sherman-Morrison): v (1 + m c^2 (gamma, v) / q)
                f = prog.let(1 + mc2 * (g[0] * vD[0] + g[1] * vD[1] + g[2] * vD[2])
                             * prog.let(1 / q))
                return [prog.let(f * x) for x in vD]
            return _solve_sym(prog, [prog.let(a) for a in IQ], g)[1]

        Md = rubber_reaction(prog, Md, P, g, w, gd, r, rd, inverse_gamma, sphere=sphere,
                             disk=disk, lam=lam if sphere else None,
                             is2=is2 if disk else None)
    return prog, state, _used(P), [*Md, *gd], checks


def _used(P):
    return [x for x in P if getattr(x, "is_Symbol", False)]


# --- numba source ---------------------------------------------------------------------------

def _code(e) -> str:
    """Python/numba text of a sympy expression: square roots as np.sqrt, integer powers
    as products, no pow() in the hot path."""
    import sympy as sp  # lazy: sympy, not at server start

    if e.is_Symbol:
        return e.name
    if e.is_Number:
        return repr(float(e))
    if e.is_Add:
        return "(" + " + ".join(_code(a) for a in e.args) + ")"
    if e.is_Mul:
        num, den = [], []
        for f in e.args:
            if f.is_Pow and f.exp.is_negative:
                den.append(_code(sp.Pow(f.base, -f.exp)))
            elif f == -1:
                num.insert(0, "-1.0")
            else:
                num.append(_code(f))
        text = "*".join(num) if num else "1.0"
        return f"({text}/({'*'.join(den)}))" if den else f"({text})"
    if e.is_Pow:
        b, x = _code(e.base), e.exp
        if x.is_Integer and x > 0:
            return "(" + "*".join([b] * int(x)) + ")"
        if x.is_Integer and x < 0:
            return "(1.0/(" + "*".join([b] * int(-x)) + "))"
        if x == sp.Rational(1, 2):
            return f"np.sqrt({b})"
        if x.is_Rational and x.q == 2:
            if x > 0:
                return "(" + "*".join([b] * int(x.p // 2) + [f"np.sqrt({b})"]) + ")"
            n = int(-x.p // 2)
            return "(1.0/(" + "*".join([b] * n + [f"np.sqrt({b})"]) + "))"
    raise ValueError(f"cannot emit {e!r}")


def _live(prog, roots):
    """The assignments the roots need, in order (dead stages dropped)."""
    need = set()
    for e in roots:
        need |= e.free_symbols
    keep = []
    for sym, ex in reversed(prog.assign):
        if sym in need:
            keep.append((sym, ex))
            need |= ex.free_symbols
    return keep[::-1]


def _share_roots(assign, extra):
    """One reciprocal square root per base: where a bound symbol b appears under a
    half-integer power, `q = 1/sqrt(b)` is bound after b and every power of b with a
    half-integer or negative integer exponent becomes a product of q's (b^-1/2 = q,
    b^-1 = q q, b^-3/2 = q q q, b^1/2 = b q): one sqrt and one division instead of one
    per power. Returns (assignments, extra expressions), both rewritten."""
    import sympy as sp  # lazy: sympy, not at server start

    exprs = [ex for _, ex in assign] + list(extra)
    pows = [pw for e in exprs for pw in e.atoms(sp.Pow)
            if pw.base.is_Symbol and pw.exp.is_Rational]
    # a base under a negative half-integer power (a sqrt alone stays a sqrt)
    bases = {pw.base for pw in pows if pw.exp.q == 2 and pw.exp < 0}
    if not bases:
        return assign, list(extra)
    q = {b: sp.Symbol(f"q_{b.name}") for b in bases}

    def rewrite(e):
        reps = {}
        for pw in e.atoms(sp.Pow):
            b, x = pw.base, pw.exp
            if b not in q or not x.is_Rational or not (x.q == 2 or (x.q == 1 and x < 0)):
                continue
            if x < 0:
                reps[pw] = sp.Mul(*([q[b]] * int(-2 * x)), evaluate=False)
            else:      # b^(n/2), n odd > 0: b^((n+1)/2) q
                reps[pw] = sp.Mul(*([b] * int((x.p + 1) // 2) + [q[b]]), evaluate=False)
        return e.xreplace(reps) if reps else e

    out = []
    for sym, ex in assign:
        out.append((sym, rewrite(ex)))
        if sym in q:
            out.append((q[sym], sp.Pow(sp.sqrt(sym), -1, evaluate=False)))
    return out, [rewrite(e) for e in extra]


def field_body(model: int, p, fold: bool = False):
    """The field's straight-line code for the case's structure, shared by the array field
    of `numba_source` and the scalar field of the small kernels (solvers/kernels/small.py),
    so both run the same expressions in the same order: (parameter symbols used, state
    symbols, body) where body is a list of (kind, text): ("let", "name = expr"),
    ("check", (condition, status)): return status if condition holds; the outputs are
    the names d0, d1, ... bound last."""
    import sympy as sp  # lazy: sympy, not at server start

    prog, state, params, outs, checks = equations(model, p, fold)
    outs = [sp.sympify(e) for e in outs]
    tests = [checks[n] for n in ("iq", "fit") if n in checks]
    body = []
    if "edge" in checks:   # before anything divides by sin theta (support.py)
        body.append(("check", (f"abs(np.sqrt(y3 * y3 + y4 * y4).real) < {FLAT_DISK!r}",
                               L.SING_EDGE)))
    assign, shared = _share_roots(_live(prog, [*outs, *tests]), [*outs, *tests])
    outs, tests = shared[:len(outs)], shared[len(outs):]
    for sym, ex in assign:
        body.append(("let", f"{sym.name} = {_code(ex)}"))
    body.append(("check", (f"{_code(checks['iq'])} == 0", L.SING_INERTIA)))
    if "fit" in checks:
        body.append(("check", (f"not {_code(tests[-1])}.real > 0.0", L.SING_FIT)))
    for i, ex in enumerate(outs):
        body.append(("let", f"d{i} = {_code(ex)} + 0.0 * y0"))
    total = " + ".join(f"d{i}" for i in range(len(outs)))
    body.append(("check", (f"not np.isfinite({total})", L.SING_NONFINITE)))
    return params, state, body


def numba_source(model: int, p, fold: bool = False) -> str:
    """A module with `field(p, y, dydt) -> status` and `rhs(model, t, y, p, dydt)` (the
    signature of fields.rhs) for the case's structure."""
    params, state, body = field_body(model, p, fold)
    key = structure(model, p, fold)
    ind = "    "
    lines = [f'"""Generated by solvers/kernels/generate.py for structure {key!r}."""',
             "", "import numba", "import numpy as np", "",
             "# inline='always': numba inlines the field into each caller's IR (the stage",
             "# loop of the integrator): no call, no reference counting of arrays per stage",
             "inline = numba.njit(cache=True, error_model='numpy', nogil=True, inline='always')",
             "", "", "@inline", "def field(p, y, dydt):"]
    for s in params:
        lines.append(f"{ind}{s.name} = p[{SLOT_NAMES.index(s.name)}]")
    for i, s in enumerate(state):
        lines.append(f"{ind}{s.name} = y[{i}]")
    for kind, what in body:
        if kind == "let":
            lines.append(f"{ind}{what}")
        else:
            lines.append(f"{ind}if {what[0]}:")
            lines.append(f"{ind}    return {what[1]}")
    for i in range(len(state)):
        lines.append(f"{ind}dydt[{i}] = d{i}")
    lines.append(f"{ind}return {L.OK}")
    lines += ["", "", "@inline", "def rhs(model, t, y, p, dydt):",
              f"{ind}return field(p, y, dydt)", ""]
    return "\n".join(lines)
