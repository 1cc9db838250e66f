"""Bad input gets one clear line and changes nothing (Python: InputError; CLI: exit 2)."""

import subprocess
import sys

import pytest

from solvers.errors import InputError
from solvers.models.cases import registry
from solvers.simulate import simulate

BALL = {"I1": 1.0, "I2": 2.0, "I3": 2.5, "m": 1.0, "R": 1.0}
G0 = [0.5, -0.3, 0.8, 0.0, 0.6, 0.8]

BAD = [
    # (case, params, state, t_end, options, words expected in the message)
    ("plane/no-such-case", BALL, G0, 1.0, {}, ["unknown case"]),
    ("plane/chaplygin-ball", {**BALL, "q": 1}, G0, 1.0, {}, ["unknown parameter", "q"]),
    ("plane/chaplygin-ball", {"I1": 1, "I2": 2, "I3": 2.5, "m": 1}, G0, 1.0, {},
     ["missing parameter", "R"]),
    ("plane/chaplygin-ball", {**BALL, "R": float("nan")}, G0, 1.0, {}, ["R", "finite"]),
    ("plane/chaplygin-ball", {**BALL, "R": "1e999"}, G0, 1.0, {}, ["R", "finite"]),
    ("plane/chaplygin-ball", {**BALL, "R": "abc"}, G0, 1.0, {}, ["R", "not a number"]),
    ("plane/chaplygin-ball", {**BALL, "m": 0.0}, G0, 1.0, {}, ["m", "positive"]),
    ("plane/chaplygin-ball", {**BALL, "m": -1.0}, G0, 1.0, {}, ["m", "positive"]),
    ("plane/chaplygin-ball", {**BALL, "I2": 0.0}, G0, 1.0, {}, ["I2", "positive"]),
    ("plane/chaplygin-ball", {**BALL, "I3": 9.0}, G0, 1.0, {}, ["triangle inequality"]),
    ("plane/chaplygin-ball", {**BALL, "R": -1.0}, G0, 1.0, {}, ["R", "positive"]),
    ("plane/chaplygin-ball", BALL, [0.5, -0.3, 0.8, 0.0, 0.6, 0.81], 1.0, {}, ["|gamma|"]),
    ("plane/chaplygin-ball", BALL, [0.5, -0.3, 0.8, 0.0, 0.6], 1.0, {}, ["state", "6"]),
    ("plane/chaplygin-ball", BALL, [0.5, -0.3, float("inf"), 0.0, 0.6, 0.8], 1.0, {},
     ["M3", "finite"]),
    ("plane/round-disk", {"I1": 0.25, "I3": 0.5, "m": 1, "R": 1}, [0, 0, 1, 0, 0, 1], 1.0, {},
     ["disk lies flat"]),
    ("plane/round-disk", {"I1": 0.25, "I2": 0.3, "I3": 0.5, "m": 1, "R": 1}, G0, 1.0, {},
     ["I1 = I2"]),
    ("sphere/chaplygin-ball", {**BALL, "k": 1.5}, G0, 1.0, {}, ["does not fit the sphere"]),
    ("sphere/chaplygin-ball", {**BALL, "k": 1.0}, G0, 1.0, {}, ["does not fit the sphere"]),
    ("sphere/round-disk", {"I1": 0.25, "I3": 0.5, "m": 1, "R": 1, "k": 0.9},
     [0, 0, 1, 0.3, 0.0, 0.9539392014169457], 1.0, {}, ["does not fit the sphere"]),
    ("sphere/flat-base", {"I1": 1, "I2": 2, "I3": 2.5, "m": 1, "k": 0.5, "z": 0.1},
     [0, 0, 1, 0.1, 0.2], 1.0, {}, ["flat base", "k"]),
    ("sphere/borisov-fedorov", {**BALL, "k": 2.0}, G0, 1.0, {}, ["k is fixed"]),
    ("plane/chaplygin-ball", BALL, G0, 0.0, {}, ["t_end", "positive"]),
    ("plane/chaplygin-ball", BALL, G0, float("nan"), {}, ["t_end", "finite"]),
    ("plane/chaplygin-ball", BALL, G0, 1.0, {"rtol": 0.0}, ["rtol"]),
    ("plane/chaplygin-ball", BALL, G0, 1.0, {"atol": -1.0}, ["atol"]),
    ("plane/chaplygin-ball", BALL, G0, 1.0, {"samples": 1}, ["samples"]),
    ("plane/chaplygin-ball", BALL, G0, 1.0, {"method": "euler"}, ["method", "unknown"]),
    ("plane/chaplygin-ball", BALL, G0, 5e-324, {}, ["t_end", "too small"]),
]


@pytest.mark.parametrize(("case", "params", "state", "t_end", "opts", "words"), BAD)
def test_bad_input_raises_input_error(case, params, state, t_end, opts, words):
    before = {k: dict(v.optional) for k, v in registry().items()}
    with pytest.raises(InputError) as info:
        simulate(case, params, state, t_end, **opts)
    msg = str(info.value)
    assert "\n" not in msg
    for w in words:
        assert w in msg, (w, msg)
    assert {k: dict(v.optional) for k, v in registry().items()} == before  # nothing changed


def test_triangle_inequality_can_be_waived():
    r = simulate("plane/chaplygin-ball", {**BALL, "I3": 9.0}, G0, 1.0,
                 allow_any_inertia=True, samples=3)
    assert r.ok


def _cli(*args):
    return subprocess.run([sys.executable, "-m", "app.cli", *args], capture_output=True,
                          text=True, timeout=120)


def _sets(params):
    out = []
    for k, v in params.items():
        out += ["--set", f"{k}={v}"]
    return out


@pytest.mark.parametrize(("args", "words"), [
    (["simulate", "plane/chaplygin-ball", *_sets(BALL), "--set", "R=nan",
      "--state", "0.5,-0.3,0.8,0,0.6,0.8", "--t-end", "1"], ["R", "finite"]),
    (["simulate", "plane/chaplygin-ball", *_sets(BALL), "--set", "R=1e999",
      "--state", "0.5,-0.3,0.8,0,0.6,0.8", "--t-end", "1"], ["R", "finite"]),
    (["simulate", "plane/chaplygin-ball", *_sets(BALL), "--set", "R",
      "--state", "0.5,-0.3,0.8,0,0.6,0.8", "--t-end", "1"], ["NAME=VALUE"]),
    (["simulate", "plane/chaplygin-ball", *_sets(BALL),
      "--state", "0.5,-0.3,0.8,0,0.6,0.9", "--t-end", "1"], ["|gamma|"]),
    (["simulate", "plane/round-disk", "--set", "I1=0.25", "--set", "I3=0.5", "--set", "m=1",
      "--set", "R=1", "--state", "0,0,1,0,0,1", "--t-end", "1"], ["disk lies flat"]),
    (["simulate", "sphere/chaplygin-ball", *_sets(BALL), "--set", "k=3",
      "--state", "0.5,-0.3,0.8,0,0.6,0.8", "--t-end", "1"], ["does not fit"]),
    (["simulate", "plane/nope", "--state", "0,0,0,0,0,1", "--t-end", "1"], ["unknown case"]),
    (["simulate", "plane/chaplygin-ball", *_sets(BALL), "--t-end", "1"], ["--state"]),
])
def test_cli_bad_input_one_line_exit_2(args, words):
    proc = _cli(*args)
    assert proc.returncode == 2, proc.stderr
    assert "Traceback" not in proc.stderr
    lines = proc.stderr.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("error: "), proc.stderr
    for w in words:
        assert w in lines[0]
    assert proc.stdout == ""
