"""CPU work in worker processes, behind a bounded queue.

`WorkerPool.run(fn, *args, deadline=...)` ships `fn(*args)` (a module-level function of
app.services.jobs, pickled by reference) to one of `workers` processes of anyio's process
pool. At most `workers` run at once and at most `queue_size` more wait; beyond that the
call raises `QueueFull` at once (the route answers 503 with Retry-After). The deadline
counts from the moment a worker takes the job: when it passes, or when the caller is
cancelled (the client went away), anyio kills that worker process (SIGKILL) and starts a
fresh one for the next job. The event loop never runs the work itself.

A worker that dies in mid-job (killed from outside, out of memory) gives that job
`WorkerCrashed` (503 with Retry-After); the death is logged and, as after a deadline,
the pool starts and warms a new process at once (`refill`), so that the next request does
not pay a cold start (without the refill the pool stayed at one process and the next
concurrent request waited for a new one).

Idle workers are kept alive: anyio's pool kills a worker idle for 5 minutes, after which the
next request would pay a cold start (a new process, the compiled kernels loaded again). The
number of processes is bounded by `workers` anyway, so keeping them costs nothing.

Stopping (Ctrl-C, SIGTERM: app.main): `kill_all()` kills every worker at once, running or
idle, and the pool neither replaces them nor starts a job after that (a prepare job may
compile for a minute; a worker holds nothing that needs saving). Without it the workers
outlived the server: uvicorn ends the process by the re-raised signal before anyio's own
clean-up runs, and a worker only exits when it reads the end of its input, after its job.
"""

from __future__ import annotations

import contextlib
import logging
import math
import os
import threading
from collections.abc import Callable
from dataclasses import dataclass

import anyio
import anyio.abc
import anyio.from_thread
import anyio.lowlevel
from anyio import to_process

log = logging.getLogger("rolling")


class QueueFull(Exception):
    """Every worker is busy and the waiting room is full (or the places of one share)."""

    def __init__(self, retry_after: int, capacity: int, share: str | None = None):
        of = f" for {SHARE_NAMES.get(share, share)}" if share else ""
        super().__init__(f"all {capacity} places{of} (running and waiting) are taken; "
                         f"retry in {retry_after} s")
        self.retry_after = retry_after


# what a share's jobs are, in a refusal
SHARE_NAMES = {"verify": "verifications"}


class DeadlineExceeded(Exception):
    """The job ran longer than its deadline; its worker was killed."""

    def __init__(self, deadline: float,
                 hint: str = "shorten t_end, loosen rtol or use fewer samples"):
        super().__init__(f"the computation needed more than the {deadline:g} s one request "
                         f"may take and was stopped; {hint}")
        self.deadline = deadline


class WorkerCrashed(Exception):
    """The worker process died without an answer (killed from outside, out of memory)."""


class WorkerUnavailable(Exception):
    """No worker process could be started (the interpreter not accessible, out of file
    handles or memory): 503 with Retry-After; the pool tries again in the background."""

    def __init__(self, reason: str, retry_after: int):
        super().__init__(f"no worker process can be started ({reason}); the server tries "
                         f"again by itself: retry in {retry_after} s")
        self.reason = reason
        self.retry_after = retry_after


class _StartFailed(Exception):
    """Raised through anyio's pool when the start of a worker process fails (not an
    OSError: a job's own OSError must not be taken for it)."""


async def start_worker_process(command, **kwargs):
    """Start one worker process (anyio's open_process, which anyio's pool calls for each
    new worker). A test replaces it to make the start fail."""
    return await _open_process(command, **kwargs)


async def _open_worker(command, **kwargs):
    try:
        return await start_worker_process(command, **kwargs)
    except OSError as exc:
        raise _StartFailed(f"{type(exc).__name__}: {exc}") from exc


_open_process = to_process.open_process
# anyio's pool starts its processes by this name of its module: the start is ours to
# watch (a failure is _StartFailed, then WorkerUnavailable, not an OSError from the job)
to_process.open_process = _open_worker

