"""Unrolled Runge-Kutta steppers: each tableau written out as numba code with literals.

solvers/kernels/rk.py runs every method from its tableau as data: a stage is a loop over a
16 x 16 table, most of it zeros, read from memory. Here each tableau becomes code: for
stage i, `ytmp[m] = y[m] + h * (a_i0 * K[0, m] + ...)` with the coefficients as float
literals (repr: the exact doubles the tableau holds) and the zero terms dropped; the same
for y_{n+1} (b), the error estimate (E, Hairer's DOP853 norm included), the extra dense
stages and the dense-output weights (Clenshaw on the Chebyshev form, literal
coefficients). The loop over the state's components stays a loop, of a literal length
where the model fixes it (unrolling it too made numba's compile several times longer
for no speed).

Same results as the generic kernel: every unrolled sum adds the same nonzero products in
the same order as rk.py's loops, and a dropped term is an exact zero (the stages are finite:
a field returns SING_NONFINITE before writing a non-finite derivative), so the states
agree bit for bit (up to the sign of an exact zero). The rest of the step (controller,
sections, projection, samples, statuses, stats) is rk.py's own source: `integrator_source`
copies rk.py's `rk_integrate` and replaces only its tableau loops by calls of the
generated `_u_*` functions, which branch on `tid`, the index of the baked tableau equal to
the one passed in (`_which`: shapes and every coefficient compared once per call), or -1:
rk.py's loops, for any other tableau. The copy keeps the loop kernel as
`rk_integrate_generic` (the tests' reference; compiled only if called).

What it buys (bench/limit.py, "gen-unrolled" against "gen-loops"): with the generated
field inlined into the stages, ~1.1-1.2x per rhs call on the Chaplygin ball and the disk;
with the field called, nothing. It costs compile time (one case, one process at load 1:
27 s with dop853 unrolled, 37 s with dop853 and vern9, against the loop kernel's 18 s),
so the generated integrators unroll only the tableaux of auto's Runge-Kutta candidates
(solvers/integrate/integrator.GENERATED_UNROLLED).

The tableaux are data of solvers/integrate (a layer above this one): that layer hands them
in with `set_provider(fn)`, fn() -> {name: (A, c, b, E, P, meth)} (integrator.method_arrays).
"""

from __future__ import annotations

import hashlib

import numpy as np

UNROLL_VERSION = 1
_PROVIDER = None
_TABLEAUX: dict = {}       # the provider's answer, asked once


def set_provider(fn) -> None:
    """fn() -> {name: (A, c, b, E, P, meth)}: the tableaux the generated kernels may bake."""
    global _PROVIDER
    _PROVIDER = fn
    _TABLEAUX.clear()


def baked_tableaux(names) -> dict:
    """{name: arrays} for the named tableaux (a name the provider lacks is an error)."""
    if names and not _TABLEAUX:
        if _PROVIDER is None:
            raise ValueError("no tableaux provided (solvers.integrate.integrator sets them)")
        _TABLEAUX.update(_PROVIDER())
    unknown = [n for n in names if n not in _TABLEAUX]
    if unknown:
        raise ValueError(f"unknown tableaux {unknown}; known: {sorted(_TABLEAUX)}")
    return {n: _TABLEAUX[n] for n in names}


def tableaux_stamp(tabs: dict) -> str:
    h = hashlib.sha256(str(UNROLL_VERSION).encode())
    for name in sorted(tabs):
        h.update(name.encode())
        for a in tabs[name]:
            a = np.ascontiguousarray(a)
            h.update(str((a.dtype, a.shape)).encode())
            h.update(a.tobytes())
    return h.hexdigest()[:16]


def _lit(x) -> str:
    return repr(float(x))


def _dot(coef, m) -> str:
    """sum_j coef[j] K[j, m] over the nonzero coef, in rk.py's order."""
    terms = [f"{_lit(a)} * K[{j}, {m}]" for j, a in enumerate(coef) if a != 0.0]
    return " + ".join(terms) if terms else "0.0"


# --- the generated helpers; each takes tid first and falls back to rk.py's loops ---------

def _stages_body(A, c, i0, i1, n, ind):
    out = []
    for i in range(i0, i1):
        out.append(f"{ind}for m in range({n}):")
        out.append(f"{ind}    ytmp[m] = y[m] + h * ({_dot(A[i, :i], 'm')})")
        out.append(f"{ind}stats[S_RHS] += 1")
        out.append(f"{ind}st = rhs(model, t + {_lit(c[i])} * h, ytmp, p, K[{i}])")
        out.append(f"{ind}if st != L.OK:")
        out.append(f"{ind}    return st")
    out.append(f"{ind}return L.OK")
    return out


