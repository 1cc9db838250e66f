"""Load test of the explorer on loopback: N concurrent users for a fixed time while a
prober measures GET /api/health. Bounded in users and time; it stops itself.

    python bench/load.py                         # 20 users, 60 s, its own server
    python bench/load.py --users 4 --duration 5 --json
    python bench/load.py --url http://127.0.0.1:8000   # an explorer already running
    python bench/load.py --slow-bodies 1100 --seconds 40   # hostile: slow request bodies

The users (simulate, pages and a 50 MB body): one user in four browses the pages
(the home page, a case page and the scripts and data they load, plotly.js included); one
user sends 50 MB bodies to POST /api/simulate, by turns with Content-Length and streamed
(chunked), reading the answer while it sends, as a browser does; the others send the demo
run of a case of Tables 1-2 (t_end 100, 201 samples), cycling through the cases, and
honour Retry-After on 503 (the designed answer of a full queue).
Reported: latency p50/p99 of the runs and of the pages, the answers to the big bodies and
how fast they came, p50/p99/max of the health probe, and the unplanned 5xx (every 5xx
except 503), which must be zero.
--slow-bodies N holds N request bodies open beside them (slow_bodies). Reported as well:
the ordinary requests (runs, pages, health probes) and how many of them were dropped (no
answer: the connection closed or reset), which must be zero.
"""

from __future__ import annotations

import argparse
import asyncio
import json
import multiprocessing
import os
import platform
import resource
import statistics
import sys
import time
from pathlib import Path

import httpx

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

def pct(xs: list[float], q: float) -> float:
    if not xs:
        return float("nan")
    xs = sorted(xs)
    return xs[min(len(xs) - 1, max(0, round(q / 100 * (len(xs) - 1))))]


async def user(client: httpx.AsyncClient, cases: list[str], k: int, stop: float,
               lat: list[float], status: dict[int, int], errors: list[str]) -> None:
    i = k
    while time.monotonic() < stop:
        body = {"case": cases[i % len(cases)], "example": True, "t_end": 100.0, "samples": 201}
        i += 1
        t0 = time.perf_counter()
        try:
            r = await client.post("/api/simulate", json=body)
        except httpx.HTTPError as exc:
            errors.append(f"{type(exc).__name__}: {exc}")
            status[0] = status.get(0, 0) + 1
            continue
        dt = time.perf_counter() - t0
        status[r.status_code] = status.get(r.status_code, 0) + 1
        if r.status_code == 200:
            lat.append(dt)
        elif r.status_code == 503:
            await asyncio.sleep(float(r.headers.get("retry-after", "1")))
        elif r.status_code >= 500:
            errors.append(f"{r.status_code}: {r.text[:200]}")


PAGES = ["/", "/static/js/home.js", "/static/css/app.css", "/api/tables/plane",
         "/case/plane/chaplygin-ball", "/static/js/case.js", "/vendor/plotly.min.js",
         "/api/cases/plane/chaplygin-ball", "/static/vendor/katex/katex.min.js"]
BIG = 50 * 2**20


async def browser(client: httpx.AsyncClient, stop: float, lat: list[float],
                  status: dict[int, int], errors: list[str]) -> None:
    i = 0
    while time.monotonic() < stop:
        path = PAGES[i % len(PAGES)]
        i += 1
        t0 = time.perf_counter()
        try:
            r = await client.get(path)
        except httpx.HTTPError as exc:
            errors.append(f"GET {path}: {type(exc).__name__}: {exc}")
            status[0] = status.get(0, 0) + 1
            continue
        status[r.status_code] = status.get(r.status_code, 0) + 1
        if r.status_code == 200:
            lat.append(time.perf_counter() - t0)
        elif r.status_code >= 500:
            errors.append(f"GET {path}: {r.status_code}")


async def _answer_while_sending(reader, writer, send, sent: list, out: dict,
                                silence_is_error: bool = True) -> int:
    """Send (the coroutine `send`, counting bytes in sent[0]) while reading the answer's
    head; stop sending once it has come. The answer's status code, 0 for none (an error
    line too unless silence_is_error is False)."""
    answer = asyncio.create_task(reader.readuntil(b"\r\n\r\n"))
    sender = asyncio.create_task(send())
    try:
        await asyncio.wait({answer}, timeout=60)
        raw = answer.result() if answer.done() else b""
        if not raw and silence_is_error:
            out["errors"].append(f"no answer after {sent[0]} bytes")
        return int(raw.split(b" ", 2)[1]) if raw else 0
    except (ConnectionError, asyncio.IncompleteReadError, OSError) as exc:
        out["errors"].append(f"{type(exc).__name__} after {sent[0]} bytes")
        return 0
    finally:
        for t in (answer, sender):
            t.cancel()
        await asyncio.gather(answer, sender, return_exceptions=True)
        writer.close()


