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
from collections.abc import Callable, Sequence
from dataclasses import asdict, dataclass, field

import numpy as np
from pydantic_settings import BaseSettings, SettingsConfigDict

from solvers.errors import InputError


class DaskSettings(BaseSettings):
    model_config = SettingsConfigDict(env_prefix="ROLLING_DASK_", extra="ignore")

    scheduler: str | None = None      # address of a running scheduler; None: LocalCluster
    workers: int = 2                  # LocalCluster worker processes
    threads_per_worker: int = 1
    processes: bool = True            # False: worker threads in this process (tests)


@dataclass(frozen=True)
class MapTask:
    """One map of a sweep; `label` names the swept value (e.g. 'lambda=0.5')."""

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
    from solvers.maps.map_analysis import correlation_dimension
    from solvers.maps.poincare import MapSpec, poincare

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
    from solvers.maps.poincare import MapSpec, poincare

    t0 = time.perf_counter()
    poincare("plane/chaplygin-ball", {"I1": 1, "I2": 2, "I3": 3, "m": 1, "R": 1},
             MapSpec(energy=1.0, points=2), trajectories=1)
    return time.perf_counter() - t0


def seeded(tasks: Sequence[MapTask], seed: int) -> list[MapTask]:
    """The tasks with seeds spawned from `seed` in task order (SeedSequence)."""
    from dataclasses import replace

    children = np.random.SeedSequence(seed).spawn(len(tasks))
    return [replace(t, seed=int(c.generate_state(1)[0])) for t, c in zip(tasks, children,
                                                                          strict=True)]


def parameter_tasks(case: str, params: dict, name: str, values: Sequence[float],
                    energy: float, **kw) -> list[MapTask]:
    """One map per value of parameter `name` (the others from `params`)."""
    return [MapTask(case, {**params, name: float(v)}, float(energy), f"{name}={v:g}", **kw)
            for v in values]


def energy_tasks(case: str, params: dict, energies: Sequence[float], **kw) -> list[MapTask]:
    """A Poincare atlas: one map per energy level."""
    return [MapTask(case, dict(params), float(e), f"E0={e:g}", **kw) for e in energies]


def _client(settings: DaskSettings):
    from dask.distributed import Client, LocalCluster

    if settings.scheduler:
        return Client(settings.scheduler), None
    cluster = LocalCluster(n_workers=settings.workers,
                           threads_per_worker=settings.threads_per_worker,
                           processes=settings.processes, dashboard_address=None,
                           silence_logs=50)   # a task's error is raised here, once
    return Client(cluster), cluster


def validate(tasks: Sequence[MapTask]) -> None:
    """Check every task here, before anything is shipped (bad input: InputError)."""
    import warnings

    from solvers.maps.poincare import MapSpec, map_model, starts_for
    from solvers.models.cases import check_derived

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
    """Run the tasks on dask.distributed (module docstring); results in task order."""
    from dask.distributed import as_completed

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
