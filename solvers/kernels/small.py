"""Small kernels: one Runge-Kutta run per case structure and tableau, shaped by what the run
needs: the step's template (step.py) on `ScalarLoop`.

The loop kernel (loop_kernel.py) is the same template on work arrays, for every method
and option at run time; a case's generated integrator binds it to the case's field, a
long compile for each structure. A plain run (samples at the output times by dense
output, the step budget, the statuses) needs little of that. Here the run is written out
as straight-line numba code for one structure and one tableau:
  - the state, the stages and the dense-output weights are local scalars (`y_0`,
    `k3_5`, ...), no work arrays: LLVM keeps them in registers;
  - the field is the generated one (generate.field_body: the same expressions, in the same
    order, as the array field `field(p, y, dydt)`), as a function of scalars returning
    (status, d0, d1, ...), inlined by LLVM at each stage (forceinline);
  - the tableau's coefficients are literals with the zero terms dropped, every sum in the
    loop kernel's order (the order of its tableau loops; a dropped term is an exact zero).
What the step decides from its numbers is control.py's, as in the loop kernel. So a small
kernel gives the same states, bit for bit, as the generated integrator
(tests/test_generated_integrator.py; tests/test_small.py checks the agreement with the
general kernel on every case and the extremes): which compiled form runs a plain run
does not change its answer.

What it costs: numba's front end, not LLVM (bench/warmup_cost.py: of the first call of
plane/chaplygin-ball's dop853 kernel, type inference, lowering and SSA reconstruction take
most of the CPU time; docs/performance.md). So the kernel is written to be cheap to type:
the linear combinations are calls of small shared functions (ops_module: axpyN, linN,
dotN, chebN, putN, typed once per process and inlined by LLVM) instead of hundreds of
binary operators each resolved on its own, a singular stage leaves the step at once
(every stage's variables then dominate their uses: far fewer variables for numba's SSA
reconstruction to rewrite), and the error and starting-step norms are one expression
each, with the operations and their order unchanged.

    module = small_kernel(model, p, "dop853")
    status, t_stop = module.run(p, y0, t_out, max_steps, compensated, fopt, atol, Y,
                                y_stop, stats)
fopt and stats are rk.py's packed vectors (F_* and S_* indices).

With sections (small_kernel(..., sections=True): integrate(kernel="small") with a section,
a large Poincare map's runs), the template's section parts: the step control near the
Andoyer section, the halving of a step whose ends misread the section, the crossing
located and refined by rk.py's own code on the general field (compiled once for every
structure: a structure's kernel compiles in much less CPU time than with a copy of it),
the refusal of g = g0 + pi and the stop after max_cross crossings. s and ds/dt at a step's
end are carried to the next step's start, where the loop kernel evaluates them again (the
same bits). The state goes to small work vectors only where that code reads it.

    status, t_stop = module.run(p, y0, t_out, max_steps, compensated, fopt, atol, Y,
                                y_stop, stats, model, code, direction, max_cross, coef,
                                A, c, b, meth, cross_t, cross_y)

With projection (small_kernel(..., projection=True): integrate(kernel="small") with
project_codes), the template's projection: every project_every-th accepted step onto the
levels (projection.project, compiled once for every structure), the field again at the
projected point (the generated field, inlined), every sample projected too.

    status, t_stop = module.run(p, y0, t_out, max_steps, compensated, fopt, atol, Y,
                                y_stop, stats, model, proj_codes, proj_vals, project_every)
"""

from __future__ import annotations

import numpy as np

from solvers.kernels import baked, field_modules, generate, module_cache, rk, small_ops
from solvers.kernels import layout as L
from solvers.kernels.sections import SECTION_ANDOYER_G
from solvers.kernels.step import IND, indent, loop_source


