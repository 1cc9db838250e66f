"""What the connection cap of app/core/server.py costs:

1. choosing the connection to evict at the cap, among `--cap` open connections (half of
   them stalled heads, half stalled bodies, a few idle keep-alive ones): the ordered
   candidates of app.core.server (_Candidates.victim) against the linear scan over every
   connection (the former choice, copied below), in the same process;
2. what held connections cost a live server: its resident memory with 0 and with `--hold`
   stalled sockets (half a head or half a body), and how many connections a second it
   accepts and evicts while a flood opens them as fast as one client can;
3. --body-cpu: the server's CPU time per stalled half body at the cap (100, held by
   stalled half bodies; 1000 more opened, then a pause for the server to drain them).
   The server evicts each stalled one.
4. with --profile: what legitimate clients look like to the server, to set stall_grace_s:
   a server whose protocol records, for every request that completed, the time its head
   took (from the connection, or from the first byte of a keep-alive connection's next
   request), the longest gap inside its body, and the idle gap before a keep-alive
   connection's next request, while bench/load.py runs against it (add --hostile to run
   its hostile mix; evicted and timed-out connections are not recorded).

    python bench/connection_cap.py                  # cap 1000, hold 1000
    python bench/connection_cap.py --cap 4000 --hold 4000
    python bench/connection_cap.py --profile 20 [--hostile]
    python bench/connection_cap.py --body-cpu
"""

from __future__ import annotations

import argparse
import asyncio
import multiprocessing
import os
import platform
import socket
import sys
import time
from pathlib import Path

import h11

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

HALF_HEAD = b"GET /api/health HTTP/1.1\r\nHost: 127.0.0.1\r\nX-Stalled: "
HALF_BODY = (b"POST /api/validate HTTP/1.1\r\nHost: 127.0.0.1\r\n"
             b"Content-Type: application/json\r\nContent-Length: 1000\r\n\r\n{\"case\": ")


class _Transport:
    """Enough of an asyncio transport for the protocol's bookkeeping."""

    def get_extra_info(self, name, default=None):
        return {"sockname": ("127.0.0.1", 8000), "peername": ("127.0.0.1", 40000)}.get(
            name, default)

    def is_closing(self):
        return False

    def set_write_buffer_limits(self, *a, **k):
        pass

    def pause_reading(self):
        pass

    def resume_reading(self):
        pass

    def write(self, data):
        pass


def _old_scan(protocols) -> object:
    """The former choice, a linear scan (the yardstick): every connection that holds no request,
    the never-served first, then the oldest."""
    idle = [p for p in protocols if p.conn.their_state is h11.IDLE
            and (p.cycle is None or p.cycle.response_complete)
            and not p.transport.is_closing()]
    return min(idle, key=lambda p: (p._served > 0, p._t0)) if idle else None


def pick_cost(cap: int, rounds: int) -> dict:
    import uvicorn
    from uvicorn.server import ServerState

    from app.core.server import Limits, protocol_for

    async def app(scope, receive, send):   # never called
        pass

    loop = asyncio.new_event_loop()
    cls = protocol_for(Limits(max_connections=cap + 1))
    config = uvicorn.Config(app, http=cls, log_level="warning")
    config.load()
    state = ServerState()
    protocols = []
    for k in range(cap):
        p = cls(config, state, {}, _loop=loop)
        p.connection_made(_Transport())
        p._t0 = time.monotonic()
        p.data_received(HALF_BODY if k % 2 else HALF_HEAD)
        protocols.append(p)
    kinds = {k: len(v) for k, v in protocols[0]._cands.kinds.items()}
    now, grace = time.monotonic() + 5.0, 1.0
    t0 = time.perf_counter()
    for _ in range(rounds):
        _old_scan(state.connections)
    old = (time.perf_counter() - t0) / rounds
    t0 = time.perf_counter()
    for _ in range(rounds):
        protocols[0]._cands.victim(now, grace)
    new = (time.perf_counter() - t0) / rounds
    tasks = [t for p in protocols for t in p.tasks]
    for p in protocols:
        p._cancel_timer()
    for t in tasks:
        t.cancel()
    loop.run_until_complete(asyncio.gather(*tasks, return_exceptions=True))
    loop.close()
    return {"cap": cap, "kinds": kinds, "old_scan_us": 1e6 * old, "ordered_us": 1e6 * new}


