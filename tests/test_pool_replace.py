"""A dead worker is logged and replaced by a warmed one (issue 21): before, a worker killed
in mid-request left the pool at one process, nothing was logged, and the next concurrent
request paid a cold start (1.0-1.9 s) in a process that had not loaded the kernels."""

import logging
import os
import signal
import time

import anyio
import anyio.to_process
import pytest
from conftest import run_async

from app.core.pool import WorkerCrashed, WorkerPool

WARMED = False


def warm_slowly() -> int:
    """Stands for app.services.jobs.warm: a second of loading, then the process is warm."""
    global WARMED
    time.sleep(0.5)
    WARMED = True
    return os.getpid()


def pid_and_warm() -> tuple[int, bool]:
    time.sleep(0.3)          # long enough that two jobs need two processes
    return os.getpid(), WARMED


def die() -> None:
    os.kill(os.getpid(), signal.SIGKILL)


def test_a_dead_worker_is_logged_and_replaced_by_a_warm_one(caplog):
    logger = logging.getLogger("rolling")
    logger.addHandler(caplog.handler)      # the app's logger may not propagate
    caplog.set_level(logging.INFO, logger="rolling")

    async def main():
        pool = WorkerPool(workers=2, queue_size=2, warm=warm_slowly)
        async with anyio.create_task_group() as tg:
            pool.attach(tg)
            async with anyio.create_task_group() as warmups:
                warmups.start_soon(pool.prewarm)
                warmups.start_soon(pool.prewarm)
            assert pool.live_workers() == 2
            with pytest.raises(WorkerCrashed):
                await pool.run(die)
            with anyio.fail_after(30):
                await anyio.sleep(0.05)
                while pool.live_workers() < 2 or pool.stats().warming:
                    await anyio.sleep(0.05)
            got: list[tuple[int, bool]] = []

            async def one():
                got.append(await pool.run(pid_and_warm))

            async with anyio.create_task_group() as jobs:
                jobs.start_soon(one)
                jobs.start_soon(one)
            stats = pool.stats()
            tg.cancel_scope.cancel()
        return got, stats

    try:
        got, stats = run_async(main)
    finally:
        logger.removeHandler(caplog.handler)
    assert len({pid for pid, _ in got}) == 2
    assert all(warm for _, warm in got), "a request ran in a cold process after the death"
    assert stats.crashed == 1 and stats.replaced == 1
    assert "worker process died" in caplog.text and "new warm worker" in caplog.text