# retrying a failed start: 1 s, doubled after each failure, at most START_BACKOFF_MAX_S
START_BACKOFF_S = 1.0
START_BACKOFF_MAX_S = 30.0


STOPPING = ("the server is stopping: the computation was stopped with it; retry once "
            "the server is back")


def _pid() -> int:
    """A job that only starts a worker (the pool's retry when it has no warm-up)."""
    return os.getpid()


async def in_daemon_thread(work: Callable):
    """work() in a daemon thread, awaited. A cancelled wait abandons the thread: a numba
    compile in it cannot be interrupted, and a daemon thread does not hold up the
    interpreter's exit (anyio's worker threads do: after Ctrl-C the process waited for
    the start-up validation to finish compiling)."""
    done = anyio.Event()
    box: dict = {}
    token = anyio.lowlevel.current_token()

    def target() -> None:
        try:
            box["value"] = work()
        except BaseException as exc:   # handed to the waiting task
            box["error"] = exc
        finally:
            with contextlib.suppress(Exception):    # the loop is gone: nobody waits
                anyio.from_thread.run_sync(done.set, token=token)

    threading.Thread(target=target, name=f"rolling: {getattr(work, '__name__', 'work')}",
                     daemon=True).start()
    await done.wait()
    if "error" in box:
        raise box["error"]
    return box.get("value")


@dataclass
class PoolStats:
    workers: int
    queue_size: int
    running: int
    waiting: int
    warming: int
    completed: int
    rejected: int
    cancelled: int
    timed_out: int
    crashed: int = 0
    replaced: int = 0
    alive: int = 0
    start_failures: int = 0
    start_error: str = ""
    retry_in_s: float | None = None


