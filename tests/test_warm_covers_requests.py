"""Once the warm-up is done, the explorer's default clicks compile nothing (issue 19: no
request pays a compile inside its deadline). kernel_prepare.needed prepares, after the
warm-up, only what it leaves out on purpose (small kernels of other structures, Taylor
integrators); everything else must be among the specializations the warm-up compiles.

tests/warm_coverage_probe.py runs every warm-up task and then the clicks (a case's Run,
plain and projected, its scene, a Poincare map with its pilot, every teaching scene's
checks, a worker's warm start) in a fresh interpreter, and lists the numba signatures the
clicks entered that the warm-up had not. It found two gaps that compiled inside requests
on a warm server: a map's kernels on the model's read-only parameters and a one-trajectory
ensemble's read-only time table (a map of plane/chaplygin-ball compiled for 38 s), and a
scene's kinematics (full_kinematics, flat_kinematics)."""

import json
import os
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]


def test_default_clicks_enter_no_specialization_the_warm_up_left_out():
    out = subprocess.run([sys.executable, str(ROOT / "tests" / "warm_coverage_probe.py")],
                         cwd=ROOT, env={**os.environ, "PYTHONPATH": str(ROOT)},
                         capture_output=True, text=True, timeout=900, check=True)
    report = json.loads(out.stdout.strip().splitlines()[-1])
    assert report["warmed"] > 0
    assert report["new"] == {}, report["new"]
