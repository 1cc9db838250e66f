"""`rolling kernels`: the kernels a run needs and whether they are compiled (solvers/
compile_state.py), --compile compiling them; bad input is one line and exit 2."""

import os
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]


def rolling(*args, env=None):
    return subprocess.run([sys.executable, "-m", "app.cli", "kernels", *args],
                          capture_output=True, text=True, timeout=900, cwd=ROOT,
                          env={**os.environ, **(env or {})})


def test_a_taylor_run_lists_its_integrator():
    out = rolling("plane/chaplygin-ball", "--method", "taylor", "--t-end", "1")
    assert out.returncode == 0, out.stderr[-2000:]
    lines = out.stdout.strip().splitlines()
    assert len(lines) == 1
    state, kind = lines[0][:13].strip(), lines[0][13:].split()[0]
    assert state in ("compiled", "not compiled") and kind == "taylor"


@pytest.mark.parametrize(("args", "says"), [
    (["nope/x"], "unknown case"),
    (["plane/chaplygin-ball", "--set", "m=-1"], "must be positive"),
])
def test_bad_input_is_one_line_and_exit_2(args, says):
    out = rolling(*args)
    assert out.returncode == 2, out.stderr[-2000:]
    lines = [ln for ln in out.stderr.splitlines() if ln.strip()]
    assert len(lines) == 1 and lines[0].startswith("error: ") and says in lines[0], lines


@pytest.mark.slow
def test_compile_compiles_what_was_not(tmp_path):
    env = {"ROLLING_KERNEL_CACHE": str(tmp_path / "kernels")}
    before = rolling("sphere/flat-base", env=env)
    assert before.returncode == 0 and before.stdout.startswith("not compiled  small"), \
        before.stdout + before.stderr[-2000:]
    done = rolling("sphere/flat-base", "--compile", env=env)
    assert done.returncode == 0 and done.stdout.startswith("compiled      small"), \
        done.stdout + done.stderr[-2000:]
    after = rolling("sphere/flat-base", env=env)
    assert after.stdout == done.stdout
