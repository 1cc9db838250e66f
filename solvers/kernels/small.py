"""Small kernels: one Runge-Kutta run per case structure and tableau, shaped by what a plain
run needs.

The generated integrator (field_modules.generated_integrator) is the general rk.py kernel
specialised per structure: sections, projection, Henon steps, compensated sums, clipped
and fixed steps, all compiled for every structure (a long compile each). A plain run
(samples at the output times by dense output, the step budget, the statuses) needs none
of that. Here that run is written out as straight-line numba code for one structure and
one tableau:
  - the state, the stages and the dense-output weights are local scalars (`y_0`,
    `k3_5`, ...), no work arrays: LLVM keeps them in registers;
  - the field is the generated one (generate.field_body: the same expressions, in the same
    order, as the array field `field(p, y, dydt)`), as a function of scalars returning
    (status, d0, d1, ...), inlined by LLVM at each stage (forceinline);
  - the tableau's coefficients are literals with the zero terms dropped, every sum in
    rk.py's order (the order of its tableau loops).
The step is rk.py's step for the plain case (no section, no projection, not fixed, dense
output on; compensated sums are a run-time flag): what differs is written here, the
scalar state, the stages (a stage with a singular status rejects the step and shrinks h
by 4), the unrolled sums of the error estimates, the FSAL stage, the extra dense stages
only for steps that hold a sample, Clenshaw on the Chebyshev weights and the step budget
(max_steps attempts); what the step decides from those numbers is control.py's, the
functions rk.py calls too (Hairer's starting step, the step's length and its underflow,
the error norm, the PI controller and its clamps, the compensated sums, the section's
crossing test), inlined by LLVM. So a small kernel gives the same states, bit for bit, as
the generated integrator (rk.py's loops on the same field;
tests/test_generated_integrator.py checks it, tests/test_small.py the agreement with the
general kernel on every case and the extremes): which compiled form runs a plain run
does not change its answer.

What it costs: numba's front end, not LLVM (bench/warmup_cost.py passes: of the first call
of plane/chaplygin-ball's dop853 kernel, type inference, lowering and SSA reconstruction
take most of the CPU time, LLVM a small part; docs/performance.md). So the kernel is written
to be cheap to type: the linear
combinations are calls of small shared functions (ops_module: axpyN, linN, dotN, chebN,
typed once per process and inlined by LLVM) instead of hundreds of binary operators each
resolved on its own, a singular stage leaves the step at once (every stage's variables
then dominate their uses: far fewer variables for numba's SSA reconstruction to rewrite),
and the error and starting-step norms are one expression each. The operations and their
order are unchanged (tests/test_small.py: the same bits as the loop kernel), and that
first call costs less CPU (docs/performance.md). The field is typed once and
inlined by LLVM (forceinline: numba's own inline='always' retyped it at each of its call
sites, a much longer compile for the same speed).

    module = small_kernel(model, p, "dop853")
    status, t_stop = module.run(p, y0, t_out, max_steps, compensated, fopt, atol, Y,
                                y_stop, stats)
fopt and stats are rk.py's packed vectors (F_* and S_* indices).

With sections (small_kernel(..., sections=True); integrate(kernel="small") with a section,
a large Poincare map's runs): the same step plus rk.py's section code, in rk.py's order:
the step control near the Andoyer section (section_step_error in the error norm), the
halving of a step whose ends misread the section (crossing_kind, the grazing rule down to
GRAZE_H), Henon's location of a crossing from the end s runs monotonically from and its
Newton refinement (locate_crossing, refine_crossing), the refusal of g = g0 + pi, and
the stop after max_cross crossings (CROSSINGS_DONE). s and ds/dt at a step's end are
carried to the next step's start, where rk.py evaluates them again (the same bits). The
state goes to small work vectors only where that code reads it. The crossing code is
rk.py's own, on the general field: compiled once for every structure (a structure's
kernel then compiles in much less CPU time than with the generated field's copy of it),
so the steps, rejections, field calls and samples are the generated integrator's bit
for bit and the crossings agree with its to round-off (tests/test_generated_integrator.py).

    status, t_stop = module.run(p, y0, t_out, max_steps, compensated, fopt, atol, Y,
                                y_stop, stats, model, code, direction, max_cross, coef,
                                A, c, b, meth, cross_t, cross_y)

With projection (small_kernel(..., projection=True); integrate(kernel="small") with
project_codes): the same step plus rk.py's projection, in rk.py's order: every
project_every-th accepted step its end is moved onto the levels (projection.project, the
loop kernel's own code on the integrals' kernels, compiled once for every structure), the
compensation reset and the field evaluated again there (the generated field, inlined); a
sample at a step's end that was not projected, and every interpolated sample, is
projected too. The generated integrator's bits (tests/test_generated_integrator.py).

    status, t_stop = module.run(p, y0, t_out, max_steps, compensated, fopt, atol, Y,
                                y_stop, stats, model, proj_codes, proj_vals, project_every)
"""

