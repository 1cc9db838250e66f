"""The HTTP server of the explorer: uvicorn with a connection protocol that bounds what a
client can hold. `rolling serve` and app.testing.live_server start it through
`run()`; `python -m app.core.server --port 8000` does the same.

uvicorn's default parser (httptools) accepts headers of any size and keeps a connection
that sent half a header or half a body open forever (huge headers are answered and held in
memory; half bodies and half heads stay open). Its h11 parser has a size limit
(`h11_max_incomplete_event_size`) and the rest is added here, on h11's protocol class:

- the request line and headers: at most `max_header_bytes` (431 and close), at most
  `max_headers` fields (431, app.core.guards.HeaderLimit), within `header_timeout_s` of
  the connection or of the first byte of the request (408 and close);
- a body: a gap of `body_timeout_s` without a byte closes the connection;
- at most `max_connections` open connections. At the cap a new connection evicts one
  that makes no progress (Candidates.victim), never a legitimate one while a stalled or
  slow one is there: first one closed by a read timeout and still lingering; then the
  longest silent of a head (counted from its start), a body (from its last byte; not one
  the app paused) or a lingering answer, once silent for `stall_grace_s`; then the slowest
  request: of the requests still arriving, the body that began the longest ago, unless it
  arrives faster than FAST_BYTES_S (an upload, not a trickle), else the oldest head (one
  not read yet may be a busy client's about to arrive); then an idle keep-alive
  connection, idle longest first; last a fast body or a lingering answer silent for less
  than the grace. A request read to its end whose answer is being made or sent is never
  evicted; with nothing to evict the new connection is closed at once. A legitimate
  request arrives within milliseconds of its start, so under a flood of slow heads or
  trickling bodies it is the youngest of the requests in progress and the
  flood evicts its own (bench/load.py --slow-bodies), and an idle client is evicted only
  when no request is arriving.
  The grace, 1 s: the legitimate clients of bench/load.py have their whole head well
  within it and no gap inside a body near it even on a loaded machine, while a flood of
  stalled sockets at half the cap a second leaves its own sockets twice the grace to age
  (bench/connection_cap.py; docs/performance.md). The candidates are kept in time order
  per kind, so choosing one costs little, not a scan of every connection (a scan at the
  cap, at every new connection of a flood, took most of a core): the slowest request is
  found among the oldest SLOW_SCAN requests in progress. The soft file limit is raised
  towards the hard one, so that fd_bound does not halve the cap; the app of a request with
  a small body starts once the body is in (_DeferringLoop), so that the stalled half
  bodies the cap now admits cost no app run;
- closing while the client is still sending (a 413, a 431, a timeout): reading stops,
  the answer is flushed, the write side is shut (the client sees the end of the answer),
  and the socket is closed `linger_s` later. The unread bytes stay in the kernel's
  buffers and never reach the event loop; closing at once would reset the connection
  and could destroy the answer before the client read it.
- uvicorn's own error answers (400 on a malformed request, 431, 408) carry the security
  headers of every other answer (app.core.guards.HEADERS).

The figures that chose h11 with these guards over httptools are in bench/results/load.txt.
"""

from __future__ import annotations

import argparse
import asyncio
import logging
import resource
import time
from dataclasses import dataclass

import h11
import uvicorn
from uvicorn.protocols.http.flow_control import HIGH_WATER_LIMIT
from uvicorn.protocols.http.h11_impl import H11Protocol

from app.core.config import get_settings
from app.core.eviction import FAST_BYTES_S, KINDS, SLOW_SCAN, Candidates  # noqa: F401
from app.core.guards import HEADERS

log = logging.getLogger("rolling.server")


@dataclass(frozen=True)
class Limits:
    max_connections: int = 1000
    max_header_bytes: int = 64 * 1024
    header_timeout_s: float = 10.0
    body_timeout_s: float = 10.0
    keep_alive_s: float = 20.0
    linger_s: float = 1.0
    stall_grace_s: float = 1.0

    @classmethod
    def from_settings(cls, s) -> Limits:
        return cls(max_connections=s.max_connections, max_header_bytes=s.max_header_bytes,
                   header_timeout_s=s.header_timeout_s, body_timeout_s=s.body_timeout_s,
                   keep_alive_s=s.keep_alive_s, linger_s=s.linger_s,
                   stall_grace_s=s.stall_grace_s)