class WorkerPool:
    def __init__(self, workers: int, queue_size: int, retry_after: int = 2,
                 warm: Callable | None = None,
                 shares: dict[str, tuple[int, int]] | None = None):
        # anyio reads this module global whenever it hands out a worker (see module doc)
        to_process.WORKER_MAX_IDLE_TIME = math.inf
        self.workers = workers
        # run in a fresh worker after one was killed, so that the next job does not spend
        # its deadline starting a process and loading the compiled kernels
        self.warm = warm
        self._tg: anyio.abc.TaskGroup | None = None
        self.queue_size = queue_size
        self.retry_after = retry_after
        # the queue: jobs wait here for a worker (their deadline has not started)
        self._slots = anyio.CapacityLimiter(workers)
        # handed to anyio's pool so it never starts more than `workers` processes; a job
        # holds a slot first, so this one is always free when it is asked
        self._procs = anyio.CapacityLimiter(workers)
        self._admitted = 0
        self._running = 0
        self._completed = self._rejected = self._cancelled = self._timed_out = 0
        self._warming = 0
        self._crashed = self._replaced = 0
        self.closing = False    # the server is stopping: no job starts, no worker is replaced
        # a worker that cannot be started: the last failure, and when to try again
        self._start_failures = 0
        self.start_error = ""
        self._backoff = START_BACKOFF_S
        self._retry_at: float | None = None
        self._retrying = False
        # shares: a kind of job (run(..., share=name)) that may hold at most `running`
        # workers and `waiting` more places, so that it cannot starve the others (long
        # verifications against the runs); its jobs wait for their share outside the
        # queue, then queue like any job
        self._shares = {name: (anyio.CapacityLimiter(running), running + waiting)
                        for name, (running, waiting) in (shares or {}).items()}
        self._share_admitted = dict.fromkeys(self._shares, 0)

    def attach(self, tg: anyio.abc.TaskGroup) -> None:
        """Background tasks (re-warming) run in this task group (the app's lifespan)."""
        self._tg = tg

    def _replace_killed_worker(self) -> None:
        if self.warm is not None and self._tg is not None and not self.closing:
            self._tg.start_soon(self.refill)

    @staticmethod
    def _processes() -> list:
        """anyio's worker processes of this event loop (none before the first job)."""
        try:
            return list(to_process._process_pool_workers.get())
        except LookupError:
            return []

    @classmethod
    def live_workers(cls) -> int:
        """Worker processes of anyio's pool that are alive (0 before the first job)."""
        return sum(1 for p in cls._processes() if p.returncode is None)

    def kill_all(self) -> int:
        """The server is stopping: kill every worker process now (SIGKILL), running or idle;
        from here on no job starts and no worker is replaced. In the event loop's thread.
        Returns how many were killed."""
        self.closing = True
        killed = 0
        for proc in self._processes():
            if proc.returncode is None:
                with contextlib.suppress(ProcessLookupError):
                    proc.kill()
                    killed += 1
        return killed

    async def close(self, timeout: float = 2.0) -> None:
        """kill_all(), then wait (at most `timeout` s) until the processes are gone."""
        self.kill_all()
        with anyio.move_on_after(timeout):
            for proc in self._processes():
                await proc.wait()

    async def refill(self) -> None:
        """Bring the pool back to `workers` warm processes after one was killed or died.
        As many warm-ups as there are workers run at once: the idle processes take some
        (a warm process finishes in milliseconds), the rest start new processes, which
        the next jobs then find warm."""
        missing = self.workers - self.live_workers()
        if missing <= 0 or self.warm is None:
            return
        try:
            async with anyio.create_task_group() as tg:
                for _ in range(self.workers):
                    tg.start_soon(self.prewarm)
        except Exception as exc:  # the next job will start its own worker
            log.warning("replacing a worker failed: %r", exc)
            return
        self._replaced += missing
        log.info("worker pool: %d new warm worker process(es), %d of %d alive", missing,
                 self.live_workers(), self.workers)

    async def prewarm(self) -> None:
        """Start one worker process and load the kernels in it (no deadline, not counted
        against the queue)."""
        if self.warm is None or self.closing:
            return
        self._warming += 1
        try:
            async with self._slots:
                await to_process.run_sync(self.warm, cancellable=True, limiter=self._procs)
        except _StartFailed as exc:    # said in the log and the health; retried
            self._start_failed(str(exc))
        finally:
            self._warming -= 1

    async def starting(self, work: Callable) -> None:
        """Run the server's own start-up work (a function, in a thread), counted as warming
        in the stats: an idle pool then means a started one (app.testing.wait_idle)."""
        self._warming += 1
        try:
            await in_daemon_thread(work)
        finally:
            self._warming -= 1

    @property
    def capacity(self) -> int:
        return self.workers + self.queue_size

    def stats(self) -> PoolStats:
        retry_in = None
        if self._retry_at is not None:
            retry_in = round(max(0.0, self._retry_at - anyio.current_time()), 1)
        return PoolStats(self.workers, self.queue_size, self._running,
                         self._admitted - self._running, self._warming, self._completed,
                         self._rejected,
                         self._cancelled, self._timed_out, self._crashed, self._replaced,
                         self.live_workers(), self._start_failures, self.start_error,
                         retry_in)

    @property
    def degraded(self) -> bool:
        """A worker process could not be started and none has been since."""
        return bool(self.start_error)

    @classmethod
    def _idle_workers(cls) -> int:
        try:
            return sum(1 for p, _ in to_process._process_pool_idle_workers.get()
                       if p.returncode is None)
        except LookupError:
            return 0

    def _start_failed(self, reason: str) -> WorkerUnavailable:
        """Record a failed start, plan the next try (backoff) and say when to retry."""
        self._start_failures += 1
        first = not self.start_error
        self.start_error = reason
        now = anyio.current_time()
        if self._retry_at is None or self._retry_at <= now:
            self._retry_at = now + self._backoff
            self._backoff = min(2 * self._backoff, START_BACKOFF_MAX_S)
        (log.warning if first else log.info)(
            "worker pool: a worker process could not be started (%s); trying again in "
            "%.0f s", reason, self._retry_at - now)
        if self._tg is not None and not self._retrying and not self.closing:
            self._retrying = True
            self._tg.start_soon(self._retry_start)
        return self._unavailable()

    def _unavailable(self) -> WorkerUnavailable:
        left = 1.0 if self._retry_at is None else self._retry_at - anyio.current_time()
        return WorkerUnavailable(self.start_error, max(1, math.ceil(left)))

    def _started(self) -> None:
        if self.start_error:
            log.info("worker pool: worker processes start again")
        self.start_error = ""
        self._backoff = START_BACKOFF_S
        self._retry_at = None

    async def _retry_start(self) -> None:
        """Start a worker when the backoff has passed, again and again (the wait doubled
        after each failure) until one starts: the pool heals without a request."""
        try:
            while self.start_error and not self.closing:
                await anyio.sleep(max(0.0, (self._retry_at or 0.0) - anyio.current_time()))
                if not self.start_error or self.closing:
                    return
                try:
                    async with self._slots:
                        await to_process.run_sync(self.warm or _pid, cancellable=True,
                                                  limiter=self._procs)
                except _StartFailed as exc:
                    self._start_failed(str(exc))
                except Exception as exc:    # it started; its warm-up failed: not ours here
                    log.warning("worker pool: a restarted worker's warm-up failed: %r", exc)
                    self._started()
                else:
                    self._started()
        finally:
            self._retrying = False

    async def run(self, fn: Callable, *args, deadline: float | None = None,
                  share: str | None = None):
        """fn(*args) in a worker process; see the module docstring. share: the name of a
        share of the pool (the constructor's `shares`) this job counts against."""
        gate = self._shares.get(share) if share is not None else None
        if gate is None:
            return await self._run(fn, args, deadline)
        limiter, places = gate
        if self.closing:
            raise WorkerCrashed(STOPPING)
        if self._share_admitted[share] >= places:
            self._rejected += 1
            raise QueueFull(self.retry_after, places, share)
        self._share_admitted[share] += 1
        try:
            try:
                await limiter.acquire()
            except anyio.get_cancelled_exc_class():
                self._cancelled += 1
                raise
            try:
                return await self._run(fn, args, deadline)
            finally:
                limiter.release()
        finally:
            self._share_admitted[share] -= 1

    async def _run(self, fn: Callable, args: tuple, deadline: float | None):
        if self.closing:
            raise WorkerCrashed(STOPPING)
        if self._admitted >= self.capacity:
            self._rejected += 1
            raise QueueFull(self.retry_after, self.capacity)
        self._admitted += 1
        try:
            try:
                await self._slots.acquire()
            except anyio.get_cancelled_exc_class():
                self._cancelled += 1          # the client left while waiting in the queue
                raise
            try:
                if self.closing:     # it waited in the queue while the server began to stop
                    raise WorkerCrashed(STOPPING)
                if (self.start_error and self._retry_at is not None
                        and anyio.current_time() < self._retry_at
                        and not self._idle_workers()):
                    raise self._unavailable()   # no process to run it before the retry
                self._running += 1
                try:
                    with anyio.move_on_after(math.inf if deadline is None else deadline) as sc:
                        result = await to_process.run_sync(fn, *args, cancellable=True,
                                                           limiter=self._procs)
                    if sc.cancelled_caught:
                        self._timed_out += 1
                        self._replace_killed_worker()
                        raise DeadlineExceeded(deadline)
                except _StartFailed as exc:
                    raise self._start_failed(str(exc)) from None
                except anyio.BrokenWorkerProcess as exc:
                    if self.closing:    # killed by the server's own stop, not a crash
                        raise WorkerCrashed(STOPPING) from exc
                    self._crashed += 1
                    log.warning("a worker process died while computing %s (%s); starting "
                                "a warmed one in its place", getattr(fn, "__name__", fn),
                                exc.__cause__ or exc)
                    self._replace_killed_worker()
                    raise WorkerCrashed("the worker process died while computing; "
                                        "the request can be retried") from exc
                except anyio.get_cancelled_exc_class():
                    self._cancelled += 1
                    self._replace_killed_worker()
                    raise
                finally:
                    self._running -= 1
            finally:
                self._slots.release()
            self._completed += 1
            return result
        finally:
            self._admitted -= 1