def _combine_body(b, n, ind):
    out = [f"{ind}if compensated:", f"{ind}    for m in range({n}):",
           f"{ind}        d = h * ({_dot(b, 'm')})",
           f"{ind}        d += comp[m]",
           f"{ind}        ynew[m] = y[m] + d",
           f"{ind}        comp_new[m] = d - (ynew[m] - y[m])",
           f"{ind}else:", f"{ind}    for m in range({n}):",
           f"{ind}        ynew[m] = y[m] + h * ({_dot(b, 'm')})",
           f"{ind}return"]
    return out


def _error_body(E, kind, n, ind):
    dop = kind == 1       # rk.ERR_DOP853
    s = E.shape[1]
    out = [f"{ind}e1 = 0.0", f"{ind}e2 = 0.0"]
    out.append(f"{ind}for m in range({n}):")
    out.append(f"{ind}    sc = atol[m] + rtol * max(abs(y[m]), abs(ynew[m]))")
    out.append(f"{ind}    a = {_dot(E[0, :s], 'm')}")
    out.append(f"{ind}    e1 += (a / sc) ** 2")
    if dop:
        out.append(f"{ind}    a = {_dot(E[1, :s], 'm')}")
        out.append(f"{ind}    e2 += (a / sc) ** 2")
    if dop:
        out += [f"{ind}if e1 == 0.0 and e2 == 0.0:", f"{ind}    return 0.0",
                f"{ind}return abs(h) * e1 / np.sqrt((e1 + 0.01 * e2) * {n})"]
    else:
        out.append(f"{ind}return abs(h) * np.sqrt(e1 / {n})")
    return out


def _dense_body(P, n, ind):
    """Y[j] = y + h sum_i w_i(x) K[i], w_i by Clenshaw on row i of the Chebyshev weights
    (rk.py's recurrence, term for term); rows of zeros give w_i = 0 and are dropped."""
    S, ncheb = P.shape
    out = []
    rows = [i for i in range(S) if np.any(P[i] != 0.0)]
    for i in rows:
        out += [f"{ind}b1 = 0.0", f"{ind}b2 = 0.0"]
        for k in range(ncheb - 1, 0, -1):
            out.append(f"{ind}b1, b2 = {_lit(P[i, k])} + 2.0 * x * b1 - b2, b1")
        out.append(f"{ind}w{i} = {_lit(P[i, 0])} + x * b1 - b2")
    terms = " + ".join(f"w{i} * K[{i}, m]" for i in rows) or "0.0"
    out.append(f"{ind}for m in range({n}):")
    out.append(f"{ind}    Y[j, m] = y[m] + h * ({terms})")
    out.append(f"{ind}return L.OK")
    return out


def _global(name, a) -> str:
    a = np.asarray(a)
    body = np.array2string(a, separator=", ", threshold=1 << 30, floatmode="unique",
                           max_line_width=1 << 30)
    return f"{name} = np.array({body}, dtype=np.{a.dtype}).reshape({a.shape})"