# what the guards did, for /api/health and bench/load.py (one process, one event loop);
# evicted_by: the evictions by rank (see Candidates.victim)
STATS = {"connections": 0, "peak_connections": 0, "evicted": 0, "refused": 0,
         "header_timeouts": 0, "body_timeouts": 0, "header_too_large": 0, "lingered": 0,
         "evicted_by": {"stalled": 0, "slowest": 0, "idle": 0, "young_body": 0}}

# the limits of the server running in this process (set by config())
ACTIVE: Limits | None = None


def raise_fd_limit(wanted: int) -> None:
    """Raise the process's soft file limit towards its hard one, to twice the wanted cap
    (a soft limit of 1024, common, would halve a cap of 1000 through fd_bound, and with
    it the flood rate the eviction policy absorbs: cap / stall_grace_s a second)."""
    soft, hard = resource.getrlimit(resource.RLIMIT_NOFILE)
    need = 2 * wanted + 64
    if soft == resource.RLIM_INFINITY or soft >= need:
        return
    target = need if hard == resource.RLIM_INFINITY else min(need, hard)
    if target > soft:
        try:
            resource.setrlimit(resource.RLIMIT_NOFILE, (target, hard))
        except (ValueError, OSError) as exc:
            log.warning("cannot raise the file limit from %d to %d: %s", soft, target, exc)


