"""Sweeps of 3D point maps over a parameter or over energy levels, on dask.distributed.

A sweep is a list of tasks, each one map (case, parameters, energy, section, starts): the
ellipsoid family's lambda, the unbalanced ball's offset, or a stack of energy levels (a
Poincare atlas). A task carries all the trajectories of its map, run as one compiled
ensemble (not one task per trajectory). Every task gets its own seed, spawned from the
sweep's seed by numpy's SeedSequence in task order, so the result does not depend on how
many workers ran it or in which order the tasks finished: a fixed seed gives the same
numbers on one core, on two, or on a cluster.

Where it runs (a setting, environment variables ROLLING_DASK_*):
  * by default a LocalCluster on this machine: ROLLING_DASK_WORKERS worker processes
    (default 2) of one thread each (numba kernels release the GIL, but one thread per
    process keeps the timing honest on a 2-core machine);
  * ROLLING_DASK_SCHEDULER=tcp://host:8786 (or the `scheduler` argument): any running
    dask scheduler, e.g. one started by `dask scheduler` on a head node with
    `dask worker tcp://head:8786 --nthreads 1` on every node of a cluster (each node needs
    this package installed: `pip install -e .` and its numba cache warmed with
    `python -m solvers.warmup`), or by dask-jobqueue / dask-kubernetes.
Progress: `progress(done, total)` with done = 0 once the cluster is up, then after every
finished task (the CLI draws a bar; its --timeout interrupts only from the first call on).
"""

from __future__ import annotations

import time
import warnings
from collections.abc import Callable, Sequence
from dataclasses import asdict, dataclass, field, replace

import numpy as np
from pydantic_settings import BaseSettings, SettingsConfigDict

from solvers.errors import InputError
from solvers.maps.map_analysis import correlation_dimension
from solvers.maps.poincare import MapSpec, map_model, poincare, starts_for
from solvers.models.cases import check_derived


class DaskSettings(BaseSettings):
    """Where a sweep runs; each field can be set by an environment variable
    ROLLING_DASK_<FIELD> (e.g. ROLLING_DASK_SCHEDULER), read when the settings are made.

    Attributes
    ----------
    scheduler : str or None, default None
        The address of a running dask scheduler (e.g. "tcp://head:8786"); None: a
        LocalCluster on this machine.
    workers : int, default 2
        The LocalCluster's workers.
    threads_per_worker : int, default 1
        Threads per LocalCluster worker.
    processes : bool, default True
        LocalCluster workers as processes; False: as threads of this process.

    Examples
    --------
    >>> import solvers
    >>> s = solvers.DaskSettings(workers=1, processes=False)
    >>> s.scheduler is None, s.workers, s.threads_per_worker
    (True, 1, 1)
    """

    model_config = SettingsConfigDict(env_prefix="ROLLING_DASK_", extra="ignore")

    scheduler: str | None = None      # address of a running scheduler; None: LocalCluster
    workers: int = 2                  # LocalCluster worker processes
    threads_per_worker: int = 1
    processes: bool = True            # False: worker threads in this process (tests)


@dataclass(frozen=True)
class MapTask:
    """One map of a sweep, as `parameter_tasks` and `energy_tasks` make them.

    Attributes
    ----------
    case : str
        The case id (with the state (M, gamma), as for `poincare`).
    params : dict of str to float
        The case's parameters.
    energy : float
        The energy level E0.
    label : str
        Names the swept value, e.g. "lambda=0.5" or "E0=1".
    g0 : float, default 0.0
        The section g = g0.
    direction : {1, -1, 0}, default 1
        The direction of crossing (`MapSpec`).
    trajectories : int, default 4
        Starts sampled on the level and the section.
    points : int, default 200
        Crossings per trajectory.
    rtol, atol : float, default 1e-10, 1e-12
        Tolerances.
    seed : int, default 0
        The seed of the starts; `sweep` replaces it with one spawned from its own seed.
    keep_points : bool, default False
        Keep every trajectory's map points in the result (else only its summary).
    threads : int, default 1
        Threads of the task's compiled parallel call.

    Examples
    --------
    >>> import solvers
    >>> (task,) = solvers.energy_tasks("plane/chaplygin-ball", {"I1": 1, "I2": 2, "I3": 3,
    ...                                "m": 1, "R": 1}, [2.0], points=10)
    >>> task.label, task.energy, task.points, task.trajectories
    ('E0=2', 2.0, 10, 4)
    """

    case: str
    params: dict
    energy: float
    label: str
    g0: float = 0.0
    direction: int = 1
    trajectories: int = 4
    points: int = 200
    rtol: float = 1e-10
    atol: float = 1e-12
    seed: int = 0
    keep_points: bool = False
    threads: int = 1          # numba threads of the task's compiled ensemble (see run_task)