def helpers_source(tabs: dict, n: int) -> str:
    """The `_which` matcher and the `_u_*` helpers for the tableaux `tabs` (state dim n)."""
    names = sorted(tabs)
    g = ["", "# --- generated by solvers/kernels/unroll.py: " + ", ".join(names) + " ---", ""]
    for t, name in enumerate(names):
        A, c, b, E, P, meth = (np.asarray(x) for x in tabs[name])
        for key, arr in (("A", A), ("C", c), ("B", b), ("E", E), ("P", P), ("M", meth)):
            g.append(_global(f"_{key}{t}", arr))
    g += ["", "", "@kernel", "def _same(x, y):",
          "    if x.shape != y.shape:", "        return False",
          "    for i in range(x.size):",
          "        if x.flat[i] != y.flat[i]:", "            return False",
          "    return True", "", "", "@kernel", "def _which(A, c, b, E, P, meth):",
          '    """Index of the baked tableau equal to (A, c, b, E, P, meth), or -1; P may be',
          '    empty (no dense output)."""']
    for t in range(len(names)):
        g += [f"    if _same(A, _A{t}) and _same(c, _C{t}) and _same(b, _B{t}) and "
              f"_same(E, _E{t}) \\",
              f"            and _same(meth, _M{t}) and (P.shape[0] == 0 or _same(P, _P{t})):",
              f"        return {t}"]
    g.append("    return -1")

    def fn(head, bodies, generic):
        out = ["", "", "@kernel", head]
        for t, body in enumerate(bodies):
            out.append(f"    {'if' if t == 0 else 'elif'} tid == {t}:")
            out += body
        out += generic
        return out

    ind = " " * 8
    stg, dense_stg, comb, err, dense = [], [], [], [], []
    for name in names:
        A, c, b, E, P, meth = (np.asarray(x) for x in tabs[name])
        s, new = int(meth[0]), int(meth[1])
        stg.append(_stages_body(A, c, 1, s, n, ind))
        dense_stg.append(_stages_body(A, c, max(s, new + 1), A.shape[0], n, ind))
        comb.append(_combine_body(b, n, ind))
        err.append(_error_body(E, int(meth[2]), n, ind))
        dense.append(_dense_body(P, n, ind) if P.shape[0] else [f"{ind}return L.OK"])
    g += fn("def _u_stages(tid, model, p, t, y, h, A, c, i0, i1, K, ytmp, stats):", stg,
            ["    return _stages(model, p, t, y, h, A, c, i0, i1, K, ytmp, stats)"])
    g += fn("def _u_dense_stages(tid, model, p, t, y, h, A, c, i0, i1, K, ytmp, stats):",
            dense_stg, ["    return _stages(model, p, t, y, h, A, c, i0, i1, K, ytmp, stats)"])
    g += fn("def _u_combine(tid, K, h, y, ynew, comp, comp_new, compensated, b, s):", comb,
            ["    for m in range(y.shape[0]):", "        acc = 0.0",
             "        for i in range(s):", "            acc += b[i] * K[i, m]",
             "        d = h * acc", "        if compensated:", "            d += comp[m]",
             "            ynew[m] = y[m] + d", "            comp_new[m] = d - (ynew[m] - y[m])",
             "        else:", "            ynew[m] = y[m] + d"])
    g += fn("def _u_error(tid, E, K, s, h, y, ynew, atol, rtol, errkind):", err,
            ["    return _error(E, K, s, h, y, ynew, atol, rtol, errkind)"])
    g += fn("def _u_dense(tid, x, K, y, h, Y, j, P, w):", dense,
            ["    S = P.shape[0]", "    ncheb = P.shape[1]",
             "    for i in range(S):      # Clenshaw: w_i = sum_k P[i, k] T_k(x)",
             "        b1 = 0.0", "        b2 = 0.0",
             "        for k in range(ncheb - 1, 0, -1):",
             "            b1, b2 = P[i, k] + 2.0 * x * b1 - b2, b1",
             "        w[i] = P[i, 0] + x * b1 - b2",
             "    for m in range(y.shape[0]):", "        acc = 0.0",
             "        for i in range(S):", "            acc += w[i] * K[i, m]",
             "        Y[j, m] = y[m] + h * acc", "    return L.OK"])
    return "\n".join(g) + "\n"


# --- rk_integrate with its tableau loops replaced -------------------------------------------

_REPLACE = [
    ("    n = y0.shape[0]\n    S = A.shape[0]\n",
     "    n = y0.shape[0]\n    S = A.shape[0]\n    tid = _which(A, c, b, E, P, meth)\n"),
    ("        st = _stages(model, p, t, y, h, A, c, 1, s, K, ytmp, stats)\n",
     "        st = _u_stages(tid, model, p, t, y, h, A, c, 1, s, K, ytmp, stats)\n"),
    ("""            for m in range(n):
                acc = 0.0
                for i in range(s):
                    acc += b[i] * K[i, m]
                d = h * acc
                if compensated:
                    d += comp[m]
                    ynew[m] = y[m] + d
                    comp_new[m] = d - (ynew[m] - y[m])
                else:
                    ynew[m] = y[m] + d
""", "            _u_combine(tid, K, h, y, ynew, comp, comp_new, compensated, b, s)\n"),
    ("err = _error(E, K, s, h, y, ynew, atol, rtol, errkind)",
     "err = _u_error(tid, E, K, s, h, y, ynew, atol, rtol, errkind)"),
    ("""                    status = _stages(model, p, t, y, h, A, c, max(s, new + 1), S, K, ytmp,
                                     stats)
""", """                    status = _u_dense_stages(tid, model, p, t, y, h, A, c, max(s, new + 1),
                                             S, K, ytmp, stats)
"""),
    ("""                for i in range(S):      # Clenshaw: w_i = sum_k P[i, k] T_k(x)
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
""", "                _u_dense(tid, x, K, y, h, Y, j, P, w)\n"),
]
_HEAD = "@kernel\ndef rk_integrate("


def integrator_source(rk_source: str, tabs: dict, n: int | str = "y.shape[0]") -> str:
    """rk.py's source (its rhs import already pointing at the field to use) with the
    generic kernel also named rk_integrate_generic and, if tabs, an unrolled rk_integrate
    in its place. n: the state dimension, a number where the model fixes it."""
    if not tabs:
        return rk_source + "\n\nrk_integrate_generic = rk_integrate\n"
    at = rk_source.index(_HEAD)
    body = rk_source[at:]
    out = body
    for old, new in _REPLACE:
        if out.count(old) != 1:
            raise RuntimeError(f"rk.py changed: cannot unroll at {old.strip()[:60]!r}")
        out = out.replace(old, new)
    generic = body.replace("def rk_integrate(", "def rk_integrate_generic(", 1)
    return (rk_source[:at] + generic + helpers_source(tabs, n) + "\n\n" + out)