def fd_bound(wanted: int) -> int:
    """The connection cap, at most half the process's file limit (the other half: worker
    pipes, the verdict store, static files)."""
    soft, _ = resource.getrlimit(resource.RLIMIT_NOFILE)
    if soft == resource.RLIM_INFINITY:
        return wanted
    return max(8, min(wanted, soft // 2))


def _raw_answer(status: int, reason: bytes, text: str) -> bytes:
    body = text.encode()
    head = [b"HTTP/1.1 %d %s" % (status, reason),
            b"content-type: text/plain; charset=utf-8",
            b"content-length: %d" % len(body), b"connection: close",
            *(k + b": " + v for k, v in HEADERS)]
    return b"\r\n".join(head) + b"\r\n\r\n" + body


class _LingeringTransport:
    """The connection's transport, whose close() does not reset a connection that still
    has a request body coming (see the module docstring)."""

    def __init__(self, transport: asyncio.Transport, protocol: GuardedH11Protocol):
        self._t = transport
        self._p = protocol
        self._closing = False

    def __getattr__(self, name):
        return getattr(self._t, name)

    def is_closing(self) -> bool:
        return self._closing or self._t.is_closing()

    def close(self) -> None:
        if self._closing or self._t.is_closing():
            return
        self._closing = True
        if not self._p.unread_input() or self._p.limits.linger_s <= 0:
            # a timed-out one may go at once; otherwise its answer is being flushed
            self._p._place("dead" if self._p._timed_out else None)
            self._t.close()
            return
        STATS["lingered"] += 1
        self._p._place("dead" if self._p._timed_out else "closing")
        self._t.pause_reading()
        try:
            if self._t.can_write_eof():
                self._t.write_eof()
        except (OSError, RuntimeError):
            pass
        self._p.loop.call_later(self._p.limits.linger_s, self._t.close)

    def abort(self) -> None:
        self._closing = True
        self._t.abort()


class _DeferringLoop:
    """The event loop as one connection's protocol sees it: the ASGI task of a request
    whose small body (Content-Length up to HIGH_WATER_LIMIT, no Expect: 100-continue) has
    not all arrived starts once it has (GuardedH11Protocol._release_app), and never if
    the connection goes first. The app reads such a body whole before anything else, so
    only a stalled half body sees a difference: it costs its parse, not a run of the
    app's middleware: less server CPU per stalled half body at the cap than with the app
    started at once (bench/connection_cap.py --body-cpu; docs/performance.md)."""

    def __init__(self, loop: asyncio.AbstractEventLoop, protocol: GuardedH11Protocol):
        self._loop = loop
        self._p = protocol

    def __getattr__(self, name):
        return getattr(self._loop, name)

    def create_task(self, coro, **kw):
        if not self._p._small_body_coming():
            return self._loop.create_task(coro, **kw)
        ready = self._loop.create_future()
        self._p._app_held = (coro, ready)

        async def after_body():
            await ready
            return await coro

        return self._loop.create_task(after_body(), **kw)


class GuardedH11Protocol(H11Protocol):
    limits = Limits()

    def __init__(self, config, server_state, app_state, _loop=None):
        super().__init__(config, server_state, app_state, _loop)
        if config.h11_max_incomplete_event_size != self.limits.max_header_bytes:
            self.conn = h11.Connection(h11.SERVER, self.limits.max_header_bytes)
        self._timer: asyncio.TimerHandle | None = None
        self._timer_kind = ""
        self._refused = False
        self._timed_out = False
        self._served = 0
        self._kind: str | None = None     # see KINDS
        self._in_bytes = 0                 # bytes of the body arriving (see _place)
        cands = getattr(server_state, "rolling_candidates", None)
        if cands is None:                # one index per server (its connections' set)
            cands = server_state.rolling_candidates = Candidates()
        self._cands: Candidates = cands
        self._app_held: tuple | None = None    # (the app's coroutine, its start signal)
        self.loop = _DeferringLoop(self.loop, self)

    def unread_input(self) -> bool:
        """The client may still be sending: a body not read to its end, a head cut short
        by a timeout or refused as too large or malformed."""
        state = self.conn.their_state
        return (state is h11.SEND_BODY or state is h11.ERROR
                or (state is h11.IDLE and bool(self.conn.trailing_data[0])))

    # --- the app of a small body starts once the body is in ---------------------------

    def _small_body_coming(self) -> bool:
        if self.conn.their_state is not h11.SEND_BODY:
            return False
        length = None
        for name, value in self.headers:
            if name == b"expect":        # the client waits for the app's 100 Continue
                return False
            if name == b"content-length":
                length = value
        return length is not None and length.isdigit() and int(length) <= HIGH_WATER_LIMIT

    def _release_app(self, run: bool) -> None:
        coro, ready = self._app_held
        self._app_held = None
        if run:
            if not ready.done():
                ready.set_result(None)
        else:                            # the connection went before its body came
            ready.cancel()
            coro.close()


    def _place(self, kind: str | None) -> None:
        """Put this connection among the candidates of `kind` (None: not evictable). A
        body that stays a body is moved to the end (its last byte is now); a head that
        stays a head keeps its place (its deadline runs from its start). A request that
        begins (a head) joins `inflight` and counts its body's bytes; one read to its end
        leaves it."""
        if kind == self._kind and kind != "body":
            return
        kinds = self._cands.kinds
        if self._kind is not None:
            kinds[self._kind].pop(self, None)
        arriving = kind in ("head", "body")
        if arriving and self._kind not in ("head", "body"):
            self._in_bytes = 0
            self._cands.inflight[self] = time.monotonic()
        elif not arriving and self._kind in ("head", "body"):
            self._cands.inflight.pop(self, None)
        self._kind = kind
        if kind is not None:
            kinds[kind][self] = time.monotonic()

    def _classify(self) -> str | None:
        state = self.conn.their_state
        if state is h11.IDLE and (self.cycle is None or self.cycle.response_complete):
            return "head" if self._served == 0 or self.conn.trailing_data[0] else "idle"
        if state is h11.SEND_BODY and not (self.cycle and self.cycle.response_started):
            return "body"
        return None                      # a request being answered

    def _evict_one(self) -> bool:
        found = self._cands.victim(time.monotonic(), self.limits.stall_grace_s)
        if found is None:
            return False
        victim, rank = found
        STATS["evicted"] += 1
        STATS["evicted_by"][rank] += 1
        victim._cancel_timer()
        victim._place(None)
        victim.transport.abort()
        victim.connections.discard(victim)
        return True

    def connection_made(self, transport) -> None:  # type: ignore[override]
        if len(self.connections) >= self.limits.max_connections and not self._evict_one():
            self._refused = True
            STATS["refused"] += 1
            transport.abort()
            return
        super().connection_made(_LingeringTransport(transport, self))
        STATS["connections"] = len(self.connections)
        STATS["peak_connections"] = max(STATS["peak_connections"], len(self.connections))
        self._arm("header", self.limits.header_timeout_s)
        self._place("head")

    def connection_lost(self, exc) -> None:
        if self._refused:
            return
        self._cancel_timer()
        self._place(None)
        if self._app_held is not None:
            self._release_app(run=False)
        super().connection_lost(exc)
        STATS["connections"] = len(self.connections)

    # --- the read timeouts ---------------------------------------------------------------

    def _arm(self, kind: str, delay: float) -> None:
        self._cancel_timer()
        self._timer_kind = kind
        self._timer = self.loop.call_later(delay, self._expired)

    def _cancel_timer(self) -> None:
        if self._timer is not None:
            self._timer.cancel()
            self._timer = None
            self._timer_kind = ""

    def data_received(self, data: bytes) -> None:
        # h11's own limit holds only while a head is incomplete: a 100 KB head that
        # arrives in one piece would pass it
        if self.conn.their_state is h11.IDLE and not self.transport.is_closing():
            buf = self.conn.trailing_data[0]
            cap = self.limits.max_header_bytes
            if len(buf) + len(data) > cap and (buf + data).find(b"\r\n\r\n", 0, cap + 4) < 0:
                self._unset_keepalive_if_required()
                self.conn.receive_data(data)
                self.send_400_response("")
                return
        super().data_received(data)
        if self._kind == "body":
            self._in_bytes += len(data)

    def handle_events(self) -> None:
        super().handle_events()
        if self.transport is None or self.transport.is_closing():
            self._cancel_timer()
            return
        state = self.conn.their_state
        if state is h11.IDLE and (self.cycle is None or self.cycle.response_complete):
            # waiting for a head: the deadline runs from its first byte (or from the
            # connection) and is not extended by a slow trickle
            if self._timer_kind != "header" and self.conn.trailing_data[0]:
                self._arm("header", self.limits.header_timeout_s)
        elif state is h11.SEND_BODY:
            if not self.flow.read_paused:      # paused by us: the app is not reading
                self._arm("body", self.limits.body_timeout_s)
            else:
                self._cancel_timer()
        else:
            self._cancel_timer()
        self._place(self._classify())
        if self._app_held is not None and (state is not h11.SEND_BODY
                                           or self.flow.read_paused):
            self._release_app(run=True)

    def on_response_complete(self) -> None:
        self._served += 1
        super().on_response_complete()
        # an idle keep-alive connection is uvicorn's keep-alive timer's (unless the next
        # request has begun to arrive: handle_events armed the header deadline)
        if self._timer_kind == "header" and not self.conn.trailing_data[0]:
            self._cancel_timer()
        if not self.transport.is_closing():
            self._place(self._classify())

    def _expired(self) -> None:
        kind, self._timer, self._timer_kind = self._timer_kind, None, ""
        if self.transport.is_closing():
            return
        if kind == "header":
            STATS["header_timeouts"] += 1
            if self.conn.trailing_data[0]:     # a head began: say why it ends
                self.transport.write(_raw_answer(
                    408, b"Request Timeout", "the request head did not arrive within "
                    f"{self.limits.header_timeout_s:g} s"))
        else:
            STATS["body_timeouts"] += 1
        self._timed_out = True
        self.transport.close()

    # --- uvicorn's own answers -----------------------------------------------------------

    def send_400_response(self, msg: str) -> None:
        if len(self.conn.trailing_data[0]) > self.limits.max_header_bytes:
            STATS["header_too_large"] += 1
            answer = _raw_answer(431, b"Request Header Fields Too Large",
                                 "the request line and headers are larger than "
                                 f"{self.limits.max_header_bytes} bytes")
        else:
            answer = _raw_answer(400, b"Bad Request", msg)
        self._cancel_timer()
        self.transport.write(answer)
        self.transport.close()


def protocol_for(limits: Limits) -> type[GuardedH11Protocol]:
    return type("GuardedH11Protocol", (GuardedH11Protocol,), {"limits": limits})


def config(host: str, port: int, settings=None, **kw):
    """The uvicorn Config of the explorer with the guarded protocol."""
    s = settings or get_settings()
    limits = Limits.from_settings(s)
    raise_fd_limit(limits.max_connections)
    limits = Limits(**{**limits.__dict__, "max_connections": fd_bound(limits.max_connections)})
    global ACTIVE
    ACTIVE = limits
    return uvicorn.Config("app.main:app", host=host, port=port, http=protocol_for(limits),
                          h11_max_incomplete_event_size=limits.max_header_bytes,
                          timeout_keep_alive=limits.keep_alive_s, **kw)


def run(host: str, port: int, log_level: str = "info") -> None:
    uvicorn.Server(config(host, port, log_level=log_level)).run()


def main(argv=None) -> None:
    ap = argparse.ArgumentParser(description="the explorer's HTTP server")
    ap.add_argument("--host", default="127.0.0.1")
    ap.add_argument("--port", type=int, default=8000)
    ap.add_argument("--log-level", default="info")
    a = ap.parse_args(argv)
    run(a.host, a.port, a.log_level)


if __name__ == "__main__":
    # run the module's importable twin, so that /api/health reads the same STATS
    from app.core.server import main as _main

    _main()