async def big_bodies(url: str, stop: float, out: dict) -> None:
    """POST 50 MB bodies over a raw connection: send in 1 MB chunks while reading the
    answer, stop sending once it has come (what a browser's fetch does). The server
    answers 413 and stops reading: a send that blocks is not waited for."""
    host, port = url.split("//", 1)[1].split(":")
    chunk = b"[" + b"0," * (2**19 - 1) + b"0"    # 1 MB of a JSON array
    k = 0
    while time.monotonic() < stop:
        chunked = k % 2 == 1
        k += 1
        try:
            reader, writer = await asyncio.open_connection(host, int(port))
        except OSError as exc:
            out["errors"].append(f"connect: {exc}")
            await asyncio.sleep(0.2)
            continue
        head = (f"POST /api/simulate HTTP/1.1\r\nHost: {host}:{port}\r\n"
                "Content-Type: application/json\r\n"
                + ("Transfer-Encoding: chunked\r\n" if chunked else f"Content-Length: {BIG}\r\n")
                + "\r\n").encode()
        t0 = time.perf_counter()
        sent = [0]

        # the head at once, as a browser sends it; the body from the sending task
        writer.write(head)

        async def send(writer=writer, sent=sent, chunked=chunked):
            while sent[0] < BIG:
                piece = chunk[:BIG - sent[0]]
                writer.write(b"%x\r\n%s\r\n" % (len(piece), piece) if chunked else piece)
                await writer.drain()
                sent[0] += len(piece)

        code = await _answer_while_sending(reader, writer, send, sent, out)
        key = f"{'chunked' if chunked else 'length'}:{code}"
        out["status"][key] = out["status"].get(key, 0) + 1
        out["answer_ms"].append(1e3 * (time.perf_counter() - t0))
        out["sent_mb"].append(sent[0] / 2**20)
        await asyncio.sleep(0.2)


async def header_bombs(url: str, stop: float, out: dict) -> None:
    """A 50 MB header, sent in 64 KB pieces while reading: the server should answer 431
    after its head limit and close, long before the 50 MB."""
    host, port = url.split("//", 1)[1].split(":")
    piece = b"a" * 65536
    while time.monotonic() < stop:
        try:
            reader, writer = await asyncio.open_connection(host, int(port))
        except OSError as exc:
            out["errors"].append(f"connect: {exc}")
            await asyncio.sleep(0.2)
            continue
        t0, sent = time.perf_counter(), [0]

        async def send(writer=writer, sent=sent):
            writer.write(f"GET /api/health HTTP/1.1\r\nHost: {host}:{port}\r\n"
                         "X-Bomb: ".encode())
            while sent[0] < BIG:
                writer.write(piece)
                await writer.drain()
                sent[0] += len(piece)

        code = await _answer_while_sending(reader, writer, send, sent, out,
                                           silence_is_error=False)
        out["status"][code] = out["status"].get(code, 0) + 1
        out["answer_ms"].append(1e3 * (time.perf_counter() - t0))
        out["sent_mb"].append(sent[0] / 2**20)
        await asyncio.sleep(0.2)


STALLED_HEAD = b"GET /api/health HTTP/1.1\r\nHost: 127.0.0.1\r\nX-Stalled: "
STALLED_BODY = (b"POST /api/validate HTTP/1.1\r\nHost: 127.0.0.1\r\n"
                b"Content-Type: application/json\r\nContent-Length: 1000\r\n\r\n{\"case\": ")


