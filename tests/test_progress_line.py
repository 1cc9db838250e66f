"""The warm-up's progress bar on the terminal (issue 19; app/services/progress_line.py):
in a pipe or a CI log one line per finished part; on a terminal one line redrawn in place,
with whatever else is logged meanwhile printed above it, never behind it."""

import io
import logging
import os
import pty
import select
import time

from app.services.kernel_warmup import KernelWarmup, bar
from app.services.progress_line import ERASE, ProgressLine

PLAN = {"event": "plan", "total": 3, "parts": [
    {"name": "general kernels", "cases": []},
    {"name": "plane/chaplygin-ball", "cases": ["plane/chaplygin-ball"]},
    {"name": "compiled ensembles (Poincare maps)", "cases": []}]}


def _done(i: int) -> dict:
    return {"event": "done", "part": PLAN["parts"][i]["name"], "seconds": 2.0 + i,
            "done": i + 1, "total": 3}


def screen(raw: str) -> list[str]:
    """What a terminal shows after `raw`: per line, what the last carriage return left."""
    rows = [row.split("\r")[-1].replace("\x1b[2K", "") for row in raw.split("\n")]
    return rows[:-1] if rows and rows[-1] == "" else rows


def _logger(name: str, stream) -> logging.Logger:
    lg = logging.getLogger(name)
    lg.handlers.clear()
    lg.propagate = False
    lg.setLevel(logging.INFO)
    h = logging.StreamHandler(stream)
    h.setFormatter(logging.Formatter("%(name)s: %(message)s"))
    lg.addHandler(h)
    return lg


def test_in_a_pipe_each_part_is_a_line_of_its_own():
    out = io.StringIO()
    log = _logger("test.progress.pipe", out)
    w = KernelWarmup(line=ProgressLine(log, stream=out, tty=False))
    w._event(PLAN)
    for i in range(3):
        w._event(_done(i))
    w.line.close()
    assert ERASE not in out.getvalue() and "\r" not in out.getvalue()
    rows = screen(out.getvalue())
    assert [r.split(" parts ")[0] for r in rows] == [
        f"test.progress.pipe: compiling kernels: {k} of 3" for k in range(4)], rows
    assert rows[0].endswith("first use on this machine)") and bar(0, 3) in rows[0]
    assert rows[2].endswith(f"{bar(2, 3)} (plane/chaplygin-ball, 3.0 s)"), rows


def test_on_a_terminal_the_bar_is_redrawn_in_place_and_other_lines_go_above_it(monkeypatch):
    # a terminal wider than the line: the bar is cut to the width (shutil reads COLUMNS,
    # which a CI shell may set to 80)
    monkeypatch.setenv("COLUMNS", "300")
    term = io.StringIO()
    kernels_log = _logger("test.progress.tty", term)
    server_log = _logger("test.progress.server", term)     # uvicorn's lines, say
    w = KernelWarmup(line=ProgressLine(kernels_log, stream=term, tty=True))
    w._event(PLAN)
    w._event(_done(0))
    server_log.info("GET / 200")
    w._event(_done(1))
    w._event(_done(2))
    w.line.close()
    raw = term.getvalue()
    rows = screen(raw)
    assert rows == [
        "test.progress.tty: compiling kernels: 3 parts, in the background: the explorer "
        "serves meanwhile; a run that needs a part still compiling compiles it first "
        "(first use on this machine)",
        "test.progress.server: GET / 200",
        f"compiling kernels: 3 of 3 parts {bar(3, 3)} "
        "(compiled ensembles (Poincare maps), 4.0 s)"], raw
    # each update redrew the one line: four bars drawn, one line break after the last
    assert raw.count(ERASE + "compiling kernels: ") == 5     # 0, 1, redraw after GET, 2, 3
    assert raw.endswith(")\n")
    # the handlers write to their own streams again once the line is closed
    assert all(type(h.stream) is io.StringIO for h in server_log.handlers)


def test_a_real_terminal_is_detected_and_gets_the_redraw():
    master, slave = pty.openpty()
    try:
        stream = os.fdopen(slave, "w", closefd=False)
        log = logging.getLogger("test.progress.pty")
        log.setLevel(logging.INFO)
        line = ProgressLine(log, stream=stream)
        assert line.tty
        line.update("compiling kernels: 0 of 2 parts")
        line.update("compiling kernels: 1 of 2 parts")
        line.close()
        stream.close()
        # until the closing newline has come (one read may return before it: seen once in
        # a full run) or 5 s pass: never block the suite
        raw, deadline = "", time.monotonic() + 5.0
        while not raw.endswith("\n") and time.monotonic() < deadline:
            ready, _, _ = select.select([master], [], [], max(0.0, deadline - time.monotonic()))
            if not ready:
                break
            raw += os.read(master, 4096).decode()
    finally:
        os.close(master)
        os.close(slave)
    # the terminal translates "\n" to "\r\n" (onlcr)
    assert raw.replace("\r\n", "\n") == (ERASE + "compiling kernels: 0 of 2 parts" + ERASE
                                         + "compiling kernels: 1 of 2 parts\n"), repr(raw)
    piped = ProgressLine(logging.getLogger("test.progress.pty"), stream=io.StringIO())
    assert not piped.tty


def test_a_quieter_log_level_draws_no_bar():
    term = io.StringIO()
    log = _logger("test.progress.quiet", term)
    log.setLevel(logging.WARNING)
    line = ProgressLine(log, stream=term, tty=True)
    line.update("compiling kernels: 0 of 2 parts")
    line.close()
    assert term.getvalue() == ""