def _rss_kb(pid: int) -> int:
    for line in Path(f"/proc/{pid}/status").read_text().splitlines():
        if line.startswith("VmRSS:"):
            return int(line.split()[1])
    return 0


def _server_pid(port: int) -> int:
    import psutil

    for c in psutil.net_connections("tcp"):
        if c.status == psutil.CONN_LISTEN and c.laddr.port == port and c.pid:
            return c.pid
    raise RuntimeError("no server process listens on the port")


def _flood(port: int, seconds: float) -> int:
    """Open half-head sockets as fast as one client can for `seconds`; how many."""
    held, n, t0 = [], 0, time.monotonic()
    while time.monotonic() - t0 < seconds:
        try:
            s = socket.create_connection(("127.0.0.1", port), timeout=5.0)
            s.sendall(HALF_HEAD)
        except OSError:
            continue
        held.append(s)
        n += 1
        if len(held) > 2000:             # keep this client's own file count bounded
            for s in held[:1000]:
                s.close()
            del held[:1000]
    for s in held:
        s.close()
    return n


def held_cost(hold: int, cap: int, flood_s: float, clients: int) -> dict:
    import httpx

    from app.testing import live_server

    with live_server(max_connections=cap, header_timeout_s=60.0, body_timeout_s=60.0) as url:
        port = int(url.rsplit(":", 1)[1])
        pid = _server_pid(port)
        httpx.get(f"{url}/api/health")
        time.sleep(1.0)
        rss0 = _rss_kb(pid)
        held = []
        for k in range(hold):
            s = socket.create_connection(("127.0.0.1", port), timeout=5.0)
            s.sendall(HALF_BODY if k % 2 else HALF_HEAD)
            held.append(s)
        time.sleep(1.0)
        c = httpx.get(f"{url}/api/health").json()["connections"]
        rss1 = _rss_kb(pid)
        t0 = time.perf_counter()
        probe = [httpx.get(f"{url}/api/health").status_code for _ in range(20)]
        health_ms = 1e3 * (time.perf_counter() - t0) / 20
        # a flood from `clients` processes, each opening sockets as fast as it can
        before = c["evicted"] + c["refused"]
        ctx = multiprocessing.get_context("spawn")
        with ctx.Pool(clients) as pool:
            t0 = time.monotonic()
            n = sum(pool.starmap(_flood, [(port, flood_s)] * clients))
            took = time.monotonic() - t0
        c2 = httpx.get(f"{url}/api/health").json()["connections"]
        for s in held:
            s.close()
        rate = n / took
    return {"hold": hold, "open": c["open"], "rss0_mb": rss0 / 1024, "rss_mb": rss1 / 1024,
            "kb_per_connection": (rss1 - rss0) / max(1, c["open"] - 1),
            "health_ms_while_held": health_ms, "health_codes": sorted(set(probe)),
            "flood_per_s": rate, "flood_clients": clients,
            "server_per_s": (c2["evicted"] + c2["refused"] - before) / took,
            "flood_evicted_or_refused": c2["evicted"] + c2["refused"]
            - before, "evicted_by": c2["evicted_by"], "refused": c2["refused"]}


def body_cpu(cap: int = 100, n: int = 1000) -> dict:
    import httpx
    import psutil

    from app.testing import live_server

    with live_server(max_connections=cap, header_timeout_s=60.0, body_timeout_s=60.0) as url:
        port = int(url.rsplit(":", 1)[1])
        server = psutil.Process(_server_pid(port))
        held = [_half(port, HALF_BODY) for _ in range(cap)]
        time.sleep(2.0)
        cpu0 = sum(server.cpu_times()[:2])
        for _ in range(n):
            try:
                held.append(_half(port, HALF_BODY))
            except OSError:
                pass
            if len(held) > 4 * cap:      # this client's own sockets stay bounded
                for s in held[:2 * cap]:
                    s.close()
                del held[:2 * cap]
        time.sleep(3.0)
        cpu = sum(server.cpu_times()[:2]) - cpu0
        try:
            c = httpx.get(f"{url}/api/health", timeout=10.0).json()["connections"]
        except httpx.HTTPError as exc:       # main refused this one too
            c = f"health refused: {type(exc).__name__}"
        for s in held:
            s.close()
    return {"cap": cap, "n": n, "cpu_us": 1e6 * cpu / n, "connections": c}


