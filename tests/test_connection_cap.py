"""The connection cap under a flood of stalled sockets (issue 21, app/core/server.py): the
connections evicted to make room are the stalled ones (half a head, half a body), never a
legitimate client's while a stalled one is there. Before: a stalled half-BODY was never
evictable, so a flood of them filled the cap; then the idle keep-alive connections of
legitimate clients were evicted and new ones refused (bench/load.py --hostile: 1475
legitimate requests without an answer).

A live server with a cap of 20 and read timeouts of 60 s, so that only the cap closes the
flood's sockets; the flood is paced so that it never opens more than the cap within the
grace time (`stall_grace_s`, 1 s by default), as the policy documents."""

import select
import socket
import time

import httpx
import pytest

from app.testing import live_server
from tests.test_server_limits import _one_response

CAP = 20
# warm_workers off: no test here runs a job (tests/test_server_limits.py's LIMITS)
LIMITS = {"max_connections": CAP, "header_timeout_s": 60.0, "body_timeout_s": 60.0,
          "keep_alive_s": 60.0, "linger_s": 0.5, "warm_workers": False}
GRACE = 1.0           # the server's default stall_grace_s

HALF_HEAD = b"GET /api/health HTTP/1.1\r\nHost: 127.0.0.1\r\nX-Stalled: "
HALF_BODY = (b"POST /api/validate HTTP/1.1\r\nHost: 127.0.0.1\r\n"
             b"Content-Type: application/json\r\nContent-Length: 1000\r\n\r\n{\"case\": ")
REQUEST = b"GET /api/health HTTP/1.1\r\nHost: 127.0.0.1\r\n\r\n"


@pytest.fixture(scope="module")
def server():
    with live_server(**LIMITS) as url:
        yield url, int(url.rsplit(":", 1)[1])


def _guards(url: str) -> dict:
    with httpx.Client(timeout=10.0) as c:       # a connection of its own, closed at once
        return c.get(f"{url}/api/health").json()["connections"]


def _stalled(port: int, what: bytes) -> socket.socket:
    s = socket.create_connection(("127.0.0.1", port), timeout=5.0)
    s.sendall(what)
    return s


def _closed_by_server(s: socket.socket) -> bool:
    """The server closed (or reset) this socket: it is readable and reads as the end."""
    if not select.select([s], [], [], 0)[0]:
        return False
    try:
        s.setblocking(False)
        return s.recv(65536) == b""
    except (ConnectionResetError, BlockingIOError):
        return True


def _guards_then_closed(url: str, flood: list) -> tuple[dict, list[bool]]:
    """The guards' counts, then which flood sockets the server closed. The server accepts
    in order: once the counts are answered it has seen every earlier socket."""
    after = _guards(url)
    time.sleep(0.2)
    return after, [_closed_by_server(s) for s in flood]


def test_a_flood_of_stalled_bodies_and_heads_evicts_itself_not_the_legitimate_clients(server):
    url, port = server
    before = _guards(url)
    # the legitimate clients: a raw keep-alive socket, an httpx pool, and new connections
    keep = socket.create_connection(("127.0.0.1", port), timeout=5.0)
    keep.sendall(REQUEST)
    assert _one_response(keep).startswith(b"HTTP/1.1 200")
    pooled = httpx.Client(base_url=url, timeout=10.0)
    assert pooled.get("/api/health").status_code == 200
    flood, answers = [], []
    try:
        # two waves of stalled sockets, half of them half a body, each wave smaller than
        # the cap and stalled past the grace time; the second fills the cap and evicts the
        # first's
        for _wave in range(2):
            for k in range(CAP - 4):
                flood.append(_stalled(port, HALF_BODY if k % 2 else HALF_HEAD))
            time.sleep(GRACE + 0.3)
        # the flood goes on (one half head and one half body a round) while the legitimate
        # clients make their requests
        for _ in range(8):
            flood.append(_stalled(port, HALF_BODY))
            flood.append(_stalled(port, HALF_HEAD))
            try:
                keep.sendall(REQUEST)
                answers.append(_one_response(keep)[:12])
            except OSError as exc:
                answers.append(repr(exc))
            try:
                answers.append(pooled.get("/api/health").status_code)
            except httpx.TransportError as exc:
                answers.append(repr(exc))
            try:
                with httpx.Client(timeout=10.0) as fresh:
                    answers.append(fresh.get(f"{url}/api/health").status_code)
            except httpx.TransportError as exc:
                answers.append(repr(exc))
            time.sleep(0.1)
        after, closed = _guards_then_closed(url, flood)
    finally:
        for s in flood:
            s.close()
        keep.close()
        pooled.close()
    assert answers == [b"HTTP/1.1 200", 200, 200] * 8, answers
    evicted = after["evicted"] - before["evicted"]
    by = {k: after["evicted_by"][k] - before["evicted_by"][k] for k in after["evicted_by"]}
    # every flood socket the server closed was evicted (the timeouts are 60 s), all of
    # them as stalled or the slowest, and the first wave's bodies among them; no idle
    # keep-alive connection was evicted and no connection refused
    assert after["refused"] == before["refused"], (before, after)
    assert by["idle"] == 0 and by["young_body"] == 0, by
    assert sum(closed) == evicted and evicted >= len(flood) - CAP, (sum(closed), evicted)
    assert by["stalled"] >= len(flood) - CAP - 4, by
    assert all(closed[1:CAP - 4:2]), "a stalled body of the first wave was not evicted"