from __future__ import annotations

import numpy as np

from solvers.kernels import field_modules, generate, module_cache, rk
from solvers.kernels import layout as L
from solvers.kernels.sections import SECTION_ANDOYER_G


def _lit(x) -> str:
    return repr(float(x))


# The linear combinations of the step (a stage's argument, the solution's increment, the
# error estimates, the dense output and its Clenshaw weights) are written as calls of
# small functions of N terms, the same in every kernel (ops_module): numba types and
# lowers each of them once per process, and LLVM inlines them (forceinline), so a kernel's
# hundreds of sums cost a call each to type instead of 2N-1 binary operators, whose typing
# (numba's operator resolution, which tries NumPy's ufunc loops first) was most of the
# compile (bench/results/warmup.txt). The operations, their operands and their order are
# the ones written out before, so the results are the same bits.
OPS_MAX = 24


def ops_source(n_max: int = OPS_MAX) -> str:
    """The module of the combinations, N = 1..n_max terms:
      axpyN(y, h, a0, k0, ...) = y + h * (a0 * k0 + ...)   (a stage's argument, a sample)
      linN(h, a0, k0, ...)     = h * (a0 * k0 + ...)       (the increment d)
      dotN(a0, k0, ...)        = a0 * k0 + ...              (an error estimate)
      chebN(x, x2, P0, ...)    = Clenshaw's sum of P0..P_{N-1} at x (rk.py's recurrence,
                                 b_N = b_{N+1} = 0 written as the literal 0.0 operands);
      putN(a, v0, ...)         : a[0] = v0, ... (a vector from scalars)."""
    out = ['"""Generated by solvers/kernels/small.py (ops_source)."""',
           "", "import numba", "",
           "inline = numba.njit(cache=True, error_model='numpy', nogil=True, forceinline=True)",
           ""]
    for n in range(1, n_max + 1):
        ak = [f"a{i}, k{i}" for i in range(n)]
        s = " + ".join(f"a{i} * k{i}" for i in range(n))
        out += ["", "@inline", f"def axpy{n}(y, h, {', '.join(ak)}):",
                f"    return y + h * ({s})",
                "", "@inline", f"def lin{n}(h, {', '.join(ak)}):", f"    return h * ({s})",
                "", "@inline", f"def dot{n}({', '.join(ak)}):", f"    return {s}"]
    for n in range(1, n_max + 1):    # putN(a, v0, ...): a[0] = v0, ... (the section code's
        vs = [f"v{i}" for i in range(n)]    # work vectors from the scalar state)
        out += ["", "@inline", f"def put{n}(a, {', '.join(vs)}):"]
        out += [f"    a[{i}] = v{i}" for i in range(n)]
    for n in range(2, n_max + 1):
        out += ["", "@inline", f"def cheb{n}(x, x2, {', '.join(f'P{i}' for i in range(n))}):"]
        prev, prev2 = "0.0", "0.0"
        for k in range(n - 1, 0, -1):
            out.append(f"    c{k} = P{k} + x2 * {prev} - {prev2}")
            prev, prev2 = f"c{k}", prev
        out.append(f"    return P0 + x * {prev} - {prev2}")
    return "\n".join(out) + "\n"


