"""A run's options as typed records, packed into the compiled kernels' arrays only at the call.

    opts = RunOptions(method="vern9", rtol=1e-12, section=Section(coef=(0, 0, 0, 1, 0, 0)),
                      max_crossings=50, projection=Projection(codes=(ENERGY,)))
    iopt, fopt = opts.packed()          # rk.py's vectors, by its I_* and F_* indices

What a run is asked to do, by theme:
  the method      `method`, a tableau of solvers.integrate.tableaux (or a collocation
                  method with h_fixed);
  step control    rtol, atol (a number or one per component), `control` (StepControl:
                  the PI controller's constants, h0, h_max), or `h_fixed` (no control);
  what to save    `dense_output` (samples interpolated; False: steps clipped to land on
                  them), `compensated` sums;
  sections        `section` (Section) and `max_crossings`, after which the run stops;
  projection      `projection` (Projection: integral codes, their levels, how often);
  budget          `max_steps` attempted steps.
The records check their own values when made (ValueError, nothing runs); integrate() and
integrate_ensemble() make one from their keywords. The kernels take plain arrays: the
packing (`packed`, `fopt`) is written here once, by the kernels' index names, and used only
where the compiled call is made.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from solvers.kernels import rk


@dataclass(frozen=True)
class StepControl:
    """Step-size control (Hairer's DOPRI5 PI controller): h_new = h * clip(safety *
    err^-(1/(q+1) - 0.75 beta) * err_prev^beta, fac_min, fac_max); beta = 0 gives the
    classical controller. h0 = 0: Hairer's automatic initial step."""

    safety: float = 0.9
    fac_min: float = 0.2
    fac_max: float = 10.0
    beta: float = 0.04
    h0: float = 0.0
    h_max: float = np.inf


@dataclass(frozen=True)
class Section:
    """The section s(y) = coef . y - offset = 0, crossed with s increasing (direction
    +1), decreasing (-1) or either (0). Crossings are located by Henon's trick."""

    coef: tuple
    offset: float = 0.0
    direction: int = 1
    code: int = rk.SECTION_LINEAR

    def packed(self, n):
        c = np.zeros(n + 1)
        c[:n] = np.asarray(self.coef, dtype=np.float64)
        c[n] = self.offset
        return c


@dataclass(frozen=True)
class Projection:
    """Projection onto the levels of first integrals: the integral codes
    (solvers.kernels.integrals, or rk.TEST_* for the test models), their levels (None:
    their values at the start, filled in by the run), every `every`-th accepted step."""

    codes: tuple
    values: tuple | None = None
    every: int = 1

    def __post_init__(self):
        if self.values is not None and len(self.values) != len(self.codes):
            raise ValueError("one project_value per code, and project_every >= 1")
        if not self.every >= 1:
            raise ValueError("one project_value per code, and project_every >= 1")


def fopt(rtol: float, control: StepControl, h: float | None = None) -> tuple:
    """rk.py's float options (F_* indices) of a run: its tolerance and step control, and
    h (the fixed step, or else control.h0, the first step)."""
    out = [0.0] * 7
    out[rk.F_RTOL] = float(rtol)
    out[rk.F_H] = float(control.h0 if h is None else h)
    out[rk.F_HMAX] = float(control.h_max)
    out[rk.F_SAFETY] = float(control.safety)
    out[rk.F_FACMIN] = float(control.fac_min)
    out[rk.F_FACMAX] = float(control.fac_max)
    out[rk.F_BETA] = float(control.beta)
    return tuple(out)


@dataclass(frozen=True)
class RunOptions:
    """What a run of the compiled integrators is asked to do (module docstring)."""

    method: str = "dop853"
    rtol: float = 1e-10
    atol: float | tuple = 1e-12
    control: StepControl = StepControl()
    h_fixed: float | None = None
    dense_output: bool = True
    compensated: bool = False
    section: Section | None = None
    max_crossings: int = 100_000
    projection: Projection | None = None
    max_steps: int = 10_000_000

    def __post_init__(self):
        if self.h_fixed is not None and not self.h_fixed > 0:
            raise ValueError("h_fixed must be positive")

    @property
    def fixed(self) -> bool:
        return self.h_fixed is not None

    @property
    def crossings(self) -> int:
        """The crossings' buffer length: max_crossings with a section (at least 1)."""
        return 1 if self.section is None else max(1, int(self.max_crossings))

    def packed(self) -> tuple[tuple, tuple]:
        """(iopt, fopt): rk.py's int and float option vectors (I_* and F_* indices), as
        tuples (the caller makes the arrays, or looks them up: integrator._option_arrays)."""
        sec = self.section
        iopt = [0] * 7
        iopt[rk.I_MAX_STEPS] = int(self.max_steps)
        iopt[rk.I_COMPENSATED] = int(self.compensated)
        iopt[rk.I_PROJECT_EVERY] = 1 if self.projection is None else int(self.projection.every)
        iopt[rk.I_SECTION] = rk.SECTION_NONE if sec is None else sec.code
        iopt[rk.I_DIRECTION] = 0 if sec is None else int(np.sign(sec.direction))
        iopt[rk.I_MAX_CROSS] = self.crossings
        iopt[rk.I_FIXED] = int(self.fixed)
        return tuple(iopt), fopt(self.rtol, self.control, self.h_fixed)

    def atol_vector(self, n: int) -> np.ndarray:
        """atol as the kernels' vector of n components."""
        if isinstance(self.atol, float | int):
            out = np.empty(n)
            out[:] = self.atol
            return out
        return np.array(np.broadcast_to(np.asarray(self.atol, dtype=np.float64), (n,)))
