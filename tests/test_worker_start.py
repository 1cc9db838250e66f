"""A worker process that cannot be started (no access to the interpreter, out of file
handles or memory) is a 503 with Retry-After and a message, /api/health says so, and the
pool tries again with a growing wait until a start succeeds (before: a plain-text 500 from
every run, and health said ok with 2 workers)."""

import errno
import os

import anyio
import pytest
from conftest import run_async
from fastapi.testclient import TestClient

from app.core import pool as pool_module
from app.core.pool import WorkerPool, WorkerUnavailable

pytestmark = pytest.mark.filterwarnings("ignore::DeprecationWarning")

RUN = {"case": "plane/chaplygin-ball", "example": True, "t_end": 1.0, "samples": 5}


class FailingStarts:
    """start_worker_process failing with EMFILE while `failing` is set; counts calls."""

    def __init__(self):
        self.failing = True
        self.calls = 0
        self.original = pool_module.start_worker_process

    async def __call__(self, command, **kwargs):
        self.calls += 1
        if self.failing:
            raise OSError(errno.EMFILE, "Too many open files")
        return await self.original(command, **kwargs)


@pytest.fixture
def starts(monkeypatch):
    fake = FailingStarts()
    monkeypatch.setattr(pool_module, "start_worker_process", fake)
    return fake


def test_the_pool_says_503_and_retries_with_backoff(starts, monkeypatch):
    monkeypatch.setattr(pool_module, "START_BACKOFF_S", 0.5)

    async def main():
        pool = WorkerPool(1, 2, warm=None)
        async with anyio.create_task_group() as tg:
            pool.attach(tg)
            with pytest.raises(WorkerUnavailable) as first:
                await pool.run(os.getpid)
            assert first.value.retry_after >= 1 and "Too many open files" in str(first.value)
            st = pool.stats()
            assert pool.degraded and st.start_failures == 1 and st.retry_in_s is not None
            calls = starts.calls
            with pytest.raises(WorkerUnavailable):     # within the wait: no new attempt
                await pool.run(os.getpid)
            assert starts.calls == calls
            # the pool tries again by itself, waiting longer after each failure
            with anyio.fail_after(10):
                while starts.calls < calls + 2:
                    await anyio.sleep(0.05)
            assert pool._backoff > 1.0
            starts.failing = False
            with anyio.fail_after(30):
                while pool.degraded:
                    await anyio.sleep(0.05)
            assert await pool.run(os.getpid) != os.getpid()
            assert pool.stats().start_error == "" and pool.stats().alive == 1
            await pool.close()
            tg.cancel_scope.cancel()

    run_async(main)


def test_the_api_answers_503_with_retry_after_and_health_says_degraded(starts):
    from app.main import create_app
    from app.testing import settings_for_tests

    with TestClient(create_app(settings_for_tests(warm_workers=False))) as c:
        r = c.post("/api/simulate", json=RUN)
        assert r.status_code == 503, r.text
        assert int(r.headers["retry-after"]) >= 1
        assert "no worker process can be started" in r.json()["detail"]
        assert "Too many open files" in r.json()["detail"]
        h = c.get("/api/health").json()
        assert h["status"] == "degraded" and "workers" in h["degraded"], h
        assert "Too many open files" in h["pool"]["start_error"]
        r = c.post("/api/poincare", json={"case": "plane/chaplygin-ball", "example": True,
                                          "trajectories": 1, "points": 3})
        assert r.status_code == 503 and "retry-after" in r.headers, r.text
        starts.failing = False


def test_a_stream_says_503_and_when_to_come_back(starts):
    import json

    from app.main import create_app
    from app.testing import settings_for_tests

    with TestClient(create_app(settings_for_tests(warm_workers=False))) as c:
        r = c.post("/api/poincare?stream=true", json={
            "case": "plane/chaplygin-ball", "example": True, "trajectories": 1, "points": 3})
        events = [json.loads(line) for line in r.text.splitlines() if line.strip()]
        error = events[-1]
        assert error["event"] == "error" and error["status"] == 503, events
        assert error["retry_after"] >= 1 and "no worker process" in error["detail"]
        starts.failing = False


def _sleep(seconds: float) -> int:
    import time

    time.sleep(seconds)
    return os.getpid()


def test_a_job_stopped_by_the_servers_stop_says_so_not_a_crash():
    """Before: on SIGTERM a stream's error event said "the worker process died ... can be
    retried"; the workers were killed by the server's own stop."""
    from app.core.pool import WorkerCrashed

    async def main():
        pool = WorkerPool(1, 1)
        caught: list[BaseException] = []

        async def job():
            try:
                await pool.run(_sleep, 30.0)
            except WorkerCrashed as exc:
                caught.append(exc)

        async with anyio.create_task_group() as tg:
            pool.attach(tg)
            tg.start_soon(job)
            with anyio.fail_after(60):
                while not (pool.stats().running and pool.live_workers()):
                    await anyio.sleep(0.05)
                await anyio.sleep(0.5)
                pool.kill_all()
                while not caught:
                    await anyio.sleep(0.05)
        assert "the server is stopping" in str(caught[0]), caught
        assert "died" not in str(caught[0]) and pool.stats().crashed == 0

    run_async(main)


def test_verifications_have_their_share_and_cannot_starve_the_runs():
    """Before: 12 concurrent verifications left 9 of 12 simulations with 503 for 14 s.
    With two workers, verifications hold at most one (and two waiting places): the runs
    keep a worker and their whole queue."""
    from app.core.pool import QueueFull

    async def main():
        pool = WorkerPool(2, 8, shares={"verify": (1, 2)})
        outcome = {"verify_ok": 0, "verify_busy": 0, "run_ok": 0, "run_busy": 0}

        async def job(kind, seconds):
            try:
                await pool.run(_sleep, seconds, share="verify" if kind == "verify" else None)
                outcome[f"{kind}_ok"] += 1
            except QueueFull as exc:
                if kind == "verify":
                    assert "verifications" in str(exc)
                outcome[f"{kind}_busy"] += 1

        async with anyio.create_task_group() as tg:
            pool.attach(tg)
            for _ in range(12):
                tg.start_soon(job, "verify", 1.5)
            await anyio.sleep(0.2)
            t0 = anyio.current_time()
            async with anyio.create_task_group() as runs:
                for _ in range(8):
                    runs.start_soon(job, "run", 0.05)
            runs_took = anyio.current_time() - t0
        await pool.close()
        return outcome, runs_took

    outcome, runs_took = run_async(main)
    assert outcome["run_busy"] == 0 and outcome["run_ok"] == 8, outcome
    assert outcome["verify_ok"] == 3 and outcome["verify_busy"] == 9, outcome
    # the runs never waited for a verification to end (each holds its worker 1.5 s)
    assert runs_took < 1.4 + 8 * 0.05 + 2.0, runs_took