def ops_module():
    """The combinations' module, one for every kernel (in the kernel cache, like them)."""
    import hashlib

    text = ops_source()
    name = f"small_ops_{hashlib.sha256(text.encode()).hexdigest()[:16]}"
    return module_cache.cached_module(name, lambda: text)


def _terms(coef, names) -> list[tuple[str, str]]:
    """(coefficient literal, name) of the nonzero coef, in order (a dropped term being an
    exact zero of rk.py's loop)."""
    return [(_lit(a), names[j]) for j, a in enumerate(coef) if a != 0.0]


def _call(fn: str, lead: list[str], terms) -> str:
    """fnN(lead..., a0, k0, ...) of the terms; None when there are none."""
    if not terms:
        return None
    if len(terms) > OPS_MAX:
        raise ValueError(f"{len(terms)} terms: more than OPS_MAX")
    return f"{fn}{len(terms)}({', '.join([*lead, *(x for t in terms for x in t)])})"


def kernel_source(model: int, p, method: str, tab, sections: bool = False,
                  projection: bool = False) -> str:
    """The module text: `fs` (the scalar field) and `run` (the plain integration;
    sections: with rk.py's section crossings; projection: with rk.py's projection onto
    the levels of integrals; module docstring)."""
    if sections and projection:
        raise ValueError("a small kernel has sections or projection, not both")
    A, _c, b, E, P, meth = (np.asarray(x) for x in tab)    # the generated field ignores t
    s, new, errkind, order, q = (int(x) for x in meth[:5])
    S = A.shape[0]
    if P.shape[0] == 0:
        raise ValueError(f"{method} has no dense output: no small kernel")
    params, state, body = generate.field_body(model, p)
    n = len(state)
    key = generate.structure(model, p)
    ind = "    "
    zeros = ", ".join(["0.0"] * n)
    out = [f'"""Generated by solvers/kernels/small.py: {method}, structure {key!r}."""',
           "", "import numba", "import numpy as np", "",
           f"from {ops_module().__name__} import *  # noqa: F403 (axpyN, linN, dotN, chebN)",
           "from solvers.kernels.control import (  # noqa: F401 (the step control, once)",
           "    advance, clip_step, crosses, error_norm, first_guess, first_step,",
           "    first_step_singular, grow, halve, shrink, step_end, time_compensation)",
           *(["from solvers.kernels.rk import locate_crossing, refine_crossing  # noqa: F401",
              "from solvers.kernels.sections import (  # noqa: F401",
              "    crossing_kind, section_accept, section_slope, section_step_error)"]
             if sections else []),
           *(["from solvers.kernels.projection import project  # noqa: F401"]
             if projection else []),
           "",
           "# forceinline: LLVM inlines the field at each stage (typed once; numba's own",
           "# inline='always' retyped it at every call site: twice the compile, same speed)",
           "inline = numba.njit(cache=True, error_model='numpy', nogil=True, forceinline=True)",
           "kernel = numba.njit(cache=True, error_model='numpy', nogil=True)", "", "",
           "@inline",
           f"def fs({', '.join([*(x.name for x in params), *(x.name for x in state)])}):",
           f'{ind}"""The generated field (generate.field_body) on scalars: (status, '
           'dy/dt)."""']
    ds = ", ".join(f"d{i}" for i in range(n))
    for kind, what in body:
        if kind == "let":
            out.append(f"{ind}{what}")
        elif what[1] == L.SING_NONFINITE:
            # the last check (non-finite derivatives) returns the derivatives with its
            # status, not zeros: a caller that sees a status other than OK uses none of
            # them (a stage is rejected, the start stops), so the bits are the same, and the
            # derivatives do not wait on the check (returning zeros made LLVM select each
            # of them on the sum of all, a slower field call: bench/limit.py --gap,
            # docs/performance.md)
            out += [f"{ind}if {what[0]}:", f"{ind}    return {what[1]}, {ds}"]
        else:
            out += [f"{ind}if {what[0]}:", f"{ind}    return {what[1]}, {zeros}"]
    out.append(f"{ind}return {L.OK}, {ds}")

    pnames = [f"P_{x.name}" for x in params]
    R = range(n)

    def call(args):     # `st, kX_0, ... = fs(params, args)`
        return f"fs({', '.join([*pnames, *args])})"

    def kv(i):
        return [f"k{i}_{m}" for m in R]

    def stage(i, ind2, fail):
        """Stage i, then `fail` (the lines run when its field is singular) under `if st !=
        OK`: each stage's failure leaves at once, so every later stage's definitions
        dominate their uses (numba's SSA reconstruction then keeps them as they are)."""
        lines = []
        for m in R:
            c = _call("axpy", [f"y_{m}", "h"], _terms(A[i, :i], [f"k{j}_{m}" for j in range(i)]))
            lines.append(f"{ind2}z{i}_{m} = {c or f'y_{m} + h * (0.0)'}")
        lines.append(f"{ind2}n_rhs += 1")
        lines.append(f"{ind2}st, {', '.join(kv(i))} = {call([f'z{i}_{m}' for m in R])}")
        lines.append(f"{ind2}if st != {L.OK}:")
        lines += [f"{ind2}    {x}" for x in fail]
        return lines

    fp = {name: f"fopt[{getattr(rk, 'F_' + name)}]" for name in
          ("RTOL", "H", "HMAX", "SAFETY", "FACMIN", "FACMAX", "BETA")}
    sec_args = (", model, code, direction, max_cross, coef, tabA, tabc, tabb, meth, "
                "cross_t, cross_y" if sections else
                ", model, proj_codes, proj_vals, project_every" if projection else "")
    i3 = ind * 3
    o = ["", "", "@kernel",
         "def run(p, ya, t_out, max_steps, compensated, fopt, atol, Y, y_stop, stats"
         f"{sec_args}):",
         f'{ind}"""rk.rk_integrate for a plain run (see the module docstring): returns '
         '(status, t_stop)."""']
    for x, pn in zip(params, pnames, strict=True):
        o.append(f"{ind}{pn} = p[{generate.SLOT_NAMES.index(x.name)}]")
    for m in R:
        o.append(f"{ind}y_{m} = ya[{m}]")
        o.append(f"{ind}at_{m} = atol[{m}]")
    o += [f"{ind}rtol = {fp['RTOL']}", f"{ind}hmax = {fp['HMAX']}",
          f"{ind}safety = {fp['SAFETY']}", f"{ind}facmin = {fp['FACMIN']}",
          f"{ind}facmax = {fp['FACMAX']}", f"{ind}beta = {fp['BETA']}",
          f"{ind}expo = {_lit(1.0 / (q + 1))} - 0.75 * beta",
          f"{ind}for i in range(stats.shape[0]):", f"{ind}    stats[i] = 0",
          f"{ind}N = t_out.shape[0]", f"{ind}t = t_out[0]", f"{ind}t_end = t_out[N - 1]"]
    o += [f"{ind}Y[0, {m}] = y_{m}" for m in R]
    o += [f"{ind}stats[{rk.S_SAMPLES}] = 1", f"{ind}stats[{rk.S_RHS}] = 1",
          f"{ind}status, {', '.join(kv(0))} = {call([f'y_{m}' for m in R])}",
          f"{ind}if status != {L.OK} or N == 1:"]
    o += [f"{ind}    y_stop[{m}] = y_{m}" for m in R]
    o += [f"{ind}    return status, t"]
    # the counters in locals, written to stats once at the end: no store per stage or step
    # (the kernel's spills and the stats array could collide in the store buffer; which
    # address stats gets is the caller's)
    o += [f"{ind}n_rhs = 1", f"{ind}n_acc = 0", f"{ind}n_rej = 0"]
    # Hairer's starting step (rk._initial_step's sums; the step from them: control.py)
    o += [f"{ind}if {fp['H']} > 0.0:", f"{ind}    h = {fp['H']}", f"{ind}else:"]
    i2 = ind * 2
    # the sums as one expression each, in rk.py's order (0.0 + t_0 + t_1 + ...)
    o += [f"{i2}span = t_end - t"]
    o += [f"{i2}s0_{m} = at_{m} + rtol * abs(y_{m})" for m in R]
    o += [f"{i2}q0 = 0.0 + {' + '.join(f'(y_{m} / s0_{m}) ** 2' for m in R)}",
          f"{i2}q1 = 0.0 + {' + '.join(f'(k0_{m} / s0_{m}) ** 2' for m in R)}",
          f"{i2}h0, d1 = first_guess(q0, q1, {n}, span)"]
    o += [f"{i2}z0_{m} = y_{m} + h0 * k0_{m}" for m in R]
    o += [f"{i2}n_rhs += 1",
          f"{i2}st, {', '.join(f'f1_{m}' for m in R)} = {call([f'z0_{m}' for m in R])}",
          f"{i2}if st != {L.OK}:", f"{i2}    h = first_step_singular(h0, hmax)", f"{i2}else:",
          f"{i2}    q2 = 0.0 + {' + '.join(f'((f1_{m} - k0_{m}) / s0_{m}) ** 2' for m in R)}",
          f"{i2}    h = first_step(h0, d1, q2, {n}, {_lit(1.0 / (order + 1))}, span, hmax)"]
    def put(arr, names):    # one call: typed once per kernel, not n item assignments
        return f"put{n}({arr}, {', '.join(names)})"

    # the scalar state and fields into the section and projection code's work vectors
    put_y, put_f0 = put("wy", [f"y_{m}" for m in R]), put("wf0", [f"k0_{m}" for m in R])
    put_yn = put("wyn", [f"yn{m}" for m in R])
    if sections:    # rk.py's work vectors of the section code (used at crossings only)
        o += [f"{ind}nst = meth[{rk.M_STAGES}]", f"{ind}qord = meth[{rk.M_ERRORDER}]",
              f"{ind}wy = np.empty({n})", f"{ind}wf0 = np.empty({n})",
              f"{ind}wyn = np.empty({n})", f"{ind}wf1 = np.empty({n})",
              f"{ind}wgrad = np.empty({n})", f"{ind}wytmp = np.empty({n})",
              f"{ind}wfb = np.empty({n})", f"{ind}wK = np.zeros(({S}, {n}))",
              f"{ind}wKH = np.empty((nst, {n + 1}))", f"{ind}wz0 = np.empty({n + 1})",
              f"{ind}wz = np.empty({n + 1})", f"{ind}wztmp = np.empty({n + 1})",
              # the crossings' field calls are counted in stats by rk.py's code (the
              # start's call is in n_rhs)
              f"{ind}stats[{rk.S_RHS}] = 0",
              # (sa, da): s and ds/dt at the step's start, (sb, db) at its end, carried
              # to the next step (rk.py evaluates each twice: the same bits)
              f"{ind}n_cross = 0", f"{ind}sa = da = sb = db = 0.0",
              f"{ind}if code != {rk.SECTION_NONE}:", f"{i2}{put_y}", f"{i2}{put_f0}",
              f"{i2}sa, da = section_slope(code, wy, wf0, coef, wgrad)"]
    if projection:  # rk.py's work arrays of the projection (projection.project)
        o += [f"{ind}nproj = proj_codes.shape[0]", f"{ind}wyn = np.empty({n})",
              f"{ind}wG = np.empty((nproj, {n}))", f"{ind}wM = np.empty((nproj, nproj))",
              f"{ind}wr = np.empty(nproj)", f"{ind}wlam = np.empty(nproj)",
              f"{ind}wyc = np.empty({n}, dtype=np.complex128)", f"{ind}projected = False"]
    proj = "proj_codes, proj_vals, wG, wM, wr, wlam, wyc"
    o += [f"{ind}{' = '.join([*(f'cm{m}' for m in R), *(f'cn{m}' for m in R)])} = 0.0",
          f"{ind}t_comp = 0.0",
          f"{ind}err_old = 1e-4", f"{ind}rejected_last = False", f"{ind}j = 1",
          f"{ind}attempts = 0", f"{ind}t_new = t",
          f"{ind}while j < N:",
          f"{i2}if attempts >= max_steps:", f"{i2}    status = {rk.MAX_STEPS}",
          f"{i2}    break", f"{i2}attempts += 1",
          f"{i2}h, h_proposed, landing, ok = clip_step(h, hmax, t, t_end)",
          f"{i2}if not ok:",
          f"{i2}    status = {rk.STEP_UNDERFLOW} if status == {L.OK} else status",
          f"{i2}    break", f"{i2}status = {L.OK}"]
    # 1.-2. the stages and the new point
    # a singular stage rejects the step and shrinks h by 4 (rk.py)
    reject = ["status = st", "n_rej += 1", "rejected_last = True",
              "h = 0.25 * h", "continue"]
    for i in range(1, s):
        o += stage(i, i2, reject)
    for m in R:     # rk.py: d = h sum b_i k_i (+ the carried compensation), ynew = y + d
        c = _call("lin", ["h"], _terms(b, [f"k{j}_{m}" for j in range(s)]))
        # cn (the new compensation) is only kept when compensated
        o += [f"{i2}yn{m}, cn{m} = advance(y_{m}, {c}, cm{m}, compensated)"]
    # 3. the error norm (control.error_sums' sums, each one expression in its order,
    # 0.0 + t_0 + t_1 + ...; the norm from them: control.error_norm)
    for m in R:
        names = [f"k{j}_{m}" for j in range(E.shape[1])]
        o += [f"{i2}sc{m} = at_{m} + rtol * max(abs(y_{m}), abs(yn{m}))",
              f"{i2}ea{m} = {_call('dot', [], _terms(E[0], names))}"]
        if errkind == rk.ERR_DOP853:
            o += [f"{i2}eb{m} = {_call('dot', [], _terms(E[1], names))}"]
    o.append(f"{i2}e1 = 0.0 + {' + '.join(f'(ea{m} / sc{m}) ** 2' for m in R)}")
    if errkind == rk.ERR_DOP853:
        o.append(f"{i2}e2 = 0.0 + {' + '.join(f'(eb{m} / sc{m}) ** 2' for m in R)}")
    else:
        o.append(f"{i2}e2 = 0.0")
    o.append(f"{i2}err = error_norm(e1, e2, h, {n}, {errkind})")
    if sections:    # rk.py: step control near the section (sections.py)
        o += [f"{i2}if code == {SECTION_ANDOYER_G}:", f"{i3}{put_y}", f"{i3}{put_yn}",
              f"{i3}err = max(err, section_step_error(wy, wyn, coef, qord))"]
    o += [f"{i2}if err <= 1.0:",
          f"{i2}    t_new = step_end(t, h, t_comp, t_end, landing, compensated)"]
    if new >= s:
        o += [f"{i2}    n_rhs += 1",
              f"{i2}    st, {', '.join(kv(new))} = {call([f'yn{m}' for m in R])}",
              f"{i2}    if st != {L.OK}:"]
        o += [f"{i2}        {x}" for x in reject]
    o += [f"{i2}if not (err <= 1.0):", f"{i2}    n_rej += 1",
          f"{i2}    rejected_last = True",
          f"{i2}    h = shrink(h, err, {_lit(-1.0 / (q + 1))}, safety, facmin)",
          f"{i2}    continue"]
    if sections:    # rk.py: a step whose ends misread the section is halved
        o += [f"{i2}from_start = 0", f"{i2}if code != {rk.SECTION_NONE}:", f"{i3}{put_yn}",
              f"{i3}{put('wf1', [f'k{new}_{m}' for m in R])}",
              f"{i3}sb, db = section_slope(code, wyn, wf1, coef, wgrad)",
              f"{i3}from_start = crossing_kind(sa, da, sb, db, h, direction)",
              f"{i3}if halve(from_start, h, t):",
              f"{i3}    n_rej += 1", f"{i3}    rejected_last = True", f"{i3}    h = 0.5 * h",
              f"{i3}    continue"]
    o += [f"{i2}n_acc += 1",
          f"{i2}t_comp = time_compensation(t, h, t_comp, t_new, landing, compensated)"]
    fnew = [f"k{new}_{m}" for m in R]
    if projection:  # rk.py: every project_every-th accepted step onto the levels, then
        fnew = [f"fn{m}" for m in R]    # the field again at the projected point
        o += [f"{i2}projected = nproj > 0 and n_acc % project_every == 0",
              f"{i2}if projected:", f"{i3}{put_yn}",
              f"{i3}status = project(model, p, wyn, {proj})",
              f"{i3}if status != {L.OK}:", f"{i3}    break"]
        o += [f"{i3}yn{m} = wyn[{m}]" for m in R] + [f"{i3}cn{m} = 0.0" for m in R]
        o += [f"{i3}n_rhs += 1", f"{i3}status, {', '.join(fnew)} = "
              f"{call([f'yn{m}' for m in R])}", f"{i3}if status != {L.OK}:", f"{i3}    break",
              f"{i2}else:"]
        o += [f"{i3}fn{m} = k{new}_{m}" for m in R]
    # outputs inside (t, t_new]: the dense stages once, Clenshaw per sample
    dense_rows = [i for i in range(S) if np.any(P[i] != 0.0)]
    ncheb = P.shape[1]
    o += [f"{i2}extra_done = False", f"{i2}while j < N and t_out[j] <= t_new:",
          f"{i3}if t_out[j] == t_new:"]
    o += [f"{i3}    Y[j, {m}] = yn{m}" for m in R]
    if projection:
        o += [f"{i3}    if nproj > 0 and not projected:",
              f"{i3}        status = project(model, p, Y[j], {proj})",
              f"{i3}        if status != {L.OK}:", f"{i3}            break"]
    o += [f"{i3}else:", f"{i3}    if not extra_done:"]
    i5 = i3 + ind * 2
    first = max(s, new + 1)
    for i in range(first, S):
        o += stage(i, i5, ["status = st", "break"])
    o += [f"{i5}extra_done = True", f"{i3}    x = 2.0 * (t_out[j] - t) / h - 1.0"]
    i4 = i3 + ind
    o.append(f"{i4}x2 = 2.0 * x")
    for i in dense_rows:     # Clenshaw (rk.py's recurrence)
        o.append(f"{i4}w{i} = cheb{ncheb}(x, x2, {', '.join(_lit(v) for v in P[i])})")
    for m in R:
        c = _call("axpy", [f"y_{m}", "h"], [(f"w{i}", f"k{i}_{m}") for i in dense_rows])
        o.append(f"{i4}Y[j, {m}] = {c or f'y_{m} + h * (0.0)'}")
    if projection:      # interpolated samples join the projected trajectory (rk.py)
        o += [f"{i4}if nproj > 0:", f"{i4}    status = project(model, p, Y[j], {proj})",
              f"{i4}    if status != {L.OK}:", f"{i4}        break"]
    o += [f"{i3}j += 1", f"{i2}if status != {L.OK}:", f"{i2}    break"]
    if sections:    # rk.py: the crossing inside (t, t_new], located and refined
        loc = ("tabA, tabc, tabb, nst, code, coef, wKH, wz0, wz, wztmp, wytmp, wfb, wgrad, "
               "stats")
        o += [f"{i2}if code != {rk.SECTION_NONE}:",
              f"{i3}if crosses(sa, sb, direction):",
              f"{i4}{put_y}", f"{i4}{put_f0}", f"{i4}kc = n_cross", f"{i4}if from_start != -1:",
              f"{i4}    status = locate_crossing(model, p, t, wy, wf0, sa, {loc})",
              f"{i4}else:",
              f"{i4}    status = locate_crossing(model, p, t_new, wyn, wf1, sb, {loc})",
              f"{i4}if status != {L.OK}:", f"{i4}    break"]
        o += [f"{i4}{put('wK[0]', [f'k0_{m}' for m in R])}"]
        o += [f"{i4}refine_crossing(model, p, t, wy, t_new, tabA, tabc, tabb, nst, code, "
              "coef, wK, wytmp, wKH, wz0, wz, wztmp, wgrad, stats)",
              f"{i4}if section_accept(code, wz, coef):", f"{i4}    cross_t[kc] = wz[{n}]",
              f"{i4}    for m in range({n}):", f"{i4}        cross_y[kc, m] = wz[m]",
              f"{i4}    n_cross = kc + 1", f"{i3}sa = sb", f"{i3}da = db"]
    o += [f"{i2}t = t_new"]
    for m in R:
        o += [f"{i2}y_{m} = yn{m}", f"{i2}k0_{m} = {fnew[m]}"]
    o.append(f"{i2}if compensated:")
    o += [f"{i2}    cm{m} = cn{m}" for m in R]
    if sections:
        o += [f"{i2}if code != {rk.SECTION_NONE} and n_cross >= max_cross:",
              f"{i2}    status = {rk.CROSSINGS_DONE}", f"{i2}    break"]
    o += [f"{i2}h, err_old = grow(h, err, err_old, expo, beta, safety, facmin, facmax, "
          "rejected_last, landing, h_proposed)",
          f"{i2}rejected_last = False"]
    # every exit of the loop has the samples written so far in j (rk.py's S_SAMPLES)
    # (with sections, the crossings' own field calls were counted in stats by rk.py's code)
    o += [f"{ind}stats[{rk.S_ACCEPTED}] = n_acc", f"{ind}stats[{rk.S_REJECTED}] = n_rej",
          f"{ind}stats[{rk.S_RHS}] = " + (f"stats[{rk.S_RHS}] + n_rhs"
                                          if sections else "n_rhs"),
          f"{ind}stats[{rk.S_SAMPLES}] = j"]
    if sections:
        o += [f"{ind}stats[{rk.S_CROSSINGS}] = n_cross"]
    o += [f"{ind}y_stop[{m}] = y_{m}" for m in R]
    o.append(f"{ind}return status, t")
    return "\n".join(out + o) + "\n"


def module_name(model: int, p, method: str, sections: bool = False,
                projection: bool = False) -> str:
    """small_<structure and sources hash>_<tableau hash>[_sec|_proj]: any edit of
    solvers/kernels (module_cache.sources_hash) or of the tableau regenerates it."""
    from solvers.kernels import baked

    tabs = baked.baked_tableaux((method,))
    return (f"small_{field_modules.module_name(model, p)[4:]}_{method}_"
            f"{baked.tableaux_stamp(tabs)[:10]}"
            f"{'_sec' if sections else '_proj' if projection else ''}")


def small_kernel(model: int, p, method: str = "dop853", sections: bool = False,
                 projection: bool = False):
    """The small kernel module of the case's structure and the tableau `method` (one of
    those the integrate layer provides: baked.set_provider), written on first use and
    compiled on its first call (then numba's on-disk cache)."""
    from solvers.kernels import baked

    if model not in generate.GENERATED_MODELS:
        raise ValueError(f"no small kernel for model {model}")
    tab = baked.baked_tableaux((method,))[method]
    ops_module()      # imported by name by the kernel's text, which may be on disk already
    return module_cache.cached_module(
        module_name(model, p, method, sections, projection),
        lambda: kernel_source(model, p, method, tab, sections, projection))