async def stalled_flood(url: str, count: int, stop: float, out: dict) -> None:
    """Open `count` sockets (bounded), half of them with half a head, half with half a
    body, at about 500 a second, and hold each until the server closes it or the run
    ends. Reported: how many the server closed and after how long."""
    host, port = url.split("//", 1)[1].split(":")

    async def one(k: int) -> None:
        try:
            reader, writer = await asyncio.open_connection(host, int(port))
        except OSError as exc:
            out["connect_errors"] += 1
            if len(out["errors"]) < 5:
                out["errors"].append(f"connect: {exc}")
            return
        out["opened"] += 1
        t0 = time.monotonic()
        try:
            writer.write(STALLED_HEAD if k % 2 == 0 else STALLED_BODY)
            await writer.drain()
            left = stop - time.monotonic()
            if left > 0:
                await asyncio.wait_for(reader.read(), left)   # b"" or an answer: closed
                out["closed_by_server"] += 1
                out["held_s"].append(time.monotonic() - t0)
        except TimeoutError:
            out["still_open_at_end"] += 1
        except (ConnectionError, OSError):
            out["closed_by_server"] += 1
            out["held_s"].append(time.monotonic() - t0)
        finally:
            writer.close()

    async with asyncio.TaskGroup() as tg:
        for k in range(count):
            if time.monotonic() >= stop:
                break
            tg.create_task(one(k))
            if k % 50 == 49:
                await asyncio.sleep(0.1)


# --slow-bodies N: N connections, each sending the head of a POST with a 1000-byte body,
# then one byte of it (JSON whitespace) every TICK_S: never silent long enough to be
# stalled (app.core.server's stall_grace_s, 1 s), never ending within the run. One the
# server closes (an eviction at its cap) is opened again at once: N are held the whole
# run, and more than the cap (1000) keeps the server evicting.
SLOW_HEAD = (b"POST /api/validate HTTP/1.1\r\nHost: 127.0.0.1\r\n"
             b"Content-Type: application/json\r\nContent-Length: 1000\r\n\r\n")
TICK_S = 0.5


def slow_out() -> dict:
    return {"held": 0, "opened": 0, "closed_by_server": 0, "connect_errors": 0,
            "bytes_sent": 0, "errors": []}


def raise_fd_limit(count: int) -> None:
    """Room for `count` held sockets besides the ordinary clients: the soft file limit
    raised towards the hard one (a soft limit of 1024 is common)."""
    soft, hard = resource.getrlimit(resource.RLIMIT_NOFILE)
    if soft != resource.RLIM_INFINITY and soft < count + 512:
        target = count + 512 if hard == resource.RLIM_INFINITY else min(count + 512, hard)
        resource.setrlimit(resource.RLIMIT_NOFILE, (target, hard))


async def _slow_one(host: str, port: int, stop: float, out: dict) -> None:
    """One slow body at a time, opened again whenever the server closes it."""
    while time.monotonic() < stop:
        try:
            reader, writer = await asyncio.open_connection(host, port)
        except OSError as exc:
            out["connect_errors"] += 1
            if len(out["errors"]) < 5:
                out["errors"].append(f"connect: {exc}")
            await asyncio.sleep(TICK_S)
            continue
        out["opened"] += 1
        try:
            writer.write(SLOW_HEAD)
            await writer.drain()
            while time.monotonic() < stop:
                await asyncio.sleep(TICK_S)
                if reader.at_eof() or reader.exception() or writer.transport.is_closing():
                    break
                writer.write(b" ")
                await writer.drain()
                out["bytes_sent"] += 1
            else:
                continue                 # the run ended with this one open
            out["closed_by_server"] += 1
        except (ConnectionError, OSError):
            out["closed_by_server"] += 1
        finally:
            writer.close()


async def slow_bodies(url: str, count: int, stop: float, out: dict) -> None:
    """Hold `count` slow bodies until `stop` (opened at about 1000 a second, 10 at a time:
    a burst as large as a small cap would fill it before the server has read a byte of
    any, when every connection, the ordinary clients' too, is a head not read yet)."""
    host, port = url.split("//", 1)[1].split(":")
    out["held"] = count
    async with asyncio.TaskGroup() as tg:
        for k in range(count):
            if time.monotonic() >= stop:
                break
            tg.create_task(_slow_one(host, int(port), stop, out))
            if k % 10 == 9:
                await asyncio.sleep(0.01)


def prober(url: str, duration: float, out) -> None:
    """GET /api/health every 0.1 s from a process of its own, so that the latency measured
    is the server's, not that of the load generator's busy event loop."""
    lat, status = [], {}
    stop = time.monotonic() + duration
    with httpx.Client(base_url=url, timeout=30.0) as client:
        while time.monotonic() < stop:
            t0 = time.perf_counter()
            try:
                r = client.get("/api/health")
                status[r.status_code] = status.get(r.status_code, 0) + 1
                lat.append(time.perf_counter() - t0)
            except httpx.HTTPError:
                status[0] = status.get(0, 0) + 1
            time.sleep(0.1)
    out.put((lat, status))


