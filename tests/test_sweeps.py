"""Sweeps of 3D point maps on dask.distributed (solvers/maps/sweeps.py): a tiny LocalCluster,
results independent of the number of workers for a fixed seed, settings, validation."""

import pytest

from solvers.errors import InputError
from solvers.maps.sweeps import (
    DaskSettings,
    MapTask,
    energy_tasks,
    parameter_tasks,
    run_task,
    seeded,
    sweep,
)

ELLIPSOID = {"m": 1.0, "b1": 1.0, "b2": 2.0, "b3": 3.0, "mu": 1.0}
THREADS = {"processes": False, "threads_per_worker": 1}


def tasks():
    return parameter_tasks("plane/ellipsoid", ELLIPSOID, "lambda", [0.0, 0.5, 1.0], 1.0,
                           trajectories=2, points=30)


def strip(results):
    return [{k: v for k, v in r.items() if k != "wall_s"} for r in results]


def test_seeds_are_spawned_in_task_order():
    a, b = seeded(tasks(), 1), seeded(tasks(), 1)
    assert [t.seed for t in a] == [t.seed for t in b]
    assert len({t.seed for t in a}) == 3
    assert [t.seed for t in seeded(tasks(), 2)] != [t.seed for t in a]


def test_local_cluster_results_match_serial_and_do_not_depend_on_workers():
    serial = [run_task(t) for t in seeded(tasks(), 11)]
    calls = []
    two = sweep(tasks(), seed=11, settings=DaskSettings(workers=2, **THREADS),
                progress=lambda done, total: calls.append((done, total)))
    one = sweep(tasks(), seed=11, settings=DaskSettings(workers=1, **THREADS))
    assert strip(two.results) == strip(one.results) == strip(serial)
    assert [r["label"] for r in two.results] == ["lambda=0", "lambda=0.5", "lambda=1"]
    assert calls == [(0, 3), (1, 3), (2, 3), (3, 3)]     # 0: the cluster is up
    assert two.workers == 2 and "LocalCluster" in two.scheduler
    for r in two.results:
        for t in r["trajectories"]:
            assert t["n"] == 30 and t["status"] == "ok" and t["missed"] == 0


def test_energy_atlas_tasks_and_settings_from_the_environment(monkeypatch):
    ts = energy_tasks("plane/routh-ball", {"I1": 2, "I3": 3, "m": 1, "R": 1, "a": 0.3, "g": 1},
                      [1.0, 2.0])
    assert [t.label for t in ts] == ["E0=1", "E0=2"] and ts[1].energy == 2.0
    monkeypatch.setenv("ROLLING_DASK_SCHEDULER", "tcp://head:8786")
    monkeypatch.setenv("ROLLING_DASK_WORKERS", "8")
    s = DaskSettings()
    assert s.scheduler == "tcp://head:8786" and s.workers == 8


def test_bad_tasks_fail_before_anything_is_shipped():
    bad = [MapTask("plane/ellipsoid", {**ELLIPSOID, "nope": 1.0}, 1.0, "x")]
    with pytest.raises(InputError, match="nope"):
        sweep(bad, settings=DaskSettings(workers=1, **THREADS))
    with pytest.raises(InputError, match="no task"):
        sweep([], settings=DaskSettings(workers=1, **THREADS))


def test_cli_sweep_json(monkeypatch):
    import json

    from typer.testing import CliRunner

    from app.cli import cli

    monkeypatch.setenv("ROLLING_DASK_PROCESSES", "false")
    r = CliRunner().invoke(cli, ["sweep", "plane/chaplygin-ball", "--example", "--energies",
                                 "1,2", "--trajectories", "1", "--points", "5", "--workers",
                                 "1", "--json"])
    assert r.exit_code == 0, r.output
    d = json.loads(r.stdout.strip().splitlines()[-1])
    assert [x["label"] for x in d["results"]] == ["E0=1", "E0=2"]
    assert d["workers"] == 1
    bad = CliRunner().invoke(cli, ["sweep", "plane/chaplygin-ball", "--example"])
    assert bad.exit_code == 2 and "exactly one of" in bad.output
