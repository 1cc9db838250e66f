"""No request pays a compile inside its deadline, Poincare maps and scenes included (issue 19;
app/services/kernel_prepare.py), on a machine where nothing is compiled.

Poincare maps and scenes run the general kernels (the compiled ensemble with sections, the
scene model on the general field): numba caches those next to their sources
(solvers/kernels/__pycache__; solvers/kernels/jit.py's locator comes before
NUMBA_CACHE_DIR), not in ROLLING_KERNEL_CACHE. An empty kernel cache alone leaves them
warm, so the server here runs from a fresh copy of the sources (no __pycache__), with an
empty ROLLING_KERNEL_CACHE and NUMBA_CACHE_DIR, no background warm-up, nothing assumed
warm, and a deadline of 5 s: far less than the compiles (tens of seconds on 2 cores). A
scene and a Poincare map of one small case must answer 200; the server's record of the
compiles it prepared (health's kernels.prepared) must show each one longer than the
deadline, and no job may have timed out. Slow: it pays the cold compiles once (the price
of a first map on a fresh machine)."""

import shutil
from pathlib import Path

import httpx
import pytest

from app.testing import live_server

ROOT = Path(__file__).resolve().parents[1]
DEADLINE = 5.0

pytestmark = pytest.mark.slow


def _fresh_copy(dest: Path) -> Path:
    for pkg in ("app", "solvers", "catalogue"):
        shutil.copytree(ROOT / pkg, dest / pkg,
                        ignore=shutil.ignore_patterns("__pycache__", "*.pyc", "*.nbi", "*.nbc"))
    return dest


def test_map_and_scene_compile_outside_their_deadline(tmp_path):
    src = _fresh_copy(tmp_path / "src")
    env = {"PYTHONPATH": str(src), "ROLLING_KERNEL_CACHE": str(tmp_path / "kernels"),
           "NUMBA_CACHE_DIR": str(tmp_path / "numba")}
    with live_server(timeout=900.0, cwd=src, extra_env=env, deadline_s=DEADLINE,
                     warm_kernels=False, kernels_warm=False, warm_workers=False,
                     workers=1) as url:
        scene = httpx.post(f"{url}/api/scene", timeout=900.0, json={
            "case": "plane/chaplygin-ball", "example": True, "t_end": 1.0, "frames": 20})
        assert scene.status_code == 200, scene.text
        poincare = httpx.post(f"{url}/api/poincare", timeout=900.0, json={
            "case": "plane/chaplygin-ball", "example": True, "energy": 1.0,
            "trajectories": 1, "points": 5, "rtol": 1e-8, "atol": 1e-10})
        assert poincare.status_code == 200, poincare.text
        assert len(poincare.json()["trajectories"][0]["points"]) == 5
        h = httpx.get(f"{url}/api/health", timeout=10.0).json()
    prepared = {p["keys"][0][0]: p["seconds"] for p in h["kernels"]["prepared"]}
    assert set(prepared) == {"scene", "map"}, h["kernels"]
    # each compile took longer than a request may: it ran before the deadline started
    assert all(s > DEADLINE for s in prepared.values()), prepared
    assert h["pool"]["timed_out"] == 0 and h["pool"]["crashed"] == 0, h["pool"]
