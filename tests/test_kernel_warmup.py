"""The kernels compile in the background of a running explorer (issue 19: ready in a minute;
app/services/kernel_warmup.py): /api/health says which parts and cases are still warming,
the terminal gets one progress line per finished part, and the warm-up's own lines
(solvers/warmup.py --progress) are what drives them.

The warm-up here is a scripted stand-in (Settings.warmup_command) that prints the lines of
`python -m solvers.warmup --progress` with pauses, so the states are seen in order and the
test compiles nothing; test_warmup_progress_lines runs the real warm-up's hook."""

import json
import logging
import sys
import time

import pytest
from fastapi.testclient import TestClient

from app.main import create_app
from app.services.kernel_warmup import KernelWarmup, bar
from app.testing import settings_for_tests

pytestmark = pytest.mark.filterwarnings("ignore::DeprecationWarning")

PLAN = {"event": "plan", "total": 3, "parts": [
    {"name": "general kernels", "cases": []},
    {"name": "plane/chaplygin-ball", "cases": ["plane/chaplygin-ball", "sphere/routh-ball"]},
    {"name": "compiled ensembles (Poincare maps)", "cases": []}]}


def scripted(pause: float, fail: bool = False) -> list[str]:
    """A stand-in warm-up: the plan, then one part every `pause` seconds, in the shapes
    of the real warm-up's lines; `fail`: it exits with code 1."""
    done = [{"event": "done", "part": p["name"], "seconds": 2.5 + i, "done": i + 1,
             "total": 3} for i, p in enumerate(PLAN["parts"])]
    code = (f"import json, sys, time\n"
            f"print(json.dumps({PLAN!r}), flush=True)\n"
            f"for ev in {done!r}:\n"
            f"    time.sleep({pause})\n"
            f"    print(json.dumps(ev), flush=True)\n"
            f"print('kernels ready in 9.9 s', flush=True)\n"
            f"sys.exit({1 if fail else 0})\n")
    return [sys.executable, "-c", code]


def test_health_reports_the_warming_state_part_by_part():
    settings = settings_for_tests(warm_kernels=True, kernels_warm=False, warm_workers=False,
                                  warmup_command=scripted(1.0), log_level="info")
    seen = []
    # the explorer's logger writes to stderr itself (app.main._log_to_stderr, no propagation)
    records: list[logging.LogRecord] = []
    catch = logging.Handler()
    catch.emit = records.append
    logging.getLogger("rolling.kernels").addHandler(catch)
    with TestClient(create_app(settings)) as client:
        deadline = time.monotonic() + 60
        while time.monotonic() < deadline:
            k = client.get("/api/health").json()["kernels"]
            seen.append(k)
            if k["state"] == "done":
                break
            time.sleep(0.2)
    logging.getLogger("rolling.kernels").removeHandler(catch)
    states = [k["state"] for k in seen]
    assert states[-1] == "done", states
    running = [k for k in seen if k["state"] == "running"]
    assert running, states
    # while the structure part compiles, its cases are warming; after it, they are not
    first = running[0]
    assert first["parts_total"] == 3 and first["parts_done"] < 2
    assert "sphere/routh-ball" in first["warming_cases"]
    assert "general kernels" in first["warming_parts"] or first["parts_done"] >= 1
    after = [k for k in seen if k["parts_done"] >= 2]
    assert after and all(k["warming_cases"] == [] for k in after)
    # the estimate is the structure part measured here (3.5 s), once it is done
    assert seen[-1]["estimate_s"] == 3.5
    assert seen[-1]["parts_done"] == 3 and seen[-1]["warming_parts"] == []
    # the terminal: one progress line per finished part, with the bar
    lines = [r.getMessage() for r in records]
    ticks = [m for m in lines if m.startswith("compiling kernels: ") and " of 3 parts " in m]
    assert [t.split(" of ")[0] for t in ticks] == [
        "compiling kernels: 0", "compiling kernels: 1", "compiling kernels: 2",
        "compiling kernels: 3"], lines
    assert bar(2, 3) in ticks[2]
    assert any(m.startswith("compiling kernels: done, 3 parts") for m in lines), lines


def test_a_failed_warm_up_is_reported_and_the_server_serves():
    settings = settings_for_tests(warm_kernels=True, kernels_warm=False, warm_workers=False,
                                  warmup_command=scripted(0.0, fail=True))
    with TestClient(create_app(settings)) as client:
        deadline = time.monotonic() + 30
        while (k := client.get("/api/health").json()["kernels"])["state"] != "failed":
            assert k["state"] in ("starting", "running", "failed"), k
            assert time.monotonic() < deadline, k
            time.sleep(0.1)
        assert "exited with code 1" in k["message"]
        assert client.get("/").status_code == 200


def test_without_a_warm_up_health_says_off():
    with TestClient(create_app(settings_for_tests(warm_workers=False))) as client:
        k = client.get("/api/health").json()["kernels"]
    assert k["state"] == "off" and k["warming_cases"] == [] and k["parts_total"] == 0


def test_case_readiness_follows_the_parts():
    w = KernelWarmup()
    w.expect()
    assert not w.case_ready("plane/chaplygin-ball") or w.warming_cases() == []
    w._event(PLAN)
    assert not w.case_ready("sphere/routh-ball") and w.case_ready("plane/round-disk")
    w._event({"event": "done", "part": "plane/chaplygin-ball", "seconds": 12.0, "done": 1,
              "total": 3})
    assert w.case_ready("sphere/routh-ball") and w.estimate_s() == 12.0
    assert not w.part_done("general kernels")


def test_warmup_progress_lines():
    """The command the explorer starts (solvers/warmup.py's hook, in spawned processes):
    the plan first (every part, with its cases), then one "done" per part, counted; on this
    machine's warm caches it compiles nothing new."""
    import os
    import subprocess
    from pathlib import Path

    root = str(Path(__file__).resolve().parents[1])
    out = subprocess.run(KernelWarmup().command(), cwd=root,
                         env={**os.environ, "PYTHONPATH": root}, capture_output=True,
                         text=True, timeout=900, check=True).stdout.splitlines()
    events = [json.loads(line) for line in out if line.startswith("{")]
    plan, done = events[0], events[1:]
    assert plan["event"] == "plan" and plan["total"] == len(plan["parts"]) == len(done)
    assert plan["parts"][0]["name"] == "general kernels"
    assert [d["done"] for d in done] == list(range(1, plan["total"] + 1))
    assert {d["part"] for d in done} == {p["name"] for p in plan["parts"]}
    assert out[-1].startswith("kernels ready in ")
