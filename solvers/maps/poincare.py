"""Three-dimensional point maps of the paper (section "Three-dimensional point maps in
nonholonomic mechanics", eq an-dp): at a fixed energy E0, the successive crossings of a
trajectory with the section g = g0 in Andoyer-Deprit variables, drawn as (L/G, H/G, l).

How (the parts are separate, diffrax style):
  * initial conditions on the level: (L/G, H/G, l) sampled (or given) on the section
    g = g0, |M| from the energy (solvers.maps.andoyer.on_energy_level);
  * crossings: the compiled integrator with the nonlinear section s = sin(g - g0)
    (solvers/kernels/sections.py), located by Henon's trick to round-off, the branch
    g = g0 + pi refused, in the direction asked (+1: g increasing);
  * no crossing missed, by step control: the kernel keeps the change of g in every step
    below 0.5 rad (sections.py), so a step cannot pass g = g0 twice unseen, nor locate a
    crossing by a long Henon step where g turns fast (near M along e3, gamma along M);
  * and by a check: the same run samples its dense output (samples never change the
    steps) at `samples_per_crossing` points per mean return time; g is unwrapped along
    the samples and, in every sample interval where g turns by less than pi/2, the
    crossings seen there must be those the kernel found. A mismatch runs the trajectory
    again with steps no longer than half the sample spacing; the counts are reported
    (`check`: missed, extra, unresolved_intervals).
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass, replace

import numpy as np

from solvers.errors import InputError
from solvers.integrate.ensemble import integrate_ensemble
from solvers.integrate.integrator import StepControl, integrate, small_fits
from solvers.kernels import layout as L
from solvers.kernels.integrals import NAMES, integral_series
from solvers.kernels.module_cache import disk_cache_ok
from solvers.maps.andoyer import TWO_PI, map_point, on_energy_level
from solvers.maps.map_spec import (
    MAX_TRAJECTORIES,
    PILOT_TAUS,
    ROUND_BYTES,
    MapSpec,
    MapTrajectory,
    dense_check,
    map_model,
    omega_norm,
)
from solvers.models.cases import Model, check_derived, initial_state
from solvers.models.observables import public_name


def _status(res) -> str:
    if res.success:
        return "ok"
    return "budget" if res.budget_exhausted else "singular"


class _Tracer:
    """One trajectory of the map as a sequence of runs of the kernel: a pilot (does it
    return? its mean return time), then chunks of at most 500 crossings, each sampled
    densely for the check, until spec.points crossings, a failure, or the step budget.
    `request()` says what to integrate next, `take(res)` digests the result; `trace` runs
    one tracer with `integrate`, `trace_all` many in lockstep with one compiled ensemble
    call per round (the same runs, so the same numbers)."""

    def __init__(self, model: Model, y0, spec: MapSpec, h_max: float = math.inf):
        self.spec, self.h_max = spec, h_max
        y0 = np.array(y0, dtype=float)
        w = omega_norm(model, y0)
        self.tau = TWO_PI / max(w, 1e-300) if math.isfinite(w) else math.nan
        self.traj = MapTrajectory(tuple(float(v) for v in map_point(y0)), y0, np.empty(0),
                                  np.empty((0, 6)))
        # the start lies on the section: a crossing at t ~ 0 is the start itself
        self.t_start = 1e-9 * self.tau
        self.dt = None                     # sample spacing, set by the pilot
        self.times, self.states = [], []
        self.counts = np.zeros(5)
        self.t, self.y = 0.0, y0
        self.steps_left = spec.max_steps
        self.done = False
        if not math.isfinite(w):     # the field stops at the start: no run to make
            self.traj.status, self.traj.message = "singular", L.STATUS_TEXT[L.SING_INERTIA]
            self._finish()

    def request(self):
        """(y0, t_out, max_crossings, max_steps) of the next run."""
        if self.dt is None:
            return self.y, np.array([0.0, PILOT_TAUS * self.tau]), 3, self.spec.max_steps
        want = min(self.spec.points - len(self.times), 500)
        n_s = math.ceil((1.5 * want + 2) * self.spec.samples_per_crossing) + 1
        return self.y, self.t + self.dt * np.arange(n_s), want, max(int(self.steps_left), 1)

    def take(self, res) -> None:
        traj, spec = self.traj, self.spec
        traj.steps += res.steps
        traj.rhs_calls += res.rhs_calls
        if self.dt is None:
            self._take_pilot(res)
            return
        self.steps_left -= res.steps + res.rejected
        first = self.t == 0.0
        keep = res.crossings_t > (self.t_start if first else -math.inf)
        ct, cy = res.crossings_t[keep], res.crossings_y[keep]
        self.times.extend(ct.tolist())
        self.states.extend(cy)
        # the check: from the second sample on in the first chunk (the start itself lies
        # on the section, where the sign of g - g0 is round-off)
        i0 = 1 if first else 0
        if spec.check and len(res.t) > i0 + 1:
            self.counts += dense_check(res.t[i0:], res.y[i0:], ct, spec.g0, spec.direction)
        if len(self.times) >= spec.points:
            self._finish()
        elif not res.success:
            traj.status, traj.message = _status(res), res.message
            self._finish()
        elif self.steps_left <= 0:
            self.t, self.y = res.t_stop, res.y_stop
            traj.status, traj.message = "budget", "the step budget ran out"
            self._finish()
        else:
            self.t, self.y = res.t_stop, res.y_stop

    def _take_pilot(self, pilot) -> None:
        traj, spec = self.traj, self.spec
        tc = pilot.crossings_t[pilot.crossings_t > self.t_start]
        if not pilot.success or tc.size == 0:
            traj.status = "no-return" if pilot.success else _status(pilot)
            traj.message = (pilot.message if not pilot.success else
                            f"no crossing of g = g0 in direction {spec.direction} within "
                            f"t = {PILOT_TAUS * self.tau:.4g} ({PILOT_TAUS:g} rotation times)")
            self.done = True
            return
        period = float(tc[-1] / tc.size)
        # samples fine enough to follow g: g turns at about the body's rate |omega|, also
        # when the crossings in the asked direction are rare
        self.dt = min(period, self.tau) / spec.samples_per_crossing

    def _finish(self) -> None:
        traj = self.traj
        traj.t = np.asarray(self.times[:self.spec.points])
        traj.states = np.asarray(self.states[:self.spec.points]).reshape(-1, 6)
        k_all, d_all, k_res, d_res, unresolved = (int(v) for v in self.counts)
        traj.check = {"kernel": k_all, "dense": d_all, "missed": max(d_res - k_res, 0),
                      "extra": max(k_res - d_res, 0), "unresolved_intervals": unresolved,
                      "sample_dt": self.dt,
                      "h_max": None if math.isinf(self.h_max) else self.h_max}
        self.done = True


# Which kernel runs a map's trajectories. The small kernel with sections (solvers/kernels/
# small.py: the case's generated field in local variables; integrate(kernel="small")) runs
# a map's trajectory in less time than the general kernel (docs/performance.md), but
# compiles once per case structure (then numba's disk cache),
# while the general kernel serves every case and is compiled by the warm-up. "auto" takes
# the small kernel for a map of at least SMALL_MAP_CROSSINGS
# crossings in all (trajectories x points), where the time saved is of the order of that
# compile; a smaller map runs the general kernel. The request alone decides (never what is
# compiled), so the same request gives the same bits: "auto" is resolved once for the
# whole map (resolve_kernel; the explorer before it splits the trajectories into jobs).
SMALL_MAP_CROSSINGS = 100_000


def map_kernel(model: Model, spec: MapSpec, trajectories: int) -> str:
    """"small" or "general": spec.kernel, with "auto" resolved by the map's size."""
    if spec.kernel != "auto":
        return spec.kernel

    fits = (spec.generated is not False and small_fits(model.model, spec.method)
            and disk_cache_ok())
    return "small" if fits and trajectories * spec.points >= SMALL_MAP_CROSSINGS else "general"


