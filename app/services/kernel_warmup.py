"""The kernel warm-up in the background of a running explorer, so that it is ready soon.

On a fresh machine nothing is compiled: `python -m solvers.warmup` takes minutes on 2 cores.
The explorer does not wait for it. The app's lifespan starts it as a subprocess
(`--progress`: one JSON line per finished part, solvers/warmup.py) at a lower CPU priority,
and serves at once. This module reads those lines:

  - the terminal shows a progress bar tied to them, advancing as each part finishes:
    "compiling kernels: 4 of 9 parts [########------------] (plane/chaplygin-ball, 14.2 s)",
    one line redrawn in place on a terminal, one log line per part in CI logs and pipes
    (app/services/progress_line.py);
  - /api/health and the pages say which parts are still warming and which cases they hold
    (`public()`), and how long a compile of one case structure took here (`estimate_s`);
  - what needs the kernels waits for `wait_done()` (the background verification), and
    the routes prepare whatever a request needs in a job without a deadline
    (app/services/kernel_prepare.py), so no request pays a compile inside its deadline.
"""

from __future__ import annotations

import json
import logging
import os
import signal
import statistics
import sys
import time
from pathlib import Path

import anyio

from app.services.progress_line import ProgressLine

log = logging.getLogger("rolling.kernels")

# The warm-up runs below the server's priority (the workers run at app.services.jobs'
# WORKER_NICE): the event loop answers pages at once while it compiles.
WARMUP_NICE = 10
BAR = 20
# Before any structure has been compiled here: a rough figure for a dop853 small kernel's
# compile (solvers/kernels/small.py; measured in docs/performance.md).
DEFAULT_ESTIMATE_S = 15.0


def bar(done: int, total: int, width: int = BAR) -> str:
    full = width * done // total if total else width
    return "[" + "#" * full + "-" * (width - full) + "]"