@dataclass
class SweepResult:
    """The maps of a sweep, in task order.

    Attributes
    ----------
    tasks : list of MapTask
        The tasks as run (with their spawned seeds).
    results : list of dict
        Per task: "label", "wall_s" and "trajectories", one dict per trajectory with
        "initial" (its start (L/G, H/G, l)), "n" (map points), "status", "missed" (the
        missed-crossing check), "spread" (of every integral and of H/G, as
        `PoincareResult.integral_spread`), "D2" (the correlation dimension of its points,
        with at least 50 of them, else None) and, with keep_points, "points".
    wall_s : float
        Wall time of the tasks (after the workers loaded the kernels).
    workers : int
        The dask workers that ran them.
    scheduler : str
        The scheduler's address, or a description of the LocalCluster.
    extra : dict
        Other figures of the run ("warm_s": the workers' kernel loading).

    Examples
    --------
    See `sweep`.

    >>> import solvers
    >>> solvers.SweepResult([], [], 0.0, 1, "none").to_json()["tasks"]
    []
    """

    tasks: list[MapTask]
    results: list[dict]
    wall_s: float
    workers: int
    scheduler: str
    extra: dict = field(default_factory=dict)

    def to_json(self) -> dict:
        return {"scheduler": self.scheduler, "workers": self.workers, "wall_s": self.wall_s,
                "tasks": [asdict(t) for t in self.tasks], "results": self.results}


def run_task(task: MapTask) -> dict:
    """The map of one task, summarised per trajectory (run on a dask worker). The task
    carries all its trajectories: they run together, one compiled parallel call per round
    (solvers.maps.poincare.trace_checked_all), on `task.threads` threads; one, since the
    dask workers (one thread each) already fill the cores."""
    spec = MapSpec(energy=task.energy, g0=task.g0, direction=task.direction,
                   points=task.points, rtol=task.rtol, atol=task.atol)
    t0 = time.perf_counter()
    res = poincare(task.case, task.params, spec, trajectories=task.trajectories,
                   seed=task.seed, workers=task.threads)
    rows = []
    for tr, sp in zip(res.trajectories, res.integral_spread(), strict=True):
        row = {"initial": list(tr.initial), "n": len(tr.points), "status": tr.status,
               "missed": tr.check.get("missed"), "spread": sp,
               "D2": (correlation_dimension(tr.points, 0.01, 0.1)
                      if len(tr.points) >= 50 else None)}
        if task.keep_points:
            row["points"] = tr.points.tolist()
        rows.append(row)
    return {"label": task.label, "trajectories": rows,
            "wall_s": time.perf_counter() - t0}


def warm() -> float:
    """Load the compiled kernels in a worker (numba's on-disk cache) with one tiny map."""
    t0 = time.perf_counter()
    poincare("plane/chaplygin-ball", {"I1": 1, "I2": 2, "I3": 3, "m": 1, "R": 1},
             MapSpec(energy=1.0, points=2), trajectories=1)
    return time.perf_counter() - t0


def seeded(tasks: Sequence[MapTask], seed: int) -> list[MapTask]:
    """The tasks with seeds spawned from `seed` in task order (SeedSequence)."""
    children = np.random.SeedSequence(seed).spawn(len(tasks))
    return [replace(t, seed=int(c.generate_state(1)[0])) for t, c in zip(tasks, children,
                                                                          strict=True)]


def parameter_tasks(case: str, params: dict, name: str, values: Sequence[float],
                    energy: float, **kw) -> list[MapTask]:
    """The tasks of a sweep over one parameter: one map per value.

    Parameters
    ----------
    case : str
        The case id (with the state (M, gamma)).
    params : dict of str to float
        The case's other parameters.
    name : str
        The swept parameter, e.g. "lambda" of the ellipsoid (eq2.29).
    values : sequence of float
        Its values, one map each.
    energy : float
        The energy level E0 of every map.
    **kw
        Further `MapTask` fields (trajectories, points, g0, direction, rtol, atol,
        keep_points, threads).

    Returns
    -------
    list of MapTask
        Labelled "<name>=<value>".

    Examples
    --------
    >>> import solvers
    >>> ellipsoid = {"m": 1.0, "b1": 1.0, "b2": 2.0, "b3": 3.0, "mu": 1.0}
    >>> tasks = solvers.parameter_tasks("plane/ellipsoid", ellipsoid, "lambda",
    ...                                 [0.0, 0.5], energy=1.0, trajectories=2, points=30)
    >>> [t.label for t in tasks], tasks[1].params["lambda"], tasks[1].points
    (['lambda=0', 'lambda=0.5'], 0.5, 30)
    """
    return [MapTask(case, {**params, name: float(v)}, float(energy), f"{name}={v:g}", **kw)
            for v in values]


def energy_tasks(case: str, params: dict, energies: Sequence[float], **kw) -> list[MapTask]:
    """The tasks of a Poincare atlas: one map per energy level.

    Parameters
    ----------
    case : str
        The case id (with the state (M, gamma)).
    params : dict of str to float
        The case's parameters.
    energies : sequence of float
        The energy levels E0, one map each.
    **kw
        Further `MapTask` fields (trajectories, points, g0, direction, rtol, atol,
        keep_points, threads).

    Returns
    -------
    list of MapTask
        Labelled "E0=<energy>".

    Examples
    --------
    >>> import solvers
    >>> routh = {"I1": 2, "I3": 3, "m": 1, "R": 1, "a": 0.3, "g": 1}
    >>> tasks = solvers.energy_tasks("plane/routh-ball", routh, [1.0, 2.0])
    >>> [t.label for t in tasks], tasks[1].energy
    (['E0=1', 'E0=2'], 2.0)
    """
    return [MapTask(case, dict(params), float(e), f"E0={e:g}", **kw) for e in energies]