def _half(port: int, what: bytes) -> socket.socket:
    s = socket.create_connection(("127.0.0.1", port), timeout=5.0)
    s.sendall(what)
    return s


def _serve_profiled(port: int, out: str) -> None:
    """The explorer's server with a protocol that records the legitimate clients' timing
    (see the module docstring), written to `out` as JSON every half second."""
    import json

    from app.core import server

    rec = {"head": [], "body": [], "idle": []}
    last = [0.0]
    place, victim = server.GuardedH11Protocol._place, server._Candidates.victim

    def measured_place(p, kind):
        old = p._kind
        since = p._cands.kinds[old].get(p) if old else None
        if since is not None and not getattr(p, "_evicted", False):
            now = time.monotonic()
            closing = p.transport is not None and p.transport.is_closing()
            if old == "head" and kind in ("body", None) and not closing:
                rec["head"].append(now - since)
            elif old == "body":
                p._gap = max(getattr(p, "_gap", 0.0), now - since)
                if kind is None and not closing:
                    rec["body"].append(p._gap)
                    p._gap = 0.0
            elif old == "idle" and kind in ("head", "body", None) and not closing:
                rec["idle"].append(now - since)
            if now - last[0] > 0.5:
                last[0] = now
                Path(out).write_text(json.dumps(rec))
        place(p, kind)

    def marked_victim(self, now, grace):
        found = victim(self, now, grace)
        if found is not None:
            found[0]._evicted = True
        return found

    server.GuardedH11Protocol._place = measured_place
    server._Candidates.victim = marked_victim
    server.main(["--port", str(port), "--log-level", "warning"])


