"""A kernel cache that cannot be written degrades the service, it does not break it: a
real server on an unwritable cache (a path under a file: unwritable for root too; a filled
cache on a read-only bind mount, where the machine allows one) answers simulate, scene and
Poincare with 200, says once in its log why, and /api/health reports "degraded" with the
reason (before: every default run was a plain-text 500 from numba's "no locator available",
and health said "ok")."""

import contextlib
import os
import shutil
import subprocess
import sys
import tempfile
from pathlib import Path

import httpx
import pytest

from app.testing import live_server, wait_idle

RUNS = [("/api/simulate", {"case": "plane/chaplygin-ball", "example": True, "t_end": 1.0,
                           "samples": 5}),
        ("/api/scene", {"case": "plane/chaplygin-ball", "example": True, "t_end": 1.0,
                        "frames": 5, "samples": 5}),
        ("/api/poincare", {"case": "plane/chaplygin-ball", "example": True,
                           "trajectories": 1, "points": 5})]
WARNING = "the kernel cache cannot be used"


def _unwritable(path: Path) -> bool:
    """Whether a file cannot be made in `path` by this process (root included)."""
    try:
        path.mkdir(parents=True, exist_ok=True)
        with tempfile.TemporaryFile(dir=path):
            return False
    except OSError:
        return True


def _can_mount_read_only() -> bool:
    if shutil.which("unshare") is None:
        return False
    probe = subprocess.run(["unshare", "-m", "sh", "-c", "d=$(mktemp -d) || exit 1; "
                            "mount --bind $d $d && mount -o remount,bind,ro $d && "
                            "! touch $d/x; r=$?; umount $d; rmdir $d; exit $r"],
                           capture_output=True)
    return probe.returncode == 0


@contextlib.contextmanager
def _serve(cache: str, tmp: Path, read_only_from: Path | None = None):
    """A server (app.testing.live_server) with the kernel cache at `cache`; read_only_from:
    a directory bind-mounted read-only at `cache` in the server's own mount namespace (the
    mount ends with the process). Yields its URL and a reader of its log."""
    prefix = None
    if read_only_from is not None:
        prefix = ["unshare", "-m", "sh", "-c", 'mount --bind "$1" "$2" && mount -o '
                  'remount,bind,ro "$2" && shift 2 && exec "$@"', "sh", str(read_only_from),
                  cache]
    log = tmp / "server.log"
    # the warm-up is asked for: on an unwritable cache it must not run; no warning said by
    # a parent process (module_cache.WARNED_ENV empty)
    with live_server(timeout=120, prefix=prefix, log_path=log,
                     extra_env={"ROLLING_KERNEL_CACHE": cache,
                                "ROLLING_KERNEL_CACHE_WARNED": ""},
                     warm_kernels=True, kernels_warm=False, warm_workers=True,
                     deadline_s=120, cache_dir=tmp / "app-cache") as url:
        yield url, lambda: log.read_text(errors="replace")


def _check_degraded_service(url, log_text, cache):
    wait_idle(url, timeout=300)
    for path, body in RUNS:
        r = httpx.post(f"{url}{path}", json=body, timeout=300)
        assert r.status_code == 200, (path, r.status_code, r.text[:500], log_text()[-3000:])
        if path == "/api/simulate":
            assert r.json()["stats"]["field"] == "general"
    h = httpx.get(f"{url}/api/health", timeout=10).json()
    assert h["status"] == "degraded" and "kernel_cache" in h["degraded"], h
    assert h["kernel_cache"]["state"] == "degraded" and cache in h["kernel_cache"]["message"]
    assert h["kernels"]["state"] == "off", h["kernels"]      # no warm-up into nowhere
    log = log_text()
    assert log.count(WARNING) == 1, log[-3000:]
    assert "Traceback" not in log and "no locator" not in log, log[-3000:]


def test_an_empty_cache_under_a_file(tmp_path):
    blocker = tmp_path / "a-file"
    blocker.write_text("not a directory")
    cache = str(blocker / "kernels")
    assert _unwritable(Path(cache))
    with _serve(cache, tmp_path) as (url, text):
        _check_degraded_service(url, text, cache)


@pytest.mark.skipif(not _can_mount_read_only(), reason="no read-only bind mount here")
def test_a_filled_cache_on_a_read_only_mount(tmp_path):
    filled = tmp_path / "filled"
    default = Path.home() / ".cache" / "rolling-hierarchy" / "kernels"
    if default.is_dir():        # what the warm-up left: sources and numba's files
        shutil.copytree(default, filled, symlinks=True,
                        ignore=shutil.ignore_patterns("taylor", "*.tmp"))
    else:
        filled.mkdir()
    mount_point = tmp_path / "kernels"
    mount_point.mkdir()
    with _serve(str(mount_point), tmp_path, read_only_from=filled) as (url, text):
        _check_degraded_service(url, text, str(mount_point))


def test_the_health_of_a_writable_cache_is_ok(tmp_path):
    from fastapi.testclient import TestClient

    from app.main import create_app
    from app.testing import settings_for_tests

    with TestClient(create_app(settings_for_tests(warm_workers=False))) as c:
        h = c.get("/api/health").json()
    assert h["status"] == "ok" and h["degraded"] == [] and h["kernel_cache"]["state"] == "ok"


LOST_MID_RUN = '''
import shutil
from solvers.kernels import jit, module_cache  # noqa: F401 (jit installs numba's cache)

src = "import numba\\n\\n@numba.njit(cache=True)\\ndef f(x):\\n    return x + 1\\n"
first = module_cache.cached_module("faults_probe_a", lambda: src)
cache = module_cache.cache_dir()
# numba's files of the module can no longer be written nor read: a file in their place
shutil.rmtree(cache / "__pycache__", ignore_errors=True)
(cache / "__pycache__").write_text("not a directory")
assert first.f(1) == 2
# the whole cache lost: a file where it was, so that it cannot be made again
for p in cache.iterdir():
    p.unlink()
cache.rmdir()
cache.write_text("gone")
second = module_cache.cached_module("faults_probe_b", lambda: src.replace("+ 1", "+ 2"))
assert second.f(1) == 3
print(sorted(module_cache.DEGRADED))
'''


def test_a_cache_lost_mid_run_costs_a_compile_not_the_run(tmp_path):
    env = {**os.environ, "ROLLING_KERNEL_CACHE": str(tmp_path / "kernels"),
           "PYTHONPATH": str(Path(__file__).resolve().parent.parent)}
    env.pop("ROLLING_KERNEL_CACHE_WARNED", None)
    proc = subprocess.run([sys.executable, "-c", LOST_MID_RUN], env=env,
                          capture_output=True, text=True, timeout=300)
    assert proc.returncode == 0, proc.stderr[-3000:]
    assert "writing" in proc.stdout and "sources" in proc.stdout, proc.stdout
    assert proc.stderr.count(WARNING) == 1, proc.stderr[-3000:]