def test_a_cap_full_of_stalled_bodies_lets_a_new_client_in(server):
    """Only half bodies, stalled past the grace time: a new connection evicts the one
    silent the longest (before: nothing was evictable and the client was refused)."""
    url, port = server
    flood = []
    try:
        for _ in range(CAP + 5):
            flood.append(_stalled(port, HALF_BODY))
            time.sleep(0.01)
        time.sleep(GRACE + 0.3)
        before = _guards(url)       # this connection evicts the oldest body
        with httpx.Client(timeout=10.0) as fresh:
            codes = [fresh.get(f"{url}/api/health").status_code for _ in range(3)]
        after, closed = _guards_then_closed(url, flood)
    finally:
        for s in flood:
            s.close()
    assert codes == [200, 200, 200]
    assert after["refused"] == before["refused"]
    # the oldest bodies went first: the closed ones are a prefix of the flood
    n = sum(closed)
    assert n >= 2 and closed[:n] == [True] * n, closed


def test_the_file_limit_is_raised_so_that_the_cap_is_not_halved():
    """A soft file limit of 256 (hard limit higher) would make fd_bound cut a cap of 1000
    to 128; the server raises the soft limit first (before: the cap was cut)."""
    import resource
    import subprocess
    import sys

    _, hard = resource.getrlimit(resource.RLIMIT_NOFILE)
    if hard != resource.RLIM_INFINITY and hard < 2 * 1000 + 64:
        pytest.skip(f"the hard file limit ({hard}) is below what a cap of 1000 needs")
    code = ("import resource\n"
            "soft, hard = resource.getrlimit(resource.RLIMIT_NOFILE)\n"
            "resource.setrlimit(resource.RLIMIT_NOFILE, (256, hard))\n"
            "from app.core.server import config\n"
            "from app.testing import settings_for_tests\n"
            "c = config('127.0.0.1', 0, settings_for_tests(max_connections=1000))\n"
            "from app.core import server\n"
            "print(server.ACTIVE.max_connections, "
            "resource.getrlimit(resource.RLIMIT_NOFILE)[0])\n")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                         timeout=120, check=True).stdout.split()
    assert out == ["1000", "2064"], out


@pytest.mark.parametrize("how", ["one-piece", "two-pieces", "expect-100", "chunked"])
def test_a_small_body_reaches_the_app_however_it_comes(server, how):
    """The app of a small Content-Length body starts once the body is in (_DeferringLoop):
    a body in two pieces, one behind Expect: 100-continue (the client waits for the
    server) and a chunked one are all answered by the app."""
    _, port = server
    body = b'{"case": "plane/chaplygin-ball", "example": true}'
    s = socket.create_connection(("127.0.0.1", port), timeout=10.0)
    head = b"POST /api/validate HTTP/1.1\r\nHost: 127.0.0.1\r\nContent-Type: application/json\r\n"
    head += (b"Transfer-Encoding: chunked\r\n" if how == "chunked"
             else b"Content-Length: %d\r\n" % len(body))
    head += b"Expect: 100-continue\r\n" if how == "expect-100" else b""
    try:
        s.sendall(head + b"\r\n")
        if how == "expect-100":
            assert s.recv(100).startswith(b"HTTP/1.1 100")
        if how == "chunked":
            s.sendall(b"%x\r\n%s\r\n0\r\n\r\n" % (len(body), body))
        elif how == "two-pieces":
            s.sendall(body[:10])
            time.sleep(0.3)
            s.sendall(body[10:])
        else:
            s.sendall(body)
        answer = _one_response(s)
    finally:
        s.close()
    # the app's own answer (the validation's 422 or 200), not a timeout or a reset
    assert answer.split(b" ", 2)[1] in (b"200", b"422"), answer[:200]
    assert b"application/json" in answer.split(b"\r\n\r\n", 1)[0].lower()


