"""The adaptive explicit Runge-Kutta step, written once: the template of every compiled
integration loop.

What the loop does, in order, for each step (Hairer, Norsett & Wanner, Solving ODEs I,
Sec. II.4-II.6 and II.10):
  0. the step budget (max_steps attempts), the step's length clipped to hmax and to the
     target (control.clip_step; its underflow stops the run);
  1. stages k_1..k_s (k_1 = f(t_n, y_n) carried over from the previous step); a stage
     whose field returns a singular status rejects the step and shrinks h by 4: a
     too-long trial step may leave the physical domain. Only if h underflows there (the
     trajectory itself reaches the singularity) does the run stop, with that status;
  2. y_{n+1} = y_n + h sum b_i k_i, optionally with compensated (Kahan) summation;
  3. the error: the scaled RMS norm of h sum e_i k_i with sc = atol + rtol max(|y_n|,
     |y_{n+1}|) (DOP853: Hairer's |err5|^2 / sqrt(|err5|^2 + 0.01 |err3|^2)); a failed
     test shrinks the step (the PI controller of Hairer's DOPRI5, control.py); near the
     Andoyer section the section's own step error joins it (sections.py);
  4. accepted: k_new = f(t_{n+1}, y_{n+1}) (the FSAL stage, or the extra stage `new`);
     a step whose ends misread the section is halved (the grazing rule); the projection
     onto known integrals every project_every-th accepted step (projection.py); the
     output times inside the step from the dense output (the extra dense stages only
     for steps that hold a sample, Clenshaw on the Chebyshev weights), projected too when
     projection is on; the section crossing located by Henon's trick and refined (rk.py);
     the stop after max_cross crossings; the next step's length (control.grow).

`loop_source(backend)` writes that loop as the text of one numba function. The
backend says how the data are held and what the run can do:
  - solvers/kernels/loop_kernel.py: the loop kernel, `rk_integrate`. Work arrays,
    the tableau as run-time arrays (every method shares one compiled kernel), the
    general field `fields.rhs` (or a case's generated field: field_modules), every
    option a run-time flag (fixed steps, steps clipped to each output time without dense
    output, sections, projection);
  - solvers/kernels/small.py: the small kernels. One case structure and one tableau:
    the state and the stages as local scalars, the tableau's coefficients as literals,
    the generated field inlined at each stage; sections or projection chosen when the
    kernel is written.
What the step decides from its numbers (the starting step, the step's length, the error
norm, the controller, the compensated sums, the section's crossing test) is control.py's
and sections.py's, called by both. So both give the same states, bit for bit, on the
same field (tests/test_small.py, tests/test_generated_integrator.py).

A backend gives the pieces the template places (each a list of lines, indented from 0,
or an expression): where the two differ in how they hold the data, not in what the step
does.
"""

from __future__ import annotations

from solvers.kernels import layout as L
from solvers.kernels.control import CROSSINGS_DONE, MAX_STEPS, STEP_UNDERFLOW
from solvers.kernels.sections import SECTION_NONE

IND = "    "


def indent(lines, depth: int = 1) -> list[str]:
    """The lines one block (or `depth` blocks) further in."""
    return [IND * depth + x for x in lines]


class Lines:
    """The text being written: lines at an indentation depth."""

    def __init__(self):
        self.out: list[str] = []

    def add(self, depth: int, lines) -> None:
        pad = IND * depth
        self.out += [pad + x if x else x for x in lines]

    def text(self) -> str:
        return "\n".join(self.out) + "\n"


