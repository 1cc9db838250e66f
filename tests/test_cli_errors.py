"""`rolling` never tracebacks (issue 9): bad input exits 2, a singular run or a budget or
a --timeout exits 3, each with one line on stderr; --json never writes NaN or Infinity."""

import json
import math
import signal
import subprocess
import sys

import numpy as np
import pytest
from typer.testing import CliRunner

from app import cli

BALL = ["--set", "I1=1", "--set", "I2=2", "--set", "I3=3", "--set", "R=1",
        "--state", "0.5,-0.3,0.8,0.3,0.4,0.8660254037844386"]


def rolling(*args, timeout=300, preexec_fn=None):
    return subprocess.run([sys.executable, "-m", "app.cli", *args], capture_output=True,
                          text=True, timeout=timeout, preexec_fn=preexec_fn)


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


# --- the holes of issue 21: every input that sizes the work is bounded -----------------

SWEEP = ["sweep", "plane/chaplygin-ball", "--example", "--vary", "m=1,2",
         "--trajectories", "1", "--points", "5"]
MAP = ["poincare", "plane/chaplygin-ball", "--example", "--trajectories", "1",
       "--points", "5"]


@pytest.mark.parametrize("args,says", [
    # before: an OverflowError traceback from the watchdog thread, exit 0, no timeout
    (["simulate", "plane/chaplygin-ball", "--example", "--t-end", "10", "--timeout",
      "1e308"], "--timeout"),
    (["poincare", "plane/chaplygin-ball", "--example", "--timeout", "nan"], "--timeout"),
    (["verify", "--case", "sphere/borisov-fedorov", "--timeout", "inf"], "--timeout"),
    # before: a cluster without workers, waiting forever
    ([*SWEEP, "--workers", "0"], "--workers 0"),
    ([*SWEEP, "--workers", "-1"], "--workers -1"),
    # before: 100,000 processes started (load average 465)
    (["errata", "--workers", "100000"], "--workers 100000"),
    (["verify", "--workers", "100000"], "--workers 100000"),
    # before: "ValueError: max_workers must be greater than 0"
    (["verify", "--workers", "-1"], "--workers -1"),
    (["serve", "--workers", "0"], "--workers 0"),
    # before: accepted, while the API caps seeds at 2**32 - 1
    ([*MAP, "--seed", str(2**70)], "--seed"),
    ([*SWEEP, "--workers", "1", "--seed", "-1"], "--seed"),
    ([*SWEEP, "--workers", "1", "--timeout", "0"], "--timeout"),
])
def test_inputs_that_size_the_work_are_bounded(args, says):
    line = _one_line_error(rolling(*args, timeout=120), 2)
    assert says in line and "ValueError" not in line


@pytest.mark.parametrize("args,says", [
    (["--trajectories", "0"], "trajectories"),
    (["--energies", "1e308"], "energy = 1e+308"),
])
def test_a_bad_sweep_is_one_line_without_a_dask_traceback(args, says):
    """Before: exit 2 with the right line, but dask's "Compute Failed ... Traceback"
    blocks from the workers on stderr as well."""
    base = ["sweep", "plane/chaplygin-ball", "--example", "--trajectories", "1",
            "--points", "5", "--workers", "1"]
    if "--energies" not in args:
        base += ["--vary", "m=1,2"]
    line = _one_line_error(rolling(*base, *args, timeout=180), 2)
    assert says in line


@pytest.mark.parametrize("sigint", ["handled", "ignored"])
def test_sweep_has_a_timeout(sigint):
    """ignored: started as a shell's background job is (SIGINT ignored). The watchdog
    interrupted the main thread with SIGINT, which then did nothing: 15 s later the hard
    exit left the cluster's semaphores to the resource tracker, whose warning followed the
    error line (both fresh-clone runs of 2026-11-27, started in the background)."""
    ignore = (lambda: signal.signal(signal.SIGINT, signal.SIG_IGN)) if sigint == "ignored" \
        else None
    proc = rolling(*SWEEP[:-4], "--trajectories", "64", "--points", "2000", "--workers", "1",
                   "--timeout", "2", timeout=120, preexec_fn=ignore)
    line = _one_line_error(proc, 3)
    assert "--timeout" in line


# --- one validation: the API's bounds and words, at once -------------------------------

# the command line run in a process that says at its exit whether it imported the solvers
# and numba (a refusal by the bounds needs neither: it comes before their imports)
IMPORTED = ("import atexit, sys\n"
            "atexit.register(lambda: print('imported:', sorted(m for m in ('numba', "
            "'solvers.simulate') if m in sys.modules)))\n"
            "from app.cli import main\nmain(sys.argv[1:])\n")


def _api_detail(path: str, body: dict) -> str:
    from fastapi.testclient import TestClient

    from app.main import create_app
    from app.testing import settings_for_tests

    with TestClient(create_app(settings_for_tests(warm_workers=False))) as c:
        r = c.post(path, json=body)
    assert r.status_code == 422, r.text
    return r.json()["detail"]


def test_a_huge_t_end_is_refused_in_the_apis_words_before_the_solvers_load():
    """Before: 19.7 s of CPU, then exit 3 ("step budget ran out"), where the API refuses
    t_end above 1e7 at once with a 422."""
    proc = subprocess.run([sys.executable, "-c", IMPORTED, "simulate", "plane/chaplygin-ball",
                           "--example", "--t-end", "1e308"], capture_output=True, text=True,
                          timeout=120)
    line = _one_line_error(proc, 2)
    assert line == "error: " + _api_detail("/api/validate", {
        "case": "plane/chaplygin-ball", "example": True, "t_end": 1e308})
    assert "imported: []" in proc.stdout, proc.stdout


def test_a_huge_energy_is_one_line_in_the_apis_words():
    """Before: exit 2, but three numpy RuntimeWarnings and an internal message ("t_out
    (trajectory 0) must be finite and strictly increasing") where the API says the
    energy is too large."""
    proc = rolling("poincare", "plane/chaplygin-ball", "--example", "--energy", "1e308",
                   timeout=120)
    line = _one_line_error(proc, 2)
    assert "Warning" not in proc.stderr
    detail = _api_detail("/api/poincare", {"case": "plane/chaplygin-ball", "example": True,
                                           "energy": 1e308})
    assert line == "error: " + detail and "too large" in detail and "overflow" in detail