async def load(url: str, users: int, duration: float, pages: int | None = None,
               big: int | None = None, bombs: int = 0, stalled: int = 0,
               slow: int = 0) -> dict:
    load0 = os.getloadavg()[0]
    limits = httpx.Limits(max_connections=users + 2, max_keepalive_connections=users + 2)
    timeout = httpx.Timeout(120.0)
    async with httpx.AsyncClient(base_url=url, limits=limits, timeout=timeout) as client:
        cases = [c["id"] for c in (await client.get("/api/cases")).json()]
        sim_lat: list[float] = []
        sim_status: dict[int, int] = {}
        errors: list[str] = []
        ctx = multiprocessing.get_context("spawn")
        queue = ctx.Queue()
        probe = ctx.Process(target=prober, args=(url, duration, queue), daemon=True)
        probe.start()
        t0 = time.monotonic()
        stop = t0 + duration
        page_lat: list[float] = []
        page_status: dict[int, int] = {}
        n_pages = users // 4 if pages is None else pages
        n_big = (1 if users >= 4 else 0) if big is None else big
        big = {"status": {}, "answer_ms": [], "sent_mb": [], "errors": []}
        bomb = {"status": {}, "answer_ms": [], "sent_mb": [], "errors": []}
        flood = {"opened": 0, "connect_errors": 0, "closed_by_server": 0,
                 "still_open_at_end": 0, "held_s": [], "errors": []}
        trickle = slow_out()
        async with asyncio.TaskGroup() as tg:
            for _ in range(bombs):
                tg.create_task(header_bombs(url, stop, bomb))
            if stalled:
                tg.create_task(stalled_flood(url, stalled, stop, flood))
            if slow:
                tg.create_task(slow_bodies(url, slow, stop, trickle))
            for k in range(users - n_pages - n_big):
                tg.create_task(user(client, cases, k, stop, sim_lat, sim_status, errors))
            for _ in range(n_pages):
                tg.create_task(browser(client, stop, page_lat, page_status, errors))
            for _ in range(n_big):
                tg.create_task(big_bodies(url, stop, big))
        wall = time.monotonic() - t0
        health_lat, health_status = await asyncio.to_thread(queue.get, True, duration + 60)
        probe.join(10)
        final = (await client.get("/api/health")).json()
        pool, server_conn = final["pool"], final.get("connections")
    unplanned = sum(n for s, n in [*sim_status.items(), *health_status.items(),
                                   *page_status.items()] if s >= 500 and s != 503)
    dropped = sim_status.get(0, 0) + health_status.get(0, 0) + page_status.get(0, 0)
    unplanned += dropped
    ordinary = sum(sim_status.values()) + sum(health_status.values()) + sum(
        page_status.values())
    unplanned += sum(n for k, n in big["status"].items() if not k.endswith(":413"))
    unplanned += sum(n for k, n in bomb["status"].items() if k != 431)
    return {
        "users": users, "duration_s": duration, "wall_s": wall, "loadavg_before": load0,
        "mix": {"simulate": users - n_pages - n_big, "pages": n_pages, "big_body": n_big},
        "pages": {"ok": len(page_lat), "p50_ms": 1e3 * pct(page_lat, 50),
                  "p99_ms": 1e3 * pct(page_lat, 99),
                  "status": {str(k): v for k, v in sorted(page_status.items())}},
        "big_body": {"sent": len(big["answer_ms"]), "status": big["status"],
                     "answer_p50_ms": pct(big["answer_ms"], 50),
                     "answer_max_ms": max(big["answer_ms"], default=float("nan")),
                     "max_sent_mb": max(big["sent_mb"], default=0.0),
                     "errors": big["errors"][:5]},
        "simulate": {"ok": len(sim_lat), "throughput_per_s": len(sim_lat) / wall,
                     "p50_ms": 1e3 * pct(sim_lat, 50), "p99_ms": 1e3 * pct(sim_lat, 99),
                     "mean_ms": 1e3 * statistics.fmean(sim_lat) if sim_lat else None,
                     "status": {str(k): v for k, v in sorted(sim_status.items())}},
        "health": {"probes": len(health_lat), "p50_ms": 1e3 * pct(health_lat, 50),
                   "p99_ms": 1e3 * pct(health_lat, 99),
                   "max_ms": 1e3 * max(health_lat) if health_lat else None,
                   "status": {str(k): v for k, v in sorted(health_status.items())}},
        "header_bombs": {"clients": bombs, "sent": len(bomb["answer_ms"]),
                         "status": {str(k): v for k, v in bomb["status"].items()},
                         "answer_p50_ms": pct(bomb["answer_ms"], 50),
                         "answer_max_ms": max(bomb["answer_ms"], default=float("nan")),
                         "max_sent_mb": max(bomb["sent_mb"], default=0.0),
                         "errors": bomb["errors"][:5]},
        "stalled": {"attempted": stalled, **{k: v for k, v in flood.items() if k != "held_s"},
                    "held_p50_s": pct(flood["held_s"], 50),
                    "held_max_s": max(flood["held_s"], default=float("nan"))},
        "slow_bodies": trickle,
        "ordinary": {"requests": ordinary, "dropped": dropped,
                     "dropped_by_kind": {"simulate": sim_status.get(0, 0),
                                         "pages": page_status.get(0, 0),
                                         "health": health_status.get(0, 0)}},
        "server_connections": server_conn,
        "unplanned_5xx": unplanned,
        "errors": errors[:10],
        "server_pool": pool,
    }