class ScalarLoop:
    """The pieces of step.loop_source for a small kernel (module docstring): one
    structure, one tableau, sections or projection or neither."""

    S_SAMPLES, S_RHS = rk.S_SAMPLES, rk.S_RHS
    max_steps = "max_steps"
    facmin = "facmin"
    halve_guard = ""
    crossings = "n_cross"
    PROJ = "proj_codes, proj_vals, wG, wM, wr, wlam, wyc"

    def __init__(self, model: int, p, method: str, tab, sections: bool = False,
                 projection: bool = False):
        if sections and projection:
            raise ValueError("a small kernel has sections or projection, not both")
        A, _c, b, E, P, meth = (np.asarray(x) for x in tab)   # the generated field ignores t
        self.s, self.new, self.errkind, self.order, self.q = (int(x) for x in meth[:5])
        if P.shape[0] == 0:
            raise ValueError(f"{method} has no dense output: no small kernel")
        self.A, self.b, self.E, self.P = A, b, E, P
        self.S = A.shape[0]
        self.model, self.p, self.method = model, p, method
        self.sections, self.projected = sections, projection
        self.params, state, self.body = generate.field_body(model, p)
        self.n = len(state)
        self.state = state
        self.R = range(self.n)
        self.pnames = [f"P_{x.name}" for x in self.params]
        self.shrink_exponent = small_ops.lit(-1.0 / (self.q + 1))
        # the new point's field: the FSAL (or extra) stage, or the field again after a
        # projection
        self.fnew = ([f"fn{m}" for m in self.R] if projection else
                     [f"k{self.new}_{m}" for m in self.R])

    # --- names and small pieces -----------------------------------------------------
    def call(self, args):     # the field at the scalars args
        return f"fs({', '.join([*self.pnames, *args])})"

    def kv(self, i):
        return [f"k{i}_{m}" for m in self.R]

    def put(self, arr, names):    # one call: typed once per kernel, not n item assignments
        return f"put{self.n}({arr}, {', '.join(names)})"

    def put_y(self):
        return self.put("wy", [f"y_{m}" for m in self.R])

    def put_f0(self):
        return self.put("wf0", [f"k0_{m}" for m in self.R])

    def put_yn(self):
        return self.put("wyn", [f"yn{m}" for m in self.R])

    def stage(self, i, fail):
        """Stage i, then `fail` (the lines run when its field is singular) under `if st !=
        OK`: each stage's failure leaves at once, so every later stage's definitions
        dominate their uses (numba's SSA reconstruction then keeps them as they are)."""
        lines = []
        for m in self.R:
            c = small_ops.call("axpy", [f"y_{m}", "h"],
                      small_ops.terms(self.A[i, :i], [f"k{j}_{m}" for j in range(i)]))
            lines.append(f"z{i}_{m} = {c or f'y_{m} + h * (0.0)'}")
        lines.append("n_rhs += 1")
        lines.append(f"st, {', '.join(self.kv(i))} = "
                     f"{self.call([f'z{i}_{m}' for m in self.R])}")
        lines.append(f"if st != {L.OK}:")
        return lines + indent(fail)

    # --- the pieces step.loop_source places -------------------------------------------
    def header(self):
        n = self.n
        key = generate.structure(self.model, self.p)
        zeros = ", ".join(["0.0"] * n)
        ops = small_ops.ops_module().__name__
        out = [f'"""Generated by solvers/kernels/small.py: {self.method}, structure {key!r}."""',
               "", "import numba", "import numpy as np", "",
               f"from {ops} import *  # noqa: F403 (axpyN, linN, dotN, chebN)",
               "from solvers.kernels.control import (  # noqa: F401 (the step control, once)",
               "    advance, clip_step, crosses, error_norm, first_guess, first_step,",
               "    first_step_singular, grow, halve, shrink, step_end, time_compensation)",
               *(["from solvers.kernels.rk import locate_crossing, refine_crossing  # noqa: F401",
                  "from solvers.kernels.sections import (  # noqa: F401",
                  "    crossing_kind, section_accept, section_slope, section_step_error)"]
                 if self.sections else []),
               *(["from solvers.kernels.projection import project  # noqa: F401"]
                 if self.projected else []),
               "",
               "# forceinline: LLVM inlines the field at each stage (typed once; numba's own",
               "# inline='always' retyped it at every call site: twice the compile, same speed)",
               "inline = numba.njit(cache=True, error_model='numpy', nogil=True, "
               "forceinline=True)",
               "kernel = numba.njit(cache=True, error_model='numpy', nogil=True)", "", "",
               "@inline",
               f"def fs({', '.join(x.name for x in [*self.params, *self.state])}):",
               f'{IND}"""The generated field (generate.field_body) on scalars: (status, '
               'dy/dt)."""']
        ds = ", ".join(f"d{i}" for i in range(n))
        for kind, what in self.body:
            if kind == "let":
                out.append(f"{IND}{what}")
            elif what[1] == L.SING_NONFINITE:
                # the last check (non-finite derivatives) returns the derivatives with its
                # status, not zeros: a caller that sees a status other than OK uses none of
                # them (a stage is rejected, the start stops), so the bits are the same, and
                # the derivatives do not wait on the check (returning zeros made LLVM select
                # each of them on the sum of all, a slower field call: bench/limit.py --gap,
                # docs/performance.md)
                out += [f"{IND}if {what[0]}:", f"{IND}    return {what[1]}, {ds}"]
            else:
                out += [f"{IND}if {what[0]}:", f"{IND}    return {what[1]}, {zeros}"]
        out.append(f"{IND}return {L.OK}, {ds}")
        sec_args = (", model, code, direction, max_cross, coef, tabA, tabc, tabb, meth, "
                    "cross_t, cross_y" if self.sections else
                    ", model, proj_codes, proj_vals, project_every" if self.projected else "")
        return [*out, "", "", "@kernel",
                "def run(p, ya, t_out, max_steps, compensated, fopt, atol, Y, y_stop, stats"
                f"{sec_args}):",
                f'{IND}"""rk.rk_integrate for a plain run (see the module docstring): returns '
                '(status, t_stop)."""']

    def unpack(self):
        o = [f"{pn} = p[{generate.SLOT_NAMES.index(x.name)}]"
             for x, pn in zip(self.params, self.pnames, strict=True)]
        for m in self.R:
            o += [f"y_{m} = ya[{m}]", f"at_{m} = atol[{m}]"]
        return [*o, f"rtol = fopt[{rk.F_RTOL}]", f"hmax = fopt[{rk.F_HMAX}]",
                    f"safety = fopt[{rk.F_SAFETY}]", f"facmin = fopt[{rk.F_FACMIN}]",
                    f"facmax = fopt[{rk.F_FACMAX}]", f"beta = fopt[{rk.F_BETA}]",
                    f"expo = {small_ops.lit(1.0 / (self.q + 1))} - 0.75 * beta"]

    def store_sample(self, j, end):
        return [f"Y[{j}, {m}] = {'yn' if end else 'y_'}{m}" for m in self.R]

    def first_field(self):
        return [f"status, {', '.join(self.kv(0))} = {self.call([f'y_{m}' for m in self.R])}"]

    def finish(self):
        return [*(f"y_stop[{m}] = y_{m}" for m in self.R), "return status, t"]

    def counters(self):
        # the counters in locals, written to stats once at the end: no store per stage or
        # step (the kernel's spills and the stats array could collide in the store
        # buffer; which address stats gets is the caller's)
        return ["n_rhs = 1", "n_acc = 0", "n_rej = 0"]

    def first_step(self):
        """Hairer's starting step: rk.initial_step's sums, each one expression in its
        order (0.0 + t_0 + t_1 + ...); the step from them: control.py."""
        R, n = self.R, self.n
        return [f"if fopt[{rk.F_H}] > 0.0:", f"    h = fopt[{rk.F_H}]", "else:",
                *indent(["span = t_end - t",
                          *(f"s0_{m} = at_{m} + rtol * abs(y_{m})" for m in R),
                          f"q0 = 0.0 + {' + '.join(f'(y_{m} / s0_{m}) ** 2' for m in R)}",
                          f"q1 = 0.0 + {' + '.join(f'(k0_{m} / s0_{m}) ** 2' for m in R)}",
                          f"h0, d1 = first_guess(q0, q1, {n}, span)",
                          *(f"z0_{m} = y_{m} + h0 * k0_{m}" for m in R),
                          "n_rhs += 1",
                          f"st, {', '.join(f'f1_{m}' for m in R)} = "
                          f"{self.call([f'z0_{m}' for m in R])}",
                          f"if st != {L.OK}:", "    h = first_step_singular(h0, hmax)",
                          "else:",
                          "    q2 = 0.0 + "
                          f"{' + '.join(f'((f1_{m} - k0_{m}) / s0_{m}) ** 2' for m in R)}",
                          f"    h = first_step(h0, d1, q2, {n}, "
                          f"{small_ops.lit(1.0 / (self.order + 1))}, span, hmax)"])]

    def options_init(self):
        n, S = self.n, self.S
        o = []
        if self.sections:   # the section code's work vectors (at crossings only)
            o += [f"nst = meth[{rk.M_STAGES}]", f"qord = meth[{rk.M_ERRORDER}]",
                  f"wy = np.empty({n})", f"wf0 = np.empty({n})", f"wyn = np.empty({n})",
                  f"wf1 = np.empty({n})", f"wgrad = np.empty({n})", f"wytmp = np.empty({n})",
                  f"wfb = np.empty({n})", f"wK = np.zeros(({S}, {n}))",
                  f"wKH = np.empty((nst, {n + 1}))", f"wz0 = np.empty({n + 1})",
                  f"wz = np.empty({n + 1})", f"wztmp = np.empty({n + 1})",
                  # the crossings' field calls are counted in stats by rk.py's code (the
                  # start's call is in n_rhs)
                  f"stats[{rk.S_RHS}] = 0",
                  # (sa, da): s and ds/dt at the step's start, (sb, db) at its end,
                  # carried to the next step (the loop kernel evaluates each twice: the
                  # same bits)
                  "n_cross = 0", "sa = da = sb = db = 0.0",
                  f"if code != {rk.SECTION_NONE}:", f"    {self.put_y()}",
                  f"    {self.put_f0()}", "    sa, da = section_slope(code, wy, wf0, coef, wgrad)"]
        if self.projected:  # the projection's work arrays (projection.project)
            o += ["nproj = proj_codes.shape[0]", f"wyn = np.empty({n})",
                  f"wG = np.empty((nproj, {n}))", "wM = np.empty((nproj, nproj))",
                  "wr = np.empty(nproj)", "wlam = np.empty(nproj)",
                  f"wyc = np.empty({n}, dtype=np.complex128)", "projected = False"]
        return o

    def loop_vars(self):
        R = self.R
        return [f"{' = '.join([*(f'cm{m}' for m in R), *(f'cn{m}' for m in R)])} = 0.0"]

    def target(self):
        return [], "t_end"

    def fixed_break(self):
        return []

    def count(self, what):
        return ["n_rej += 1" if what == "rejected" else "n_acc += 1"]

    def stages(self, reject):
        return [x for i in range(1, self.s) for x in self.stage(i, reject)]

    def advance(self):
        # d = h sum b_i k_i (+ the carried compensation), ynew = y + d; cn (the new
        # compensation) is only kept when compensated
        d = [small_ops.call("lin", ["h"], small_ops.terms(self.b, [f"k{j}_{m}"
                                                                     for j in range(self.s)]))
             for m in self.R]
        return [f"yn{m}, cn{m} = advance(y_{m}, {d[m]}, cm{m}, compensated)" for m in self.R]

    def error(self):
        """control.error_sums' sums, each one expression in its order (0.0 + t_0 + ...);
        the norm from them: control.error_norm."""
        o, R, E = [], self.R, self.E
        dop853 = self.errkind == rk.ERR_DOP853
        for m in R:
            names = [f"k{j}_{m}" for j in range(E.shape[1])]
            o += [f"sc{m} = at_{m} + rtol * max(abs(y_{m}), abs(yn{m}))",
                  f"ea{m} = {small_ops.call('dot', [], small_ops.terms(E[0], names))}"]
            if dop853:
                o += [f"eb{m} = {small_ops.call('dot', [], small_ops.terms(E[1], names))}"]
        o.append(f"e1 = 0.0 + {' + '.join(f'(ea{m} / sc{m}) ** 2' for m in R)}")
        o.append(f"e2 = 0.0 + {' + '.join(f'(eb{m} / sc{m}) ** 2' for m in R)}"
                 if dop853 else "e2 = 0.0")
        return [*o, f"err = error_norm(e1, e2, h, {self.n}, {self.errkind})"]

    def section_error(self):
        if not self.sections:
            return []
        return [f"if code == {SECTION_ANDOYER_G}:", f"    {self.put_y()}", f"    {self.put_yn()}",
                "    err = max(err, section_step_error(wy, wyn, coef, qord))"]

    def new_stage(self, reject):
        if self.new < self.s:
            return []
        return ["n_rhs += 1",
                f"st, {', '.join(self.kv(self.new))} = "
                f"{self.call([f'yn{m}' for m in self.R])}",
                f"if st != {L.OK}:", *indent(reject)]

    def section_ends(self):
        return [self.put_yn(), self.put("wf1", self.kv(self.new)),
                "sb, db = section_slope(code, wyn, wf1, coef, wgrad)",
                "from_start = crossing_kind(sa, da, sb, db, h, direction)"]

    def projection(self):
        if not self.projected:
            return []
        R = self.R
        return ["projected = nproj > 0 and n_acc % project_every == 0",
                "if projected:", f"    {self.put_yn()}",
                f"    status = project(model, p, wyn, {self.PROJ})",
                f"    if status != {L.OK}:", "        break",
                *(f"    yn{m} = wyn[{m}]" for m in R), *(f"    cn{m} = 0.0" for m in R),
                "    n_rhs += 1",
                f"    status, {', '.join(self.fnew)} = {self.call([f'yn{m}' for m in R])}",
                f"    if status != {L.OK}:", "        break", "else:",
                *(f"    fn{m} = k{self.new}_{m}" for m in R)]

    def project_end_sample(self):
        if not self.projected:
            return []
        return ["if nproj > 0 and not projected:",
                f"    status = project(model, p, Y[j], {self.PROJ})",
                f"    if status != {L.OK}:", "        break"]

    def extra_stages(self, fail):
        return [x for i in range(max(self.s, self.new + 1), self.S)
                for x in self.stage(i, fail)]

    def dense_sample(self):
        """Clenshaw on the Chebyshev weights (the loop kernel's recurrence), then the
        sample."""
        P = self.P
        rows = [i for i in range(self.S) if np.any(P[i] != 0.0)]
        o = ["x2 = 2.0 * x"]
        o += [f"w{i} = cheb{P.shape[1]}(x, x2, {', '.join(small_ops.lit(v) for v in P[i])})"
              for i in rows]
        for m in self.R:
            c = small_ops.call("axpy", [f"y_{m}", "h"], [(f"w{i}", f"k{i}_{m}") for i in rows])
            o.append(f"Y[j, {m}] = {c or f'y_{m} + h * (0.0)'}")
        return o

    def project_dense_sample(self):
        if not self.projected:
            return []
        # interpolated samples join the projected trajectory
        return ["if nproj > 0:", f"    status = project(model, p, Y[j], {self.PROJ})",
                f"    if status != {L.OK}:", "        break"]

    def samples_done(self):
        return []

    def crossing(self):
        """The crossing inside (t, t_new], located and refined by rk.py's code."""
        n = self.n
        loc = ("tabA, tabc, tabb, nst, code, coef, wKH, wz0, wz, wztmp, wytmp, wfb, wgrad, "
               "stats")
        return [f"if code != {rk.SECTION_NONE}:", "    if crosses(sa, sb, direction):",
                *indent([self.put_y(), self.put_f0(), "kc = n_cross",
                          "if from_start != -1:",
                          f"    status = locate_crossing(model, p, t, wy, wf0, sa, {loc})",
                          "else:",
                          f"    status = locate_crossing(model, p, t_new, wyn, wf1, sb, {loc})",
                          f"if status != {L.OK}:", "    break",
                          self.put("wK[0]", self.kv(0)),
                          "refine_crossing(model, p, t, wy, t_new, tabA, tabc, tabb, nst, "
                          "code, coef, wK, wytmp, wKH, wz0, wz, wztmp, wgrad, stats)",
                          "if section_accept(code, wz, coef):", f"    cross_t[kc] = wz[{n}]",
                          f"    for m in range({n}):", "        cross_y[kc, m] = wz[m]",
                          "    n_cross = kc + 1"], 2),
                "    sa = sb", "    da = db"]

    def commit(self):
        o = []
        for m in self.R:
            o += [f"y_{m} = yn{m}", f"k0_{m} = {self.fnew[m]}"]
        return [*o, "if compensated:", *(f"    cm{m} = cn{m}" for m in self.R)]

    def next_step(self):
        return ["h, err_old = grow(h, err, err_old, expo, beta, safety, facmin, facmax, "
                "rejected_last, landing, h_proposed)"]

    def epilogue(self):
        # every exit of the loop has the samples written so far in j (S_SAMPLES);
        # with sections, the crossings' own field calls were counted in stats by rk.py's
        # code
        sec = self.sections
        return [f"stats[{rk.S_ACCEPTED}] = n_acc", f"stats[{rk.S_REJECTED}] = n_rej",
                f"stats[{rk.S_RHS}] = " + (f"stats[{rk.S_RHS}] + n_rhs" if sec else "n_rhs"),
                f"stats[{rk.S_SAMPLES}] = j",
                *([f"stats[{rk.S_CROSSINGS}] = n_cross"] if sec else []),
                *(f"y_stop[{m}] = y_{m}" for m in self.R), "return status, t"]


