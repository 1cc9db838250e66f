"""SIGTERM of `rolling serve` while it compiles stops it within seconds and leaves no process
behind (issue 19; app/main.py's _stop_now, app/core/pool.py's kill_all,
app/services/kernel_warmup.py's stop and reap).

The server runs with an empty kernel cache, so that the generated kernels compile: the
background warm-up (a subprocess in its own session, with its spawned compile processes),
the start-up validation (a thread of the server), and a simulate request's prepare job in a
pool worker (compiling its small kernel, then a run of minutes). SIGTERM comes while they
compile. Before, the server took 17 s to exit here
(it waited for the validation's compile and for the request's prepare job) and its
workers outlived it until their job ended. The general kernels come from this checkout's
numba cache: a fresh copy of the sources (tests/test_cold_prepare.py) would add a cold
start of 20-40 s on 2 cores to the CI and nothing to the check. No compile is waited
for."""

import os
import signal
import subprocess
import sys
import threading
import time
from pathlib import Path

import httpx
import pytest

from app.testing import free_port, wait_answering

pytestmark = pytest.mark.slow

BOUND_S = 2.5       # the aim is 1-2 s; 0.4-0.8 s measured at load 14 on 2 cores


def _procs() -> dict[int, tuple[int, int, str]]:
    """pid -> (ppid, process group, state) of every process (/proc)."""
    out = {}
    for stat in Path("/proc").glob("[0-9]*/stat"):
        try:
            text = stat.read_text()
        except OSError:
            continue
        fields = text.rsplit(")", 1)[1].split()
        out[int(stat.parent.name)] = (int(fields[1]), int(fields[2]), fields[0])
    return out


def _family(root: int) -> set[int]:
    """The descendants of `root`, and every member of their process groups (the warm-up's
    compile processes are its children, in the warm-up's own session)."""
    procs = _procs()
    found, todo = set(), [root]
    while todo:
        p = todo.pop()
        for pid, (ppid, _, _) in procs.items():
            if ppid == p and pid not in found:
                found.add(pid)
                todo.append(pid)
    groups = {procs[p][1] for p in found if p in procs}
    return found | {pid for pid, (_, pgrp, _) in procs.items()
                    if pgrp in groups and pid != root and procs[root][1] != pgrp}


def _alive(pids: set[int]) -> set[int]:
    procs = _procs()
    return {p for p in pids if p in procs and procs[p][2] != "Z"}


def _serve(tmp_path, src: Path | None, extra: dict | None = None, preexec_fn=None):
    """`rolling serve` on a free port with empty kernel caches (src: a fresh copy of the
    sources, whose numba caches are empty too; None: this checkout's, warm); extra: more
    environment; preexec_fn: run in the child before the server starts."""
    port = free_port()
    root = src or Path(__file__).resolve().parents[1]
    env = {**os.environ, "PYTHONPATH": str(root),
           "ROLLING_KERNEL_CACHE": str(tmp_path / "kernels"),
           "XDG_CACHE_HOME": str(tmp_path / "xdg"),
           "ROLLING_CACHE_DIR": str(tmp_path / "cache"), "ROLLING_VERIFY_ON_START": "false",
           "ROLLING_USE_VERDICT_CACHE": "false", "ROLLING_PRECOMPRESS": "false",
           "ROLLING_WORKERS": "2", "ROLLING_LOG_LEVEL": "info",
           "ROLLING_WARMUP_JOBS": "2"}      # compile processes, whatever the CPU count
    if src is not None:
        env["NUMBA_CACHE_DIR"] = str(tmp_path / "numba")
    env.update(extra or {})
    log = open(tmp_path / "serve.log", "wb")     # closed by _stop
    server = subprocess.Popen(
        [sys.executable, "-c", "from app.cli import main; main()", "serve",
         "--port", str(port)], cwd=root, env=env, stdout=log, stderr=log,
        preexec_fn=preexec_fn)
    server.log = log
    return server, f"http://127.0.0.1:{port}"


def _wait_compiling(server, url: str, tmp_path, deadline: float) -> None:
    """Until the warm-up has listed its parts and started its compile processes."""
    while True:
        assert server.poll() is None, (tmp_path / "serve.log").read_text()[-2000:]
        assert time.monotonic() < deadline, (tmp_path / "serve.log").read_text()[-2000:]
        try:
            k = httpx.get(f"{url}/api/health", timeout=2.0).json()["kernels"]
            if k["state"] == "running" and len(_family(server.pid)) >= 4:
                return
        except httpx.TransportError:
            pass
        time.sleep(0.2)