def report(r: dict, settings: dict) -> str:
    s, h = r["simulate"], r["health"]
    lines = [
        "Load test of the explorer (bench/load.py) on loopback",
        f"machine: {os.cpu_count()} cores, {platform.python_implementation()} "
        f"{platform.python_version()}, {platform.system()}; load average before the run "
        f"{r['loadavg_before']:.2f} (other jobs on the machine share the cores)",
        f"server: uvicorn app.main:app, {settings}",
        f"load: {r['users']} concurrent users for {r['duration_s']:g} s: {r['mix']['simulate']} "
        "POST /api/simulate (demo run of a case of Tables 1-2, t_end 100, 201 samples, "
        f"Retry-After honoured), {r['mix']['pages']} browsing pages and their assets, "
        f"{r['mix']['big_body']} sending 50 MB bodies (Content-Length and chunked by turns)",
        "",
        f"simulate: {s['ok']} runs answered 200 ({s['throughput_per_s']:.1f}/s); "
        f"latency p50 {s['p50_ms']:.0f} ms, p99 {s['p99_ms']:.0f} ms",
        f"          answers by status: {s['status']}",
        f"pages:    {r['pages']['ok']} answered 200; latency p50 {r['pages']['p50_ms']:.0f} ms, "
        f"p99 {r['pages']['p99_ms']:.0f} ms; by status {r['pages']['status']}",
        f"50 MB:    {r['big_body']['sent']} bodies; answers {r['big_body']['status']}; "
        f"answer after p50 {r['big_body']['answer_p50_ms']:.1f} ms, max "
        f"{r['big_body']['answer_max_ms']:.1f} ms; at most {r['big_body']['max_sent_mb']:.0f} MB "
        "sent before the answer",
        f"health:   {h['probes']} probes every 0.1 s; p50 {h['p50_ms']:.1f} ms, "
        f"p99 {h['p99_ms']:.1f} ms, max {h['max_ms']:.1f} ms (goal p99 < 100 ms)",
        "unplanned 5xx (5xx other than 503, no answer, a big body not refused with 413, or "
        f"a header bomb not refused with 431): {r['unplanned_5xx']}",
        f"server pool afterwards: {r['server_pool']}",
    ]
    b, f = r["header_bombs"], r["stalled"]
    if b["clients"]:
        lines.insert(-2, f"50 MB heads: {b['clients']} clients, {b['sent']} heads; answers "
                     f"{b['status']}; answer after p50 {b['answer_p50_ms']:.1f} ms, max "
                     f"{b['answer_max_ms']:.1f} ms; at most {b['max_sent_mb']:.1f} MB sent "
                     "before the answer")
    if f["attempted"]:
        lines.insert(-2, f"stalled:  {f['attempted']} sockets attempted (half a head or half "
                     f"a body), {f['opened']} opened, {f['connect_errors']} refused at "
                     f"connect; {f['closed_by_server']} closed by the server after p50 "
                     f"{f['held_p50_s']:.1f} s, max {f['held_max_s']:.1f} s; "
                     f"{f['still_open_at_end']} still open at the end")
    t = r["slow_bodies"]
    if t["held"]:
        lines.insert(-2, f"slow bodies: {t['held']} held (one byte every 0.5 s), "
                     f"{t['opened']} connections opened, {t['closed_by_server']} closed by "
                     f"the server, {t['connect_errors']} refused at connect, "
                     f"{t['bytes_sent']} bytes sent")
    o = r["ordinary"]
    lines.insert(-2, f"ordinary requests (runs, pages, health probes): {o['requests']}, "
                 f"dropped (no answer) {o['dropped']} {o['dropped_by_kind']}")
    if r.get("server_connections"):
        lines.append(f"server connection guards: {r['server_connections']}")
    if r["errors"]:
        lines.append(f"errors: {r['errors']}")
    return "\n".join(lines) + "\n"


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--users", type=int, default=20)
    ap.add_argument("--duration", "--seconds", type=float, default=60.0)
    ap.add_argument("--url", help="an explorer already running (default: start one)")
    ap.add_argument("--pages", type=int, help="users browsing pages (default users // 4)")
    ap.add_argument("--big", type=int, help="users sending 50 MB bodies (default 1)")
    ap.add_argument("--bombs", type=int, default=0,
                    help="extra clients sending 50 MB headers in a loop (at most 8)")
    ap.add_argument("--stalled", type=int, default=0,
                    help="stalled sockets to attempt (half a head or body; at most 5000)")
    ap.add_argument("--slow-bodies", type=int, default=0,
                    help="request bodies held open, one byte every 0.5 s (at most 5000)")
    ap.add_argument("--hostile", action="store_true",
                    help="the hostile mix: --big 3 --bombs 2 --stalled 3000")
    ap.add_argument("--max-connections", type=int,
                    help="the server's connection cap (default: its setting, 1000); a "
                    "smaller one lets a slow flood fill it on a loaded machine")
    ap.add_argument("--plain-uvicorn", action="store_true",
                    help="start `uvicorn app.main:app` with its defaults (httptools, no "
                    "bounds) instead of app.core.server, for comparison")
    ap.add_argument("--json", action="store_true", help="print the figures as JSON")
    ap.add_argument("--out", help="also write the report to this file")
    args = ap.parse_args(argv)
    raise_fd_limit(args.stalled + args.slow_bodies)
    if args.hostile:
        args.big = 3 if args.big is None else args.big
        args.bombs = args.bombs or 2
        args.stalled = args.stalled or 3000
    if not (1 <= args.users <= 200 and 0 < args.duration <= 600):
        ap.error("users in [1, 200], duration in (0, 600] s")
    if not (0 <= args.bombs <= 8 and 0 <= args.stalled <= 5000
            and 0 <= args.slow_bodies <= 5000):
        ap.error("--bombs in [0, 8], --stalled and --slow-bodies in [0, 5000]")
    if args.max_connections is not None and not 8 <= args.max_connections <= 100_000:
        ap.error("--max-connections in [8, 100000]")
    if (args.pages or 0) + (args.big or 0) > args.users or min(args.pages or 0,
                                                               args.big or 0) < 0:
        ap.error("--pages and --big are parts of --users")

    def run(url: str, settings: dict) -> dict:
        r = asyncio.run(load(url, args.users, args.duration, args.pages, args.big,
                             args.bombs, args.stalled, args.slow_bodies))
        text = report(r, settings)
        print(json.dumps(r, indent=1) if args.json else text, end="" if not args.json else "\n")
        if args.out:
            Path(args.out).write_text(text)
        return r

    if args.url:
        if not args.url.startswith(("http://127.", "http://localhost", "http://[::1]")):
            ap.error("loopback addresses only")
        r = run(args.url, {"url": args.url})
    else:
        from app.core.config import Settings
        from app.testing import live_server, wait_idle

        s = Settings()
        cap = {} if args.max_connections is None else {"max_connections": args.max_connections}
        settings = {"workers": s.workers, "queue_size": s.queue_size,
                    "deadline_s": s.deadline_s, "max_steps": s.max_steps, **cap,
                    "server": "plain uvicorn (httptools)" if args.plain_uvicorn else
                    "app.core.server (h11 + bounds)"}
        # the defaults of `rolling serve`, without the background verification
        with live_server(plain_uvicorn=args.plain_uvicorn,
                         verify_on_start=False, workers=s.workers, queue_size=s.queue_size,
                         deadline_s=s.deadline_s, max_steps=s.max_steps, **cap) as url:
            wait_idle(url, timeout=600)
            r = run(url, settings)
    return 1 if r["unplanned_5xx"] else 0


if __name__ == "__main__":
    sys.exit(main())