def kernel_source(model: int, p, method: str, tab, sections: bool = False,
                  projection: bool = False) -> str:
    """The module text: `fs` (the scalar field) and `run` (the plain integration;
    sections: with the section crossings; projection: with the projection onto
    the levels of integrals; module docstring): step.py's template on ScalarLoop."""
    return loop_source(ScalarLoop(model, p, method, tab, sections, projection))


def module_name(model: int, p, method: str, sections: bool = False,
                projection: bool = False) -> str:
    """small_<structure and sources hash>_<tableau hash>[_sec|_proj]: any edit of
    solvers/kernels (module_cache.sources_hash) or of the tableau regenerates it."""
    tabs = baked.baked_tableaux((method,))
    return (f"small_{field_modules.module_name(model, p)[4:]}_{method}_"
            f"{baked.tableaux_stamp(tabs)[:10]}"
            f"{'_sec' if sections else '_proj' if projection else ''}")


def small_kernel(model: int, p, method: str = "dop853", sections: bool = False,
                 projection: bool = False):
    """The small kernel module of the case's structure and the tableau `method` (one of
    those the integrate layer provides: baked.set_provider), written on first use and
    compiled on its first call (then numba's on-disk cache)."""
    if model not in generate.GENERATED_MODELS:
        raise ValueError(f"no small kernel for model {model}")
    tab = baked.baked_tableaux((method,))[method]
    small_ops.ops_module()    # imported by name by the kernel's text, maybe on disk already
    return module_cache.cached_module(
        module_name(model, p, method, sections, projection),
        lambda: kernel_source(model, p, method, tab, sections, projection))