def test_slow_bodies_at_the_cap_cost_ordinary_clients_nothing(server):
    """As many trickling bodies as the cap (each sends one byte every half second, so
    none is ever stalled, and is opened again when evicted), which with the clients'
    connections exceed it by about a tenth, as bench/load.py --slow-bodies 1100 does a cap
    of 1000: every request of a raw keep-alive socket, an httpx pool and fresh
    connections is answered, and what is evicted is the slow bodies. Before: an idle
    keep-alive connection was evicted before a trickling body, and its next request went
    unanswered (issue 42: 2 of 507 ordinary requests dropped under 1,100 slow bodies)."""
    import asyncio
    import threading

    from bench.load import slow_bodies, slow_out

    url, port = server
    before = _guards(url)
    out = slow_out()
    stop = time.monotonic() + 7.0
    flood = threading.Thread(target=lambda: asyncio.run(slow_bodies(url, CAP, stop, out)))
    # the keep-alive clients make a first request before the flood (a connection that
    # sends nothing for stall_grace_s is stalled, rightly)
    keep = socket.create_connection(("127.0.0.1", port), timeout=5.0)
    keep.sendall(REQUEST)
    assert _one_response(keep).startswith(b"HTTP/1.1 200")
    pooled = httpx.Client(base_url=url, timeout=10.0)
    assert pooled.get("/api/health").status_code == 200
    answers: list = []
    flood.start()
    try:
        time.sleep(1.5)              # the cap is full of slow bodies and evicting them
        while time.monotonic() < stop - 0.5:
            try:
                keep.sendall(REQUEST)
                answers.append(_one_response(keep)[:12])
            except OSError as exc:
                answers.append(repr(exc))
            for client in (pooled, None):
                try:
                    if client is None:
                        with httpx.Client(timeout=10.0) as fresh:
                            answers.append(fresh.get(f"{url}/api/health").status_code)
                    else:
                        answers.append(client.get("/api/health").status_code)
                except httpx.TransportError as exc:
                    answers.append(repr(exc))
            time.sleep(0.2)
    finally:
        flood.join(15)
        keep.close()
        pooled.close()
    after = _guards(url)
    by = {k: after["evicted_by"][k] - before["evicted_by"][k] for k in after["evicted_by"]}
    rounds = len(answers) // 3
    assert rounds >= 5, answers
    assert answers == [b"HTTP/1.1 200", 200, 200] * rounds, answers
    # the slow bodies filled the cap and were evicted by their own reconnections
    assert out["opened"] > CAP and out["closed_by_server"] > 0, out
    assert by["slowest"] > 0 and by["idle"] == 0, by
    assert after["refused"] == before["refused"], (before, after)


class _Conn:
    """What Candidates reads of a connection: its kind, its body's bytes, whether the app
    paused its reading (hashable by identity, as the protocol objects are)."""

    def __init__(self, kind: str, body_bytes: int = 0):
        from types import SimpleNamespace

        self._kind, self._in_bytes = kind, body_bytes
        self.flow = SimpleNamespace(read_paused=False)


def test_the_slowest_request_goes_before_an_idle_client_and_a_fast_upload():
    """The ranks of Candidates.victim below the stalled one, on the candidates as the
    protocol files them (kinds by last sign of life, `inflight` by the request's start):
    a trickling body, then a head, then an idle connection, then a fast upload."""
    from app.core.eviction import Candidates

    now, grace = 100.0, 1.0
    cands = Candidates()
    trickle = _Conn("body", body_bytes=12)        # began 6 s ago, a byte 0.4 s ago
    upload = _Conn("body", body_bytes=900_000)    # began 8 s ago, streaming fast
    fresh = _Conn("head")                         # a client's connection, 5 ms old
    idle = _Conn("idle")
    cands.inflight.update({upload: now - 8, trickle: now - 6, fresh: now - 0.005})
    cands.kinds["body"].update({upload: now - 0.001, trickle: now - 0.4})
    cands.kinds["head"][fresh] = now - 0.005
    cands.kinds["idle"][idle] = now - 3
    assert cands.victim(now, grace) == (trickle, "slowest")
    # without the trickle: the head is the slowest in progress (a flood's own sockets are
    # older than a client's, which is why a flood of empty sockets evicts its own)
    for d in (cands.inflight, cands.kinds["body"]):
        d.pop(trickle)
    assert cands.victim(now, grace) == (fresh, "slowest")
    # nothing arriving slowly: the idle keep-alive connection, then the upload
    cands.inflight.pop(fresh)
    cands.kinds["head"].pop(fresh)
    assert cands.victim(now, grace) == (idle, "idle")
    cands.kinds["idle"].pop(idle)
    assert cands.victim(now, grace) == (upload, "young_body")
    # a trickling body goes before an older head not read yet (a busy client's, maybe)
    starting = _Conn("body", body_bytes=0)
    older = _Conn("head")
    cands.inflight.update({older: now - 0.3, starting: now - 0.2})
    cands.kinds["head"][older] = now - 0.3
    cands.kinds["body"][starting] = now - 0.2
    assert cands.victim(now, grace) == (starting, "slowest")
    for d in (cands.inflight, cands.kinds["body"]):
        d.pop(starting)
    assert cands.victim(now, grace) == (older, "slowest")
    for d in (cands.inflight, cands.kinds["head"]):
        d.pop(older)
    # a body the app paused is neither slow nor stalled
    upload.flow.read_paused = True
    assert cands.victim(now + 5, grace) is None
