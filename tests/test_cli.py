"""The machine interface of `rolling simulate` (external checks use exactly this)."""

import json
import subprocess
import sys

import numpy as np
import pytest

from solvers.models.cases import registry


def rolling(*args):
    return subprocess.run([sys.executable, "-m", "app.cli", *args], capture_output=True,
                          text=True, timeout=300)


def sets(params):
    return [a for k, v in params.items() for a in ("--set", f"{k}={v}")]


@pytest.mark.parametrize("case_id", ["plane/chaplygin-ball", "sphere/flat-base"])
def test_simulate_json_contract(case_id):
    c = registry()[case_id]
    proc = rolling("simulate", case_id, *sets({k: c.example[k] for k in c.required}),
                   "--state", ",".join(map(repr, c.state)), "--t-end", "10",
                   "--samples", "11", "--method", "vern9", "--rtol", "1e-11",
                   "--atol", "1e-13", "--json")
    assert proc.returncode == 0, proc.stderr
    out = json.loads(proc.stdout)
    assert len(out["t"]) == 11 and out["t"][0] == 0.0 and out["t"][-1] == 10.0
    width = 5 if "flat" in case_id else 6
    assert np.array(out["state"]).shape == (11, width)
    assert out["state"][0] == pytest.approx(c.state, abs=0)
    assert "energy" in out["invariants"]
    assert all(len(v) == 11 for v in out["invariants"].values())
    for key in ("steps", "rhs_calls", "wall_s", "method"):
        assert key in out["stats"]
    assert out["stats"]["method"] == "vern9" and out["stats"]["rhs_calls"] > out["stats"]["steps"]
    assert out["status"] == "ok"


def test_simulate_project_flag_holds_integrals():
    c = registry()["plane/chaplygin-ball"]
    proc = rolling("simulate", "plane/chaplygin-ball", *sets(c.example), "--state",
                   ",".join(map(repr, c.state)), "--t-end", "200", "--rtol", "1e-6",
                   "--project", "--json")
    out = json.loads(proc.stdout)
    for name in ("energy", "gamma_squared", "M_squared", "area"):
        v = np.array(out["invariants"][name])
        assert np.max(np.abs(v - v[0])) / abs(v[0]) < 1e-14, name


def test_summary_without_json_is_readable():
    proc = rolling("simulate", "sphere/borisov-fedorov", "--example", "--t-end", "5")
    assert proc.returncode == 0, proc.stderr
    for word in ("sphere/borisov-fedorov", "energy", "borisov_fedorov", "steps", "rhs calls"):
        assert word in proc.stdout


def test_singular_run_exits_3_with_where():
    proc = rolling("simulate", "plane/round-disk", "--set", "I1=0.25", "--set", "I3=0.5",
                   "--set", "m=1", "--set", "R=1", "--set", "g=9.81",
                   "--state", "0,0,0,0.05,0,0.99874921777190895", "--t-end", "5", "--json")
    assert proc.returncode == 3
    out = json.loads(proc.stdout)          # still valid JSON, finite numbers only
    assert out["status"] == "singular" and "t =" in out["message"]
    assert "flat" in proc.stderr and "Traceback" not in proc.stderr


def test_cases_and_methods_listed():
    out = rolling("cases").stdout
    assert all(cid in out for cid in registry())
    out = rolling("methods").stdout
    for m in ("dop853", "vern9", "scipy-dop853"):
        assert m in out
