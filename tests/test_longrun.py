"""Long runs: with projection the integrals hold to 1e-15 (relative, as `drift` measures it:
|F - F(0)| / max(|F(0)|, 1)) over 1e5 time units; without, the drift stays what the
tolerance allows. The full tables (cost, growth exponents): bench/longrun.py,
bench/results/longrun.txt. A projected 1e5 run costs ~1 s here, so it runs in the suite."""

import json
import subprocess
import sys

import numpy as np
import pytest

from solvers.models.cases import registry
from solvers.simulate import simulate

T_LONG = 1e5


@pytest.mark.parametrize("method", ["dop853", "vern9"])
@pytest.mark.parametrize("case_id", ["plane/chaplygin-ball", "sphere/borisov-fedorov",
                                     "plane/routh-ball"])
def test_projected_run_holds_every_integral_to_1e_15(case_id, method):
    c = registry()[case_id]
    r = simulate(case_id, c.example, c.state, T_LONG, method=method, samples=1001,
                 project=True)
    assert r.ok, r.message
    assert len(r.invariants) >= 3          # energy, gamma2 and the case's own
    for name in r.invariants:
        assert r.drift(name) <= 1e-15, (name, r.drift(name))
    assert np.all(np.isfinite(r.state))


def test_unprojected_drift_is_reported_and_bounded():
    """The same run without projection drifts (linearly in t at rtol 1e-10): reported in
    stats["drift"], far above round-off and within what the tolerance allows."""
    c = registry()["plane/chaplygin-ball"]
    r = simulate("plane/chaplygin-ball", c.example, c.state, T_LONG, method="vern9",
                 samples=1001)
    assert r.ok
    d = r.stats["drift"]
    assert 1e-14 < max(d.values()) < 1e-6, d


def test_cli_long_projected_run():
    """`rolling simulate plane/chaplygin-ball --example --t-end 100000 --project`."""
    proc = subprocess.run([sys.executable, "-m", "app.cli", "simulate", "plane/chaplygin-ball",
                           "--example", "--t-end", "100000", "--project", "--samples", "101",
                           "--json"], capture_output=True, text=True, timeout=600)
    assert proc.returncode == 0, proc.stderr
    out = json.loads(proc.stdout)
    assert out["stats"]["projected"] is True and out["t"][-1] == T_LONG
    assert max(out["stats"]["drift"].values()) <= 1e-15, out["stats"]["drift"]