def _client(settings: DaskSettings):
    from dask.distributed import Client, LocalCluster  # lazy: dask, only when a sweep runs

    if settings.scheduler:
        return Client(settings.scheduler), None
    cluster = LocalCluster(n_workers=settings.workers,
                           threads_per_worker=settings.threads_per_worker,
                           processes=settings.processes, dashboard_address=None,
                           silence_logs=50)   # a task's error is raised here, once
    return Client(cluster), cluster


def validate(tasks: Sequence[MapTask]) -> None:
    """Check every task here, before anything is shipped (bad input: InputError)."""
    if not tasks:
        raise InputError("the sweep has no task")
    for t in tasks:
        model = map_model(t.case, t.params)
        spec = MapSpec(energy=t.energy, g0=t.g0, direction=t.direction, points=t.points,
                       rtol=t.rtol, atol=t.atol)
        spec.validate()
        # the starts as the task will draw them: a bad count, or a level so high that its
        # starts overflow (energy = 1e308), is refused here and not as a worker's traceback
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", RuntimeWarning)
            for s in starts_for(model, spec, trajectories=t.trajectories, seed=t.seed):
                check_derived(model, s, blame=f"energy = {t.energy!r}")


def sweep(tasks: Sequence[MapTask], *, seed: int = 0, settings: DaskSettings | None = None,
          client=None, progress: Callable[[int, int], None] | None = None) -> SweepResult:
    """Run the maps of a sweep on dask.distributed; the results in task order.

    Every task gets its own seed, spawned from `seed` in task order, so a fixed seed
    gives the same numbers on any number of workers (module docstring). All tasks are
    validated here before any is shipped.

    Parameters
    ----------
    tasks : sequence of MapTask
        From `parameter_tasks` or `energy_tasks`, or made directly.
    seed : int, default 0
        The sweep's seed.
    settings : DaskSettings or None, default None
        Where to run; None: DaskSettings() (from the environment, else a LocalCluster of
        two worker processes).
    client : dask.distributed.Client or None, default None
        A client to run on (the sweep then leaves it open); None: one made from
        `settings` and closed at the end.
    progress : callable (done, total), optional
        Called with done = 0 once the cluster is up, then after every finished task.

    Returns
    -------
    SweepResult
        The summary of every task's map (and its points with keep_points).

    Raises
    ------
    InputError
        No task, or a task with bad input.

    Examples
    --------
    Two energy levels of the Chaplygin ball, on one worker thread of this process:

    >>> import solvers
    >>> ball = {"I1": 1.0, "I2": 2.0, "I3": 3.0, "m": 1.0, "R": 1.0}
    >>> tasks = solvers.energy_tasks("plane/chaplygin-ball", ball, [0.5, 1.0],
    ...                              trajectories=1, points=5)
    >>> out = solvers.sweep(tasks, seed=1,
    ...                     settings=solvers.DaskSettings(workers=1, processes=False))
    >>> [r["label"] for r in out.results], out.workers
    (['E0=0.5', 'E0=1'], 1)
    >>> [(t["status"], t["n"], t["missed"]) for r in out.results for t in r["trajectories"]]
    [('ok', 5, 0), ('ok', 5, 0)]
    >>> max(t["spread"]["energy"] for r in out.results for t in r["trajectories"]) < 1e-8
    True
    """
    from dask.distributed import as_completed  # lazy: dask, only when a sweep runs

    settings = settings or DaskSettings()
    tasks = seeded(tasks, seed)
    validate(tasks)
    own = client is None
    cluster = None
    if own:
        client, cluster = _client(settings)
    try:
        if progress is not None:    # 0 done: the cluster is up (the CLI's --timeout may
            progress(0, len(tasks))  # interrupt from here on: this `finally` closes it)
        n_workers = len(client.scheduler_info()["workers"])
        t0 = time.perf_counter()
        client.run(warm)      # every worker loads the kernels before the clock starts
        warm_s = time.perf_counter() - t0
        t0 = time.perf_counter()
        futures = client.map(run_task, tasks, pure=False)
        index = {f.key: i for i, f in enumerate(futures)}
        results: list[dict | None] = [None] * len(tasks)
        done = 0
        for fut in as_completed(futures):
            results[index[fut.key]] = fut.result()
            done += 1
            if progress is not None:
                progress(done, len(tasks))
        wall = time.perf_counter() - t0
        address = settings.scheduler or f"LocalCluster({n_workers} workers, " \
            f"{'processes' if settings.processes else 'threads'})"
        return SweepResult(list(tasks), results, wall, n_workers, address,
                           {"warm_s": warm_s})
    finally:
        if own:
            client.close()
            if cluster is not None:
                cluster.close()