class KernelWarmup:
    """The state of the background warm-up. `state`: off (not started: the caches are
    assumed warm, or no warm-up was asked for), starting (listing what is not compiled),
    running, done, failed, stopped (with the server)."""

    def __init__(self, command: list[str] | None = None, line: ProgressLine | None = None) -> None:
        self._command = command
        # the terminal's progress line (stderr; tests pass their own stream and tty mode)
        self.line = line if line is not None else ProgressLine(log)
        self.state = "off"
        self.message = ""
        self.total = 0
        self.done = 0
        self.parts: list[dict] = []        # {"name", "cases", "done", "seconds"}
        self.started: float | None = None
        self.seconds: float | None = None  # wall time of the whole warm-up
        self._finished = anyio.Event()
        self._proc = None
        self._group: int | None = None     # the warm-up's process group (its session)
        self._stopping = False
        # prepare jobs run by the routes (app/services/kernel_prepare.py): keys, seconds
        self.prepared: list[dict] = []

    # --- what the pages and the routes read ----------------------------------------------

    @property
    def running(self) -> bool:
        return self.state in ("starting", "running")

    def warming_cases(self) -> list[str]:
        """The cases whose small kernels are still being compiled."""
        return sorted({c for p in self.parts if not p["done"] for c in p["cases"]})

    def part_done(self, name: str) -> bool:
        return not self.running or any(p["name"] == name and p["done"] for p in self.parts)

    def case_ready(self, case_id: str) -> bool:
        return not self.running or case_id not in self.warming_cases()

    def estimate_s(self) -> float:
        """Seconds one case structure's kernel took to compile here (the median of the
        parts of one structure finished so far), else DEFAULT_ESTIMATE_S."""
        measured = [p["seconds"] for p in self.parts if p["done"] and p["cases"]]
        return round(statistics.median(measured), 1) if measured else DEFAULT_ESTIMATE_S

    def public(self) -> dict:
        return {"state": self.state, "message": self.message, "parts_done": self.done,
                "parts_total": self.total, "warming_cases": self.warming_cases(),
                "warming_parts": [p["name"] for p in self.parts if not p["done"]],
                "estimate_s": self.estimate_s(),
                "prepared": self.prepared[-20:],
                "elapsed_s": None if self.started is None else
                round((self.seconds if self.seconds is not None
                       else time.monotonic() - self.started), 1)}

    def expect(self) -> None:
        """Called by the lifespan before it starts `run`: warming from the first request."""
        self.state, self.started = "starting", time.monotonic()

    async def wait_done(self) -> None:
        if self.running:
            await self._finished.wait()

    # --- the subprocess ------------------------------------------------------------------

    def command(self) -> list[str]:
        """solvers.warmup's warm() with its progress hook printing one JSON line per event
        (as `python -m solvers.warmup --progress`), reniced first (its spawned compile
        processes inherit the priority); or the command given (Settings.warmup_command).
        Not runpy as __main__: the spawned processes must find warm()'s tasks by their
        module's name."""
        if self._command:
            return list(self._command)
        code = (f"import json, os; os.nice({WARMUP_NICE}); from solvers import warmup; "
                "t = warmup.warm(progress=lambda e: print(json.dumps(e), flush=True)); "
                "print(f'kernels ready in {t:.1f} s', flush=True)")
        return [sys.executable, "-c", code]

    def _event(self, ev: dict) -> None:
        if ev.get("event") == "plan":
            self.total = int(ev["total"])
            self.parts = [{"name": p["name"], "cases": list(p["cases"]), "done": False,
                           "seconds": None} for p in ev["parts"]]
            self.state = "running"
            why = ("in the background: the explorer serves meanwhile; a run that needs a "
                   "part still compiling compiles it first (first use on this machine)")
            if self.line.tty:       # the explanation once, then the bar redrawn below it
                self.line.log.info("compiling kernels: %d parts, %s", self.total, why)
                self.line.update(f"compiling kernels: 0 of {self.total} parts "
                                 f"{bar(0, self.total)}")
            else:
                self.line.log.info("compiling kernels: 0 of %d parts %s, %s", self.total,
                                   bar(0, self.total), why)
        elif ev.get("event") == "done":
            self.done = int(ev["done"])
            for p in self.parts:
                if p["name"] == ev["part"] and not p["done"]:
                    p["done"], p["seconds"] = True, float(ev["seconds"])
                    break
            self.line.update(f"compiling kernels: {self.done} of {self.total} parts "
                             f"{bar(self.done, self.total)} ({ev['part']}, "
                             f"{float(ev['seconds']):.1f} s)")

    async def run(self) -> None:
        """Run the warm-up to its end (a task of the lifespan; cancelled at shutdown, when
        the subprocess's whole process group is stopped)."""
        self.state, self.started = "starting", time.monotonic()
        log.info("compiling kernels: listing what the caches lack")
        try:
            # its own session: stopping the explorer stops the warm-up's compile processes
            async with await anyio.open_process(self.command(), stdout=-1, stderr=None,
                                                start_new_session=True) as proc:
                self._proc, self._group = proc, proc.pid
                try:
                    await self._read(proc)
                    code = await proc.wait()
                except BaseException:
                    self.stop()     # its compile processes too, not only its main process
                    raise
            self.seconds = time.monotonic() - self.started
            self.line.close()
            if self._stopping:
                self.state = "stopped"
                log.info("compiling kernels: stopped with the server, %d of %d parts done",
                         self.done, self.total)
            elif code == 0:
                self.state = "done"
                log.info("compiling kernels: done, %d parts in %.1f s %s", self.total,
                         self.seconds, bar(self.total, self.total))
            else:
                self.state = "failed"
                self.message = (f"the kernel warm-up exited with code {code}: runs compile "
                                "what they need on first use")
                log.warning(self.message)
        except anyio.get_cancelled_exc_class():
            raise
        except Exception as exc:  # serve anyway: runs compile on first use (prepared)
            self.state, self.message = "failed", f"the kernel warm-up did not run: {exc!r}"
            log.warning(self.message)
        finally:
            self.line.close()       # a cancelled warm-up leaves the terminal's line ended
            self._proc = None
            self._finished.set()

    async def _read(self, proc) -> None:
        buf = b""
        async for chunk in proc.stdout:
            buf += chunk
            *lines, buf = buf.split(b"\n")
            for line in lines:
                try:
                    ev = json.loads(line)
                except ValueError:
                    continue        # its final "kernels ready in ..." line
                if isinstance(ev, dict):
                    self._event(ev)

    def stop(self, sig: int = signal.SIGTERM) -> None:
        """Signal the warm-up's whole process group (its compile processes too). Safe to
        call at any time, from the event loop's thread."""
        if self._group is None:
            return
        self._stopping = True
        try:
            os.killpg(self._group, sig)
        except (ProcessLookupError, PermissionError):
            pass

    async def reap(self, timeout: float = 1.0) -> None:
        """After stop(): wait until no process of the group is left (a process that
        ignores SIGTERM, as multiprocessing's resource tracker does, ends when its pipe
        closes), and kill what is still there after `timeout` s."""
        if self._group is None or not self._stopping:
            return
        with anyio.move_on_after(timeout):
            while _group_alive(self._group):
                await anyio.sleep(0.05)
        if _group_alive(self._group):
            self.stop(signal.SIGKILL)


def _group_alive(pgid: int) -> bool:
    """Whether a process of the group is left that is not a zombie (a zombie has ended; a
    container's init may be slow to reap the orphans)."""
    try:
        os.killpg(pgid, 0)
    except (ProcessLookupError, PermissionError):
        return False
    if not Path("/proc").is_dir():
        return True
    for stat in Path("/proc").glob("[0-9]*/stat"):
        try:
            fields = stat.read_text().rsplit(")", 1)[1].split()
        except OSError:
            continue
        if int(fields[2]) == pgid and fields[0] != "Z":     # state, ppid, pgrp
            return True
    return False
