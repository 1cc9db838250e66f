"""One progress line: redrawn in place on a terminal, one log line per update elsewhere.

The kernel warm-up (app/services/kernel_warmup.py) reports "compiling kernels: k of n
parts [###---]" as each part finishes. In CI logs and pipes every update stays a line of
its own (a log record of the given logger, as before). On a terminal (the stream's
isatty(), or `tty=True`) the line is redrawn where it stands ("\r" and erase-line), so the
bar advances instead of scrolling; what else is logged meanwhile (uvicorn's lines, the
explorer's own) must not land behind the bar, so while the bar is on screen the
StreamHandlers that write to the same terminal write through a proxy that erases the bar
first and draws it again below their line (what rich's Live does for sys.stdout, for
handlers, which keep the stream they were made with). `close()` ends the line and gives
the handlers their streams back.
"""

from __future__ import annotations

import logging
import shutil
import sys
import threading

ERASE = "\r\x1b[2K"     # to the line's start, erase the line (ECMA-48 EL 2)


class ProgressLine:
    def __init__(self, log: logging.Logger, stream=None, tty: bool | None = None) -> None:
        self.log = log
        self.stream = stream if stream is not None else sys.stderr
        if tty is None:
            try:
                tty = bool(self.stream.isatty())
            except (AttributeError, ValueError):    # no isatty, or a closed stream
                tty = False
        self.tty = tty
        self._text: str | None = None      # the line on screen (tty), None: nothing drawn
        self._lock = threading.RLock()      # draws and the handlers' writes, in any thread
        self._wrapped: list[tuple[logging.StreamHandler, object]] = []

    def update(self, text: str) -> None:
        if not self.tty:
            self.log.info("%s", text)
            return
        if not self.log.isEnabledFor(logging.INFO):     # the log level asked for less
            return
        with self._lock:
            if self._text is None:
                self._wrap_handlers()
            self._text = text
            self._draw()

    def close(self) -> None:
        """End the line (tty: leave the last bar on screen and go to the next line)."""
        with self._lock:
            if self._text is not None:
                self._write("\n")
                self._text = None
            self._unwrap_handlers()

    # --- drawing ------------------------------------------------------------------------

    def _width(self) -> int:
        return max(20, shutil.get_terminal_size((100, 24)).columns - 1)

    def _write(self, s: str) -> None:
        try:
            self.stream.write(s)
            self.stream.flush()
        except (OSError, ValueError):       # the terminal went away: nothing to draw on
            pass

    def _draw(self) -> None:
        if self._text is not None:
            # cut to the terminal's width: a wrapped line could not be redrawn in place
            self._write(ERASE + self._text[:self._width()])

    def _erase(self) -> None:
        if self._text is not None:
            self._write(ERASE)

    # --- the other writers to the same terminal -----------------------------------------

    def _same_terminal(self, stream) -> bool:
        if stream is self.stream:
            return True
        try:
            return bool(stream.isatty())
        except (AttributeError, ValueError):
            return False

    def _wrap_handlers(self) -> None:
        loggers = [logging.getLogger()] + [lg for lg in logging.Logger.manager.loggerDict.values()
                                           if isinstance(lg, logging.Logger)]
        for lg in loggers:
            for h in lg.handlers:
                if (type(h) is logging.StreamHandler and not isinstance(h.stream, _Around)
                        and self._same_terminal(h.stream)):
                    self._wrapped.append((h, h.setStream(_Around(h.stream, self))))

    def _unwrap_handlers(self) -> None:
        for h, stream in self._wrapped:
            h.setStream(stream)
        self._wrapped.clear()


class _Around:
    """A handler's stream while the bar is drawn: erase the bar, write the record, draw
    the bar again under it."""

    def __init__(self, stream, line: ProgressLine) -> None:
        self._stream, self._line = stream, line

    def write(self, s: str):
        with self._line._lock:
            self._line._erase()
            n = self._stream.write(s)
            if s.endswith("\n"):
                self._stream.flush()
                self._line._draw()
            return n

    def flush(self) -> None:
        self._stream.flush()

    def __getattr__(self, name):
        return getattr(self._stream, name)
