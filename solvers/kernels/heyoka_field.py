"""The case's field as a heyoka system: solvers/kernels/generate.py's sympy equations of the
case's structure (the lean system: zero terms dropped) translated into heyoka expressions,
for the Taylor backend (solvers/integrate/taylor_backend.py)."""

from __future__ import annotations

import numpy as np

from solvers.kernels.generate import SLOT_NAMES, equations


def heyoka_system(model: int, p, fold: bool = True, with_checks: bool = False):
    """(state variables, right-hand sides, parameter values) for heyoka from the same sympy
    equations: the lean system (zero terms dropped). fold=False keeps the nonzero
    parameters as heyoka runtime parameters par[slot] (pass the returned values as pars),
    so one compiled integrator serves every value; fold=True returns no values.
    with_checks: a fourth item, the singularity checks of `equations` ("iq", "fit",
    "edge") as heyoka expressions (the Taylor backend's terminal events)."""
    # lazy: heyoka and sympy, slow to import, only when the Taylor backend compiles
    import heyoka as hy
    import sympy as sp

    prog, state, params, outs, checks = equations(model, p, fold)
    hvars = list(hy.make_vars(*[s.name for s in state]))
    table = dict(zip(state, hvars, strict=True))
    for s in params:
        table[s] = hy.par[SLOT_NAMES.index(s.name)]
    defs = dict(prog.assign)
    memo: dict = {}

    def tr(e):
        if e in memo:
            return memo[e]
        if e in table:
            out = table[e]
        elif e in defs:
            out = tr(defs[e])
        elif e.is_Number:
            out = hy.expression(float(e))
        elif e.is_Add:
            out = hy.sum([tr(a) for a in e.args])
        elif e.is_Mul:
            out = tr(e.args[0])
            for a in e.args[1:]:
                out = out * tr(a)
        elif e.is_Pow:
            b, x = tr(e.base), e.exp
            if x == sp.Rational(1, 2):
                out = hy.sqrt(b)
            elif x == -1:
                out = 1.0 / b
            elif x.is_Integer and x > 0:
                out = b
                for _ in range(int(x) - 1):
                    out = out * b
            else:
                out = b ** float(x)
        else:
            raise ValueError(f"cannot translate {e!r}")
        memo[e] = out
        return out

    n_par = 1 + max((SLOT_NAMES.index(s.name) for s in params), default=-1)
    out = (hvars, [tr(sp.sympify(e)) for e in outs], np.asarray(p, dtype=float)[:n_par].copy())
    if with_checks:
        out = (*out, {name: tr(sp.sympify(e)) for name, e in checks.items()})
    return out