def _stop(server, sig: int) -> tuple[float, set[int], set[int], str]:
    """Send `sig`; (seconds to exit, the processes before, those still alive after, log)."""
    family = _family(server.pid)
    try:
        assert len(family) >= 4, family       # workers, the warm-up and its processes
        t0 = time.monotonic()
        server.send_signal(sig)
        server.wait(60)
        took = time.monotonic() - t0
        time.sleep(0.5)     # the last SIGKILLed processes are gone by now
        left = _alive(family)
    finally:
        if server.poll() is None:
            server.kill()
        for p in _alive(family):
            os.kill(p, signal.SIGKILL)
        server.log.close()
    text = Path(server.log.name).read_text()
    print(f"{signal.Signals(sig).name} to exit: {took:.2f} s; {len(family)} processes, "
          f"left: {sorted(left)}")
    return took, family, left, text


def test_sigterm_while_compiling_stops_in_seconds_and_leaves_no_process(tmp_path):
    # a step budget and a deadline that let the request below run for minutes: its job is
    # in a worker when SIGTERM comes, however fast the machine (a scene of the example,
    # asked before, loaded its general kernels from this checkout's cache and answered 200
    # in about a second on a fast machine, before the signal)
    server, url = _serve(tmp_path, None, {"ROLLING_MAX_STEPS": str(10**10),
                                          "ROLLING_DEADLINE_S": "600"})
    try:
        _wait_compiling(server, url, tmp_path, time.monotonic() + 300)
        # a request whose small kernel is not compiled (the kernel cache is empty): its
        # prepare job compiles it in a worker, then its run (T = 1e7 at rtol 1e-13, about
        # 10^8 steps) goes on in a worker
        answers = []

        def ask():
            try:
                answers.append(httpx.post(f"{url}/api/simulate", timeout=120.0, json={
                    "case": "plane/chaplygin-ball", "example": True, "t_end": 1e7,
                    "rtol": 1e-13, "atol": 1e-13, "samples": 2}).status_code)
            except httpx.TransportError as exc:
                answers.append(repr(exc))
        asker = threading.Thread(target=ask)
        asker.start()
        deadline = time.monotonic() + 120
        while httpx.get(f"{url}/api/health", timeout=2.0).json()["pool"]["running"] < 1:
            assert time.monotonic() < deadline
            assert not answers, answers     # it answered before its job ran
            time.sleep(0.1)
        time.sleep(1.0)     # the prepare job compiles, or the run has begun
        assert not answers, answers         # the job is still in its worker
    except BaseException:
        server.kill()
        raise
    took, _, left, text = _stop(server, signal.SIGTERM)
    asker.join(30)
    assert took < BOUND_S, (took, text[-3000:])
    assert not left, (left, text[-3000:])
    # the request whose job was killed was not left hanging: 503 (the server is
    # stopping), or its connection closed
    assert answers and (answers[0] == 503 or "Error(" in str(answers[0])), answers


def test_ctrl_c_while_the_warm_up_compiles_stops_in_seconds(tmp_path):
    """Ctrl-C (SIGINT), on this checkout's warm numba caches with an empty kernel cache:
    the warm-up compiles the small kernels. uvicorn re-raises the interrupt after its
    shutdown; the interpreter's teardown then took 2-4 s more (app/cli/serve.py's serve exits
    at once instead)."""
    server, url = _serve(tmp_path, None)
    try:
        _wait_compiling(server, url, tmp_path, time.monotonic() + 300)
    except BaseException:
        server.kill()
        raise
    took, _, left, text = _stop(server, signal.SIGINT)
    assert server.returncode == 130, text[-3000:]
    assert took < BOUND_S, (took, text[-3000:])
    assert not left, (left, text[-3000:])


def test_ctrl_c_exits_130_when_started_with_sigint_ignored(tmp_path):
    """A shell's background job starts with SIGINT ignored; uvicorn still stops on it, then
    restores that disposition before re-raising the signal, which then did nothing: the
    server exited 0 (seen once in a full run, test above). It exits 130, as on a terminal."""
    server, url = _serve(tmp_path, None, extra={"ROLLING_WARM_KERNELS": "false"},
                         preexec_fn=lambda: signal.signal(signal.SIGINT, signal.SIG_IGN))
    try:
        wait_answering(url, server, 120, (tmp_path / "serve.log").read_text)
        server.send_signal(signal.SIGINT)
        server.wait(60)
    finally:
        if server.poll() is None:
            server.kill()
        server.log.close()
    text = (tmp_path / "serve.log").read_text()
    assert server.returncode == 130, text[-3000:]
    assert "error: interrupted" in text
