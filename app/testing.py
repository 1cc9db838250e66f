"""Helpers for tests, benches and demos: an app with test settings, and a real uvicorn
server in a subprocess on a free loopback port (safe under pytest-xdist: every server
gets its own port from the kernel)."""

from __future__ import annotations

import contextlib
import json
import os
import socket
import subprocess
import sys
import tempfile
import time
from collections.abc import Callable, Iterator
from pathlib import Path

import httpx

from app.core.config import Settings

# quiet, quick defaults for tests: no background verification, no disk cache
# ("testserver" is the Host of Starlette's TestClient)
# (no start-up compression of the static files: a test that needs it asks for it)
# (the kernels were compiled by ./dev test's warm-up: no background warm-up)
TEST_SETTINGS = {"verify_on_start": False, "use_verdict_cache": False, "workers": 2,
                 "precompress": False, "warm_kernels": False, "kernels_warm": True,
                 "deadline_s": 20.0, "log_level": "warning",
                 "allowed_hosts": ["127.0.0.1", "localhost", "::1", "testserver"],
                 # /guide/ as on a machine without the built guide, whatever site/ holds
                 # (a test that wants the built guide names its directory)
                 "guide_dir": str(Path(tempfile.gettempdir()) / "rolling-hierarchy-no-guide")}


def settings_for_tests(**overrides) -> Settings:
    cache = Path(tempfile.gettempdir()) / "rolling-hierarchy-test-cache"
    return Settings(**{**TEST_SETTINGS, "cache_dir": cache, **overrides})


def free_port() -> int:
    with socket.socket(socket.AF_INET, socket.SOCK_STREAM) as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


@contextlib.contextmanager
def live_server(timeout: float = 60.0, plain_uvicorn: bool = False,
                cwd: Path | None = None, extra_env: dict | None = None,
                prefix: list[str] | None = None, log_path: Path | None = None,
                **settings) -> Iterator[str]:
    """Start the explorer's server (app.core.server: uvicorn app.main:app with its bounds)
    on 127.0.0.1 and a free port with ROLLING_* settings;
    yield its base URL once /api/health answers; stop it (SIGTERM, then SIGKILL).
    cwd, extra_env: where it runs and more environment (a copy of the sources with
    PYTHONPATH on it: tests/test_cold_prepare.py). prefix: a command the server is
    started under (an `unshare` that mounts its kernel cache read-only first:
    tests/test_kernel_cache_faults.py); log_path: the server's stderr goes to this file,
    for the test to read."""
    port = free_port()
    # pydantic-settings reads a list or dict from the environment as JSON
    env = {**os.environ, **(extra_env or {}), **{f"ROLLING_{k.upper()}":
                            json.dumps(v) if isinstance(v, list | dict) else str(v)
                            for k, v in {**TEST_SETTINGS, **settings}.items()}}
    env.setdefault("ROLLING_CACHE_DIR",
                   str(Path(tempfile.gettempdir()) / "rolling-hierarchy-test-cache"))
    # a file, not a pipe: a chatty server never blocks
    log = open(log_path, "w+b") if log_path is not None else tempfile.TemporaryFile()
    proc = subprocess.Popen(
        # plain_uvicorn: uvicorn's defaults (httptools, no bounds), for bench/load.py's
        # comparison only
        [*(prefix or []), sys.executable, "-m",
         "uvicorn" if plain_uvicorn else "app.core.server",
         *(["app.main:app"] if plain_uvicorn else []), "--host", "127.0.0.1",
         "--port", str(port), "--log-level", "warning"],
        env=env, stdout=subprocess.DEVNULL, stderr=log, cwd=cwd)
    url = f"http://127.0.0.1:{port}"

    def log_text() -> str:
        log.seek(0)
        return log.read().decode()

    try:
        wait_answering(url, proc, timeout, log_text)
        yield url
    finally:
        proc.terminate()
        try:
            proc.wait(10)
        except subprocess.TimeoutExpired:
            proc.kill()
            proc.wait(5)
        log.close()


def wait_answering(url: str, proc: subprocess.Popen, timeout: float,
                   log_text: Callable[[], str] = lambda: "") -> None:
    """Until the server process `proc` answers GET /api/health with 200; RuntimeError (with
    the end of log_text()) if it exits first or `timeout` seconds pass."""
    deadline = time.monotonic() + timeout
    while True:
        if proc.poll() is not None:
            raise RuntimeError(f"uvicorn exited with {proc.returncode}: {log_text()[-2000:]}")
        try:
            if httpx.get(f"{url}/api/health", timeout=1.0).status_code == 200:
                return
        except httpx.TransportError:
            pass
        if time.monotonic() > deadline:
            raise RuntimeError("uvicorn did not answer /api/health in time")
        time.sleep(0.1)


def wait_idle(url: str, timeout: float = 30.0) -> dict:
    """Wait until the server's worker pool is idle (warm-up done); return /api/health."""
    deadline = time.monotonic() + timeout
    while True:
        h = httpx.get(f"{url}/api/health", timeout=2.0).json()
        p = h["pool"]
        if p["running"] == 0 and p["waiting"] == 0 and p["warming"] == 0:
            return h
        if time.monotonic() > deadline:
            return h
        time.sleep(0.1)