def loop_source(b) -> str:
    """The text of the integration loop on the backend `b` (module docstring)."""
    OK = L.OK
    o = Lines()
    o.add(0, b.header())
    o.add(1, b.unpack())
    o.add(1, ["for i in range(stats.shape[0]):", "    stats[i] = 0",
              "N = t_out.shape[0]", "t = t_out[0]", "t_end = t_out[N - 1]"])
    o.add(1, b.store_sample("0", end=False))
    o.add(1, [f"stats[{b.S_SAMPLES}] = 1", f"stats[{b.S_RHS}] = 1"])
    o.add(1, b.first_field())
    o.add(1, [f"if status != {OK} or N == 1:"])
    o.add(2, b.finish())
    o.add(1, b.counters())
    o.add(1, b.first_step())
    o.add(1, b.options_init())
    o.add(1, b.loop_vars())
    o.add(1, ["t_comp = 0.0", "err_old = 1e-4", "rejected_last = False", "j = 1",
              "attempts = 0", "t_new = t"])
    o.add(1, ["while j < N:"])
    # 0. the budget and the step's length
    target_lines, target = b.target()
    o.add(2, [f"if attempts >= {b.max_steps}:", f"    status = {MAX_STEPS}", "    break",
              "attempts += 1", *target_lines,
              f"h, h_proposed, landing, ok = clip_step(h, hmax, t, {target})",
              "if not ok:", f"    status = {STEP_UNDERFLOW} if status == {OK} else status",
              "    break", f"status = {OK}"])
    # 1.-2. the stages (a singular one rejects the step, h / 4) and the new point
    reject_singular = ["status = st", *b.fixed_break(), *b.count("rejected"),
                       "rejected_last = True", "h = 0.25 * h", "continue"]
    o.add(2, b.stages(reject_singular))
    o.add(2, b.advance())
    # 3. the error test, and the field at the new point
    o.add(2, b.error())
    o.add(2, b.section_error())
    o.add(2, ["if err <= 1.0:",
              f"    t_new = step_end(t, h, t_comp, {target}, landing, compensated)"])
    o.add(3, b.new_stage(reject_singular))
    o.add(2, ["if not (err <= 1.0):", *indent(b.count("rejected")),
              "    rejected_last = True",
              f"    h = shrink(h, err, {b.shrink_exponent}, safety, {b.facmin})",
              "    continue"])
    # 4. accepted, unless its ends misread the section: then halved (the grazing rule,
    # down to GRAZE_H, where the pair of crossings is at round-off distance)
    if b.sections:
        o.add(2, ["from_start = 0", f"if code != {SECTION_NONE}:"])
        o.add(3, b.section_ends())
        o.add(3, [f"if {b.halve_guard}halve(from_start, h, t):",
                  *indent(b.count("rejected")), "    rejected_last = True",
                  "    h = 0.5 * h", "    continue"])
    o.add(2, [*b.count("accepted"),
              "t_comp = time_compensation(t, h, t_comp, t_new, landing, compensated)"])
    o.add(2, b.projection())
    # the output times inside (t, t_new]: the end itself, or the dense output (the
    # extra dense stages once per step)
    o.add(2, ["extra_done = False", "while j < N and t_out[j] <= t_new:",
              "    if t_out[j] == t_new:"])
    o.add(4, b.store_sample("j", end=True))
    o.add(4, b.project_end_sample())
    o.add(3, ["else:", "    if not extra_done:"])
    o.add(5, b.extra_stages(["status = st", "break"]))
    o.add(5, ["extra_done = True"])
    o.add(4, ["x = 2.0 * (t_out[j] - t) / h - 1.0"])
    o.add(4, b.dense_sample())
    o.add(4, b.project_dense_sample())
    o.add(3, ["j += 1"])
    o.add(2, b.samples_done())
    o.add(2, [f"if status != {OK}:", "    break"])
    # the section crossing inside the step, then the step committed
    if b.sections:
        o.add(2, b.crossing())
    o.add(2, ["t = t_new"])
    o.add(2, b.commit())
    if b.sections:
        o.add(2, [f"if code != {SECTION_NONE} and {b.crossings} >= max_cross:",
                  f"    status = {CROSSINGS_DONE}", "    break"])
    o.add(2, b.next_step())
    o.add(2, ["rejected_last = False"])
    o.add(1, b.epilogue())
    return o.text()
