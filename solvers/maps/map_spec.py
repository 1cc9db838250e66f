"""What a three-dimensional point map asks for (`MapSpec`: section, energy, points, method
and the check's sampling) and what one trajectory of it gives (`MapTrajectory`), with the
bounds of a request and the check of the crossings against the dense samples
(`dense_check`); poincare.py traces the maps.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from solvers.errors import InputError
from solvers.integrate.integrator import Section
from solvers.kernels import layout as L
from solvers.kernels.fields import omega_s
from solvers.kernels.sections import SECTION_ANDOYER_G
from solvers.kernels.support import support
from solvers.maps.andoyer import TWO_PI, g_angle, map_point
from solvers.models.cases import Model, build

MAX_POINTS = 100_000
MAX_TRAJECTORIES = 1_000
ROUND_BYTES = 64e6        # memory of the samples of one ensemble call (trace_all)
KERNELS = ("auto", "small", "general")
PILOT_TAUS = 2000.0       # a trajectory that does not return within 2000 rotation times


@dataclass(frozen=True)
class MapSpec:
    """What map to draw: the energy level E0, the section g = g0 in Andoyer-Deprit
    variables (eq an-dp), the direction of crossing, the points per trajectory, and the
    integration options. Frozen: a field is changed by dataclasses.replace.

    Attributes
    ----------
    energy : float
        The energy level E0 of the map.
    g0 : float, default 0.0
        The section g = g0 (radians).
    direction : {1, -1, 0}, default 1
        Crossings with g increasing (+1), decreasing (-1), or both (0).
    points : int, default 200
        Crossings per trajectory, from 1 to 100 000.
    method : str, default "dop853"
        A compiled adaptive Runge-Kutta method of `methods()` ("dop853", "vern9",
        "rk45").
    rtol, atol : float, default 1e-10, 1e-12
        Tolerances; rtol in [1e-14, 1e-3].
    max_steps : int, default 20 000 000
        The step budget of one trajectory.
    samples_per_crossing : int, default 32
        Dense samples per mean return time for the missed-crossing check, at least 8.
    check : bool, default True
        Check that no crossing was missed, and run a trajectory again with shorter steps
        if one was (module docstring).
    generated : bool or None, default None
        Run the case's generated field (True) or the general one (False); None: the
        integrator's default.
    kernel : {"auto", "small", "general"}, default "auto"
        The compiled kernel; "auto" chooses by the map's size (`map_kernel`).

    Examples
    --------
    >>> import solvers
    >>> spec = solvers.MapSpec(energy=1.0, points=50, direction=0)
    >>> spec.g0, spec.rtol
    (0.0, 1e-10)
    >>> solvers.MapSpec(energy=1.0, direction=2).validate()
    Traceback (most recent call last):
    ...
    solvers.errors.InputError: direction = 2: must be +1, -1 or 0
    """

    energy: float
    g0: float = 0.0
    direction: int = 1
    points: int = 200
    method: str = "dop853"
    rtol: float = 1e-10
    atol: float = 1e-12
    max_steps: int = 20_000_000
    samples_per_crossing: int = 32
    check: bool = True
    generated: bool | None = None     # the case's generated field; None: integrate's default
    kernel: str = "auto"              # small | general | auto: by the map's size (map_kernel)

    def validate(self) -> None:
        """Raise InputError for a value out of range (`poincare` calls it first)."""
        if not math.isfinite(self.energy):
            raise InputError(f"energy = {self.energy!r}: must be a finite number")
        if not math.isfinite(self.g0):
            raise InputError(f"g0 = {self.g0!r}: must be a finite angle")
        if self.direction not in (-1, 0, 1):
            raise InputError(f"direction = {self.direction!r}: must be +1, -1 or 0")
        if not 1 <= self.points <= MAX_POINTS:
            raise InputError(f"points = {self.points!r}: must lie in [1, {MAX_POINTS}]")
        if not 1e-14 <= self.rtol <= 1e-3:
            raise InputError(f"rtol = {self.rtol!r}: must lie in [1e-14, 1e-3]")
        if self.samples_per_crossing < 8:
            raise InputError("samples_per_crossing must be at least 8")
        if self.kernel not in KERNELS:
            raise InputError(f"kernel = {self.kernel!r}: one of {', '.join(KERNELS)}")

    def section(self):
        return Section(coef=(math.cos(self.g0), math.sin(self.g0), 0.0, 0.0, 0.0, 0.0),
                       direction=self.direction, code=SECTION_ANDOYER_G)


@dataclass
class MapTrajectory:
    initial: tuple[float, float, float]        # (L/G, H/G, l) of the start, on the section
    state0: np.ndarray
    t: np.ndarray                              # crossing times
    states: np.ndarray                         # (k, 6) states at the crossings
    status: str = "ok"                         # ok | singular | budget | no-return
    message: str = ""
    check: dict = field(default_factory=dict)  # the missed-crossing check
    steps: int = 0
    rhs_calls: int = 0

    @property
    def points(self) -> np.ndarray:
        return map_point(self.states) if len(self.states) else np.empty((0, 3))

    def to_json(self) -> dict:
        return {"initial": list(self.initial), "state0": self.state0.tolist(),
                "points": self.points.tolist(), "t": self.t.tolist(),
                "status": self.status, "message": self.message, "check": self.check,
                "steps": self.steps, "rhs_calls": self.rhs_calls}


def omega_norm(model: Model, y) -> float:
    """|omega| at the state y, omega = I_Q^-1 M solved as the compiled field solves it
    (fields.omega_s, by the adjugate); nan where the field finds I_Q singular, as the
    run from y would stop at once."""
    r, J = np.empty(3), np.empty((3, 3))
    support(model.p, np.ascontiguousarray(y[3:6]), r, J)
    det, w0, w1, w2 = omega_s(model.p, float(y[0]), float(y[1]), float(y[2]),
                              float(r[0]), float(r[1]), float(r[2]))
    return math.hypot(w0, w1, w2) if det != 0 else math.nan


def dense_check(t: np.ndarray, Y: np.ndarray, ct: np.ndarray, g0: float,
                direction: int) -> np.ndarray:
    """Compare, between consecutive samples (t, Y), the crossings of g = g0 in
    `direction` seen on the samples (g unwrapped along them) with the kernel's crossing
    times ct. Returns per-interval counts [kernel, dense, resolved] summed into
    (kernel, dense, kernel in resolved intervals, dense in resolved, unresolved
    intervals); an interval is resolved when g changes by less than pi/2 across it."""
    g = g_angle(Y)
    d = np.angle(np.exp(1j * np.diff(g)))          # wrapped increments in (-pi, pi]
    resolved = np.isfinite(d) & (np.abs(d) < 0.5 * np.pi)
    d = np.where(np.isfinite(d), d, 0.0)
    a = (np.nan_to_num(g[0]) + np.concatenate([[0.0], np.cumsum(d)]) - g0) / TWO_PI
    jumps = np.diff(np.floor(a))
    up = np.where(jumps > 0, jumps, 0.0)
    down = np.where(jumps < 0, -jumps, 0.0)
    dense = up if direction > 0 else down if direction < 0 else up + down
    # kernel crossings per interval (t_i, t_i+1]
    idx = np.searchsorted(t, ct, side="left") - 1
    inside = (idx >= 0) & (idx < len(t) - 1)
    kern = np.bincount(idx[inside], minlength=len(t) - 1)[:len(t) - 1].astype(float)
    return np.array([kern.sum(), dense.sum(), kern[resolved].sum(), dense[resolved].sum(),
                     np.count_nonzero(~resolved)])


def map_model(case: str, params: dict | None, *, allow_any_inertia=False) -> Model:
    """The model of a case the Andoyer-Deprit map can draw: the state (M, gamma), marble
    rolling; any other case is refused with the reason."""
    model = build(case, params, allow_any_inertia=allow_any_inertia)
    if model.model != L.MODEL_FULL:
        raise InputError(f"case {case}: the Andoyer-Deprit map needs the state (M, gamma); "
                         "the flat-base cases have (M, r1, r2)")
    if model.case.constraint == "rubber":
        raise InputError(f"case {case}: the Andoyer-Deprit map samples its starts on the marble "
                         "energy level; a rubber body's states also keep (omega, gamma) = 0, "
                         "which these starts do not")
    return model