def profile(duration: float, hostile: bool) -> dict:
    import json
    import signal
    import subprocess
    import tempfile

    import httpx

    from app.core.config import Settings
    from app.testing import TEST_SETTINGS, free_port, wait_idle

    s = Settings()
    port, out = free_port(), tempfile.NamedTemporaryFile(suffix=".json", delete=False).name
    settings = {**TEST_SETTINGS, "verify_on_start": False, "workers": s.workers,
                "queue_size": s.queue_size, "deadline_s": s.deadline_s,
                "max_steps": s.max_steps}       # as bench/load.py starts its server
    env = {**os.environ, **{f"ROLLING_{k.upper()}": json.dumps(v) if isinstance(v, list)
                            else str(v) for k, v in settings.items()}}
    proc = subprocess.Popen([sys.executable, __file__, "--serve-profiled", str(port), out],
                            env=env, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    url = f"http://127.0.0.1:{port}"
    try:
        t0 = time.monotonic()
        while True:
            try:
                if httpx.get(f"{url}/api/health", timeout=1.0).status_code == 200:
                    break
            except httpx.TransportError:
                pass
            if proc.poll() is not None or time.monotonic() - t0 > 120:
                raise RuntimeError("the profiled server did not start")
            time.sleep(0.2)
        wait_idle(url, timeout=600)
        load = subprocess.run([sys.executable, str(ROOT / "bench" / "load.py"), "--url", url,
                               "--duration", str(duration), "--json",
                               *(["--hostile"] if hostile else [])],
                              capture_output=True, text=True, timeout=duration + 600)
        time.sleep(1.0)
        r = json.loads(load.stdout)
    finally:
        proc.send_signal(signal.SIGTERM)
        try:
            proc.wait(15)
        except subprocess.TimeoutExpired:
            proc.kill()
    rec = json.loads(Path(out).read_text())
    Path(out).unlink()

    def q(xs, p):
        xs = sorted(xs)
        return 1e3 * xs[min(len(xs) - 1, int(p / 100 * len(xs)))] if xs else float("nan")

    return {"load_unplanned": r["unplanned_5xx"], "health_p99_ms": r["health"]["p99_ms"],
            **{k: {"n": len(v), "p50_ms": q(v, 50), "p99_ms": q(v, 99),
                   "max_ms": 1e3 * max(v, default=float("nan"))} for k, v in rec.items()}}


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--cap", type=int, default=1000)
    ap.add_argument("--hold", type=int, default=1000)
    ap.add_argument("--rounds", type=int, default=2000)
    ap.add_argument("--flood-s", type=float, default=3.0)
    ap.add_argument("--flood-clients", type=int, default=1)
    ap.add_argument("--body-cpu", action="store_true",
                    help="only the server's CPU per stalled half body at the cap")
    ap.add_argument("--profile", type=float, metavar="SECONDS",
                    help="profile the legitimate clients of bench/load.py for SECONDS")
    ap.add_argument("--hostile", action="store_true", help="with --profile: its hostile mix")
    ap.add_argument("--serve-profiled", nargs=2, metavar=("PORT", "OUT"),
                    help=argparse.SUPPRESS)
    a = ap.parse_args(argv)
    if a.serve_profiled:
        _serve_profiled(int(a.serve_profiled[0]), a.serve_profiled[1])
        return 0
    if a.body_cpu:
        r = body_cpu()
        print(f"machine: {os.cpu_count()} cores; load average {os.getloadavg()[0]:.2f}")
        print(f"server CPU per stalled half body at the cap ({r['cap']}, {r['n']} opened): "
              f"{r['cpu_us']:.0f} us; guards afterwards: {r['connections']}")
        return 0
    if a.profile:
        if not 0 < a.profile <= 120:
            ap.error("--profile in (0, 120] s")
        print(f"machine: {os.cpu_count()} cores; load average {os.getloadavg()[0]:.2f}")
        r = profile(a.profile, a.hostile)
        print(f"bench/load.py --duration {a.profile:g}{' --hostile' if a.hostile else ''} "
              f"against the profiled server: unplanned {r['load_unplanned']}, health p99 "
              f"{r['health_p99_ms']:.1f} ms")
        names = {"head": "head (connection or first byte -> whole head)",
                 "body": "longest gap inside a body", "idle": "keep-alive idle gap"}
        for k, label in names.items():
            v = r[k]
            print(f"  {label}: {v['n']} requests, p50 {v['p50_ms']:.1f} ms, p99 "
                  f"{v['p99_ms']:.1f} ms, max {v['max_ms']:.1f} ms")
        return 0
    if not (8 <= a.cap <= 8000 and 0 <= a.hold <= a.cap and 1 <= a.rounds <= 100_000
            and 0 < a.flood_s <= 30):
        ap.error("cap in [8, 8000], hold in [0, cap], rounds in [1, 1e5], flood-s in (0, 30]")
    print(f"machine: {os.cpu_count()} cores, {platform.python_implementation()} "
          f"{platform.python_version()}; load average {os.getloadavg()[0]:.2f}")
    p = pick_cost(a.cap, a.rounds)
    print(f"choosing a victim among {p['cap']} connections {p['kinds']}: linear scan "
          f"(before) {p['old_scan_us']:.0f} us, ordered candidates {p['ordered_us']:.2f} us")
    if not 1 <= a.flood_clients <= 4:
        ap.error("--flood-clients in [1, 4]")
    h = held_cost(a.hold, a.cap, a.flood_s, a.flood_clients)
    print(f"live server, cap {a.cap}: {h['open']} connections held, RSS {h['rss0_mb']:.0f} -> "
          f"{h['rss_mb']:.0f} MB ({h['kb_per_connection']:.1f} KB a connection); health "
          f"{h['health_ms_while_held']:.1f} ms a request meanwhile ({h['health_codes']})")
    print(f"flood from {h['flood_clients']} client(s): {h['flood_per_s']:.0f} new sockets/s "
          f"for {a.flood_s:g} s; the server evicted or refused {h['server_per_s']:.0f}/s, "
          f"{h['flood_evicted_or_refused']} in all (evicted_by "
          f"{h['evicted_by']}, refused {h['refused']})")
    return 0


if __name__ == "__main__":
    sys.exit(main())
