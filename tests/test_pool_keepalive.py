"""Workers stay warm (issue 9): anyio's process pool kills a worker idle for 5 minutes, and
the next request then paid a cold start (a new process, the kernels loaded again). The
pool keeps its workers: after a long idle time the same processes answer."""

import os
import time

import anyio
import anyio.to_process
import pytest
from conftest import run_async

from app.core.pool import WorkerPool


def pid_after(seconds: float) -> int:
    time.sleep(seconds)
    return os.getpid()


def test_idle_workers_are_kept(monkeypatch):
    async def main():
        pool = WorkerPool(workers=2, queue_size=2)
        first: set[int] = set()

        async def one(into):
            into.add(await pool.run(pid_after, 0.3))

        async with anyio.create_task_group() as tg:   # two at once: two processes
            tg.start_soon(one, first)
            tg.start_soon(one, first)
        assert len(first) == 2
        # ten idle minutes pass (the clock anyio's pool prunes by)
        now = anyio.current_time()
        monkeypatch.setattr(anyio.to_process, "current_time", lambda: now + 600.0)
        later: set[int] = set()
        await one(later)
        async with anyio.create_task_group() as tg:
            tg.start_soon(one, later)
            tg.start_soon(one, later)
        assert later == first, "a worker was pruned and replaced by a cold one"

    run_async(main)


@pytest.fixture(autouse=True)
def _restore_idle_time():
    saved = anyio.to_process.WORKER_MAX_IDLE_TIME
    yield
    anyio.to_process.WORKER_MAX_IDLE_TIME = saved
