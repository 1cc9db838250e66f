"""`rolling` never tracebacks (issue 9): bad input exits 2, a singular run or a budget or
a --timeout exits 3, each with one line on stderr; --json never writes NaN or Infinity."""

import json
import math
import subprocess
import sys

import numpy as np
import pytest
from typer.testing import CliRunner

from app import cli

BALL = ["--set", "I1=1", "--set", "I2=2", "--set", "I3=3", "--set", "R=1",
        "--state", "0.5,-0.3,0.8,0.3,0.4,0.8660254037844386"]


def rolling(*args, timeout=300):
    return subprocess.run([sys.executable, "-m", "app.cli", *args], capture_output=True,
                          text=True, timeout=timeout)


def _one_line_error(proc, code):
    assert proc.returncode == code, (proc.returncode, proc.stderr[-2000:])
    lines = [ln for ln in proc.stderr.splitlines() if ln.strip()]
    assert len(lines) == 1 and lines[0].startswith("error: "), proc.stderr[-2000:]
    assert "Traceback" not in proc.stderr
    return lines[0]


def test_overflowing_mass_is_bad_input():
    line = _one_line_error(rolling("simulate", "plane/chaplygin-ball", "--set", "m=1e308",
                                   *BALL, "--t-end", "1", "--json"), 2)
    assert "m = 1e+308" in line


def test_unknown_claim_exits_2():
    line = _one_line_error(rolling("verify", "--claim", "no-such-claim"), 2)
    assert "no-such-claim" in line


def test_timeout_stops_a_long_run_with_exit_3():
    proc = rolling("simulate", "plane/chaplygin-ball", "--set", "m=1", *BALL,
                   "--t-end", "1e7", "--samples", "11", "--timeout", "1", timeout=120)
    line = _one_line_error(proc, 3)
    assert "--timeout" in line and "1 s" in line


def test_bad_timeout_is_bad_input():
    _one_line_error(rolling("simulate", "plane/chaplygin-ball", "--set", "m=1", *BALL,
                            "--t-end", "1", "--timeout", "-1"), 2)


def test_json_writes_null_for_non_finite_values(monkeypatch):
    from solvers import simulate as sim

    def fake(case, params, y0, t_end, **kw):
        t = np.array([0.0, 1.0])
        return sim.SimulationResult(case, {"m": 1.0}, ("x",), t, np.array([[1.0], [np.nan]]),
                                    {"energy": np.array([1.0, np.inf])},
                                    {"drift": {"energy": math.inf}}, "singular", "stopped")

    monkeypatch.setattr(sim, "simulate", fake)
    res = CliRunner().invoke(cli.cli, ["simulate", "plane/chaplygin-ball", "--set", "m=1",
                                       *BALL, "--t-end", "1", "--json"])
    assert res.exit_code == 3
    out = json.loads(res.stdout.splitlines()[0])
    assert out["state"] == [[1.0], [None]] and out["invariants"]["energy"] == [1.0, None]
    assert out["stats"]["drift"]["energy"] is None


def test_an_unexpected_failure_is_one_line(monkeypatch, capsys):
    from solvers import simulate as sim

    def broken(*a, **kw):
        raise ZeroDivisionError("float division by zero")

    monkeypatch.setattr(sim, "simulate", broken)
    with pytest.raises(SystemExit) as exit_:
        cli.main(["simulate", "plane/chaplygin-ball", "--set", "m=1", *BALL, "--t-end", "1"])
    assert exit_.value.code == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and err.startswith("error: ") and "Traceback" not in err