def resolve_kernel(model: Model, spec: MapSpec, trajectories: int) -> MapSpec:
    """spec with its kernel decided for a map of `trajectories` trajectories."""
    return spec if spec.kernel != "auto" else replace(
        spec, kernel=map_kernel(model, spec, trajectories))


def _integrate_options(spec: MapSpec) -> dict:
    opts = {"method": spec.method, "rtol": spec.rtol, "atol": spec.atol,
            "section": spec.section()}
    if spec.generated is not None:
        opts["generated"] = spec.generated
    if spec.kernel == "small":
        opts["kernel"] = "small"
    return opts


def trace(model: Model, y0, spec: MapSpec, *, h_max: float = math.inf) -> MapTrajectory:
    """spec.points crossings of the section from y0 (see the module docstring), one
    `integrate` call per run."""
    spec = resolve_kernel(model, spec, 1)
    tr = _Tracer(model, y0, spec, h_max)
    control = StepControl(h_max=h_max)
    while not tr.done:
        y, t_out, n_cross, steps = tr.request()
        tr.take(integrate(model.model, model.p, y, t_out, max_steps=steps,
                          max_crossings=n_cross, control=control,
                          **_integrate_options(spec)))
    return tr.traj


def trace_all(model: Model, starts, spec: MapSpec, *, h_max=None, workers: int | None = None,
              progress: Callable[[int, int], None] | None = None) -> list[MapTrajectory]:
    """`trace` for every start, the runs of all unfinished trajectories in one compiled
    parallel call per round (solvers/integrate/ensemble.py; several if their samples
    would take more than ROUND_BYTES); h_max: one per start or None.
    progress(finished, total) when a round finishes some."""
    spec = resolve_kernel(model, spec, len(starts))
    hm = [math.inf] * len(starts) if h_max is None else list(h_max)
    tracers = [_Tracer(model, y0, spec, h) for y0, h in zip(starts, hm, strict=True)]
    finished = 0
    while True:
        live = [tr for tr in tracers if not tr.done]
        if not live:
            break
        reqs = [tr.request() for tr in live]
        # the samples of a round take rows x width x 6 doubles: at most ~64 MB per call
        width = max(len(r[1]) for r in reqs)
        block = max(1, int(ROUND_BYTES // (width * 6 * 8)))
        for lo in range(0, len(live), block):
            _round(model, spec, live[lo:lo + block], reqs[lo:lo + block], workers)
        now = sum(tr.done for tr in tracers)
        if progress is not None and now > finished:
            progress(now, len(tracers))
        finished = now
    return [tr.traj for tr in tracers]


def _round(model, spec, live, reqs, workers) -> None:
    """One compiled ensemble call for the requests of the tracers `live`."""
    width = max(len(r[1]) for r in reqs)
    T = np.zeros((len(live), width))
    for i, r in enumerate(reqs):
        T[i, :len(r[1])] = r[1]
    res = integrate_ensemble(model.model, model.p, np.array([r[0] for r in reqs]), T,
                             n_out=[len(r[1]) for r in reqs],
                             max_crossings=[r[2] for r in reqs],
                             max_steps=[r[3] for r in reqs],
                             h_max=[tr.h_max for tr in live], workers=workers,
                             **_integrate_options(spec))
    for tr, r in zip(live, res, strict=True):
        tr.take(r)


def _needs_again(spec: MapSpec, traj: MapTrajectory) -> bool:
    c = traj.check
    return bool(spec.check and c and (c["missed"] or c["extra"]))


def _again(first: MapTrajectory, again: MapTrajectory) -> MapTrajectory:
    again.check["first_pass"] = {k: first.check[k]
                                 for k in ("kernel", "dense", "missed", "extra")}
    return again


def trace_checked(model: Model, y0, spec: MapSpec) -> MapTrajectory:
    """trace(), and once more with h_max = the sample spacing if the check found a
    crossing the kernel missed (or the samples were too coarse to tell)."""
    traj = trace(model, y0, spec)
    if _needs_again(spec, traj):
        return _again(traj, trace(model, y0, spec, h_max=0.5 * traj.check["sample_dt"]))
    return traj


def trace_checked_all(model: Model, starts, spec: MapSpec, *, workers: int | None = None,
                      progress: Callable[[int, int], None] | None = None
                      ) -> list[MapTrajectory]:
    """trace_checked() for every start: trace_all, then trace_all again for those whose
    check asks for it. progress(finished, total) as the first pass finishes them, and
    once more after the second pass if there is one."""
    starts = list(starts)
    spec = resolve_kernel(model, spec, len(starts))     # the redo runs as the first pass
    out = trace_all(model, starts, spec, workers=workers, progress=progress)
    redo = [i for i, tr in enumerate(out) if _needs_again(spec, tr)]
    if redo:
        again = trace_all(model, [starts[i] for i in redo], spec, workers=workers,
                          h_max=[0.5 * out[i].check["sample_dt"] for i in redo])
        for i, tr in zip(redo, again, strict=True):
            out[i] = _again(out[i], tr)
        if progress is not None:
            progress(len(starts), len(starts))
    return out


def sample_initial(model: Model, spec: MapSpec, n: int, rng: np.random.Generator,
                   bound: float = 0.95, tries: int = 200) -> list[np.ndarray]:
    """n states on the level E0 and the section g = g0: (L/G, H/G) uniform in
    [-bound, bound]^2 (away from the poles where g is undefined), l uniform."""
    out = []
    for _ in range(n * tries):
        lam, h = rng.uniform(-bound, bound, 2)
        l = rng.uniform(0.0, TWO_PI)
        y = on_energy_level(model, lam, h, l, spec.g0, spec.energy)
        if y is not None:
            out.append(y)
            if len(out) == n:
                return out
    raise InputError(f"energy = {spec.energy!r}: found {len(out)} of {n} points of the "
                     "level on the section (E0 must exceed the potential energy)")


def given_initial(model: Model, spec: MapSpec, points) -> list[np.ndarray]:
    """States on the level E0 and the section for given (L/G, H/G, l)."""
    out = []
    for x in points:
        if len(x) != 3 or not all(math.isfinite(float(v)) for v in x):
            raise InputError(f"initial point {x!r}: expected three numbers L/G, H/G, l")
        lam, h, l = (float(v) for v in x)
        if not (abs(lam) < 1 and abs(h) < 1):
            raise InputError(f"initial point {x!r}: |L/G| < 1 and |H/G| < 1 are needed "
                             "(the angle g is undefined at +-1)")
        y = on_energy_level(model, lam, h, l, spec.g0, spec.energy)
        if y is None:
            raise InputError(f"initial point {x!r}: the energy {spec.energy!r} does not "
                             "exceed the potential energy there")
        out.append(y)
    return out


@dataclass
class PoincareResult:
    """A map drawn by `poincare`.

    Attributes
    ----------
    case : str
        The case id.
    params : dict of str to float
        Every parameter of the case, the optional ones with their defaults.
    spec : MapSpec
        The map, with its kernel decided.
    trajectories : list of MapTrajectory
        One per start. Each has `initial` (the start's (L/G, H/G, l)), `state0`, `t` (the
        crossing times), `states` (the states (M, gamma) there), `points` (the map points
        (L/G, H/G, l), shape (k, 3)), `status` ("ok", "singular", "budget" or
        "no-return"), `message`, and `check` (the missed-crossing check: "missed",
        "extra", "unresolved_intervals", ...).
    integral_names : tuple of str
        The first integrals the case carries, "energy" first, under the names of a run's
        outputs (solvers/models/observables.py: "M_squared" is |M|^2).

    Examples
    --------
    >>> import solvers
    >>> ball = {"I1": 1.0, "I2": 2.0, "I3": 3.0, "m": 1.0, "R": 1.0}
    >>> res = solvers.poincare("plane/chaplygin-ball", ball, solvers.MapSpec(energy=1.0,
    ...                        points=4), trajectories=1)
    >>> res.integral_names
    ('energy', 'gamma_squared', 'area', 'M_squared')
    >>> (tr,) = res.trajectories
    >>> tr.status, tr.points.shape, tr.check["missed"]
    ('ok', (4, 3), 0)
    >>> res.integral_spread()[0]["energy"] < 1e-8
    True
    >>> sorted(res.to_json())[:3]
    ['atol', 'case', 'coordinates']
    """

    case: str
    params: dict
    spec: MapSpec
    trajectories: list[MapTrajectory]
    integral_names: tuple[str, ...]

    def integral_spread(self) -> list[dict[str, float]]:
        """Per trajectory: (max - min) / |mean| over its crossings of every integral the
        case carries, and the absolute spread of H/G (`integral_spread` below)."""
        model = map_model(self.case, self.params, allow_any_inertia=True)
        return [integral_spread(model, tr) for tr in self.trajectories]

    def header(self) -> dict:
        return {"case": self.case, "params": self.params, "energy": self.spec.energy,
                "section": {"g0": self.spec.g0, "direction": self.spec.direction},
                "coordinates": ["L/G", "H/G", "l"], "points": self.spec.points,
                "method": self.spec.method, "rtol": self.spec.rtol, "atol": self.spec.atol,
                "kernel": self.spec.kernel}

    def to_json(self) -> dict:
        """The map as plain data for JSON: the header (case, params, energy, section,
        coordinates, points, method, tolerances, kernel) and every trajectory with its
        points, check and integral spread."""
        trs = []
        for tr, sp in zip(self.trajectories, self.integral_spread(), strict=True):
            trs.append({**tr.to_json(), "spread": sp})
        return {**self.header(), "trajectories": trs}


def integral_spread(model: Model, tr: MapTrajectory) -> dict[str, float]:
    """(max - min) / max(|mean|, 1e-300) over the crossings of one trajectory of every
    integral the case carries, and the absolute spread of H/G."""
    d = {}
    if len(tr.states):
        Y = np.ascontiguousarray(tr.states)
        for name in model.integral_names:
            v = np.empty(len(Y))
            integral_series(NAMES.index(name), model.model, Y, model.p, v)
            d[public_name(name)] = float(np.ptp(v) / max(abs(float(np.mean(v))), 1e-300))
        d["H/G"] = float(np.ptp(tr.points[:, 1]))
    return d


def starts_for(model: Model, spec: MapSpec, *, trajectories: int = 8, initial=None,
               states=None, seed: int = 0) -> list[np.ndarray]:
    """The initial states: given full `states`, or given map points `initial`, or
    `trajectories` sampled with `seed` (see `poincare`)."""
    if states is not None:
        return [initial_state(model, s) for s in states]
    if initial is not None:
        starts = given_initial(model, spec, initial)
    else:
        if not 1 <= trajectories <= MAX_TRAJECTORIES:
            raise InputError(f"trajectories = {trajectories!r}: must lie in "
                             f"[1, {MAX_TRAJECTORIES}]")
        starts = sample_initial(model, spec, trajectories, np.random.default_rng(seed))
    # a level so high that its starts overflow (energy = 1e308) is bad input, refused
    # here for the API, the CLI and the sweeps alike, in the same words
    for s in starts:
        check_derived(model, s, blame=f"energy = {spec.energy!r}")
    return starts


def poincare(case: str, params: dict | None, spec: MapSpec, *, trajectories: int = 8,
             initial=None, states=None, seed: int = 0,
             progress: Callable[[int, int], None] | None = None,
             allow_any_inertia: bool = False, workers: int | None = None) -> PoincareResult:
    """Draw the three-dimensional point map of a case on one energy level.

    The successive crossings of trajectories on the level E0 = spec.energy with the
    section g = spec.g0 in Andoyer-Deprit variables (eq an-dp), as points (L/G, H/G, l);
    no crossing is missed (module docstring). All trajectories run together, one compiled
    parallel call per round.

    Parameters
    ----------
    case : str
        A case with the state (M, gamma): a key of `cases()` other than the flat-base
        cases.
    params : dict of str to float, or None
        The case's parameters by name, as for `simulate`.
    spec : MapSpec
        The map: energy level, section, points per trajectory, integration options.
    trajectories : int, default 8
        The number of starts sampled on the level and the section, (L/G, H/G) uniform in
        [-0.95, 0.95]^2 and l uniform, from 1 to 1000; ignored with `initial` or `states`.
    initial : sequence of (float, float, float), optional
        Starts given as map points (L/G, H/G, l), with |L/G| < 1 and |H/G| < 1.
    states : sequence of sequence of float, optional
        Starts given as full states (M, gamma), taken as they are (their own energy).
    seed : int, default 0
        The seed of the sampled starts.
    progress : callable (done, total), optional
        Called as trajectories finish.
    allow_any_inertia : bool, default False
        As for `simulate`.
    workers : int or None, default None
        Threads of the compiled parallel call; None: numba's default.

    Returns
    -------
    PoincareResult
        One MapTrajectory per start, with its points, status and missed-crossing check.

    Raises
    ------
    InputError
        Bad parameters or map options, a flat-base case, or an energy level below the
        potential energy on the section.

    Examples
    --------
    The Chaplygin ball carries the area integral H = (M, gamma) and |M|^2 = G^2, so
    along each trajectory of its map H/G stays constant:

    >>> import solvers
    >>> ball = {"I1": 1.0, "I2": 2.0, "I3": 3.0, "m": 1.0, "R": 1.0}
    >>> res = solvers.poincare("plane/chaplygin-ball", ball,
    ...                        solvers.MapSpec(energy=1.0, points=5), trajectories=2)
    >>> [(tr.status, len(tr.points), tr.check["missed"]) for tr in res.trajectories]
    [('ok', 5, 0), ('ok', 5, 0)]
    >>> max(sp["H/G"] for sp in res.integral_spread()) < 1e-8
    True
    """
    spec.validate()
    model = map_model(case, params, allow_any_inertia=allow_any_inertia)
    starts = starts_for(model, spec, trajectories=trajectories, initial=initial,
                        states=states, seed=seed)
    spec = resolve_kernel(model, spec, len(starts))
    out = trace_checked_all(model, starts, spec, workers=workers, progress=progress)
    names = tuple(public_name(n) for n in model.integral_names)
    return PoincareResult(case, model.params, spec, out, names)
