"""Slow request bodies for bench/load.py --slow-bodies N: N connections, each sending the
head of a POST with a 1000-byte body and then one byte of it every half second, so that
none is ever silent long enough to be stalled (app.core.server's stall_grace_s, 1 s) and
none ends within the run. A connection the server closes (an eviction at its connection
cap) is opened again at once, so that N are held for the whole run: more than the cap
keeps the server evicting, and what an ordinary client loses meanwhile is the measure.

The clients live in bench/load.py's event loop; their figures go to the dict `out`
(new_out()): connections opened, closed by the server, refused at connect, bytes sent."""

from __future__ import annotations

import asyncio
import resource
import time

HEAD = (b"POST /api/validate HTTP/1.1\r\nHost: 127.0.0.1\r\n"
        b"Content-Type: application/json\r\nContent-Length: 1000\r\n\r\n")
# one byte of the body every TICK_S seconds (JSON whitespace: the body stays valid so far)
TICK_S = 0.5
BYTE = b" "


def new_out() -> dict:
    return {"held": 0, "opened": 0, "closed_by_server": 0, "connect_errors": 0,
            "bytes_sent": 0, "errors": []}


def raise_fd_limit(count: int) -> None:
    """The bench holds `count` sockets besides its ordinary clients: raise its soft file
    limit towards the hard one (a soft limit of 1024 is common)."""
    soft, hard = resource.getrlimit(resource.RLIMIT_NOFILE)
    need = count + 512
    if soft != resource.RLIM_INFINITY and soft < need:
        target = need if hard == resource.RLIM_INFINITY else min(need, hard)
        resource.setrlimit(resource.RLIMIT_NOFILE, (target, hard))


def _closed(reader: asyncio.StreamReader, writer: asyncio.StreamWriter) -> bool:
    return (reader.at_eof() or reader.exception() is not None
            or writer.transport.is_closing())


async def _one(host: str, port: int, stop: float, out: dict) -> None:
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
            writer.write(HEAD)
            await writer.drain()
            while time.monotonic() < stop:
                await asyncio.sleep(TICK_S)
                if _closed(reader, writer):
                    break
                writer.write(BYTE)
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
    """Hold `count` slow bodies until `stop` (opened at about 1000 a second)."""
    host, port = url.split("//", 1)[1].split(":")
    out["held"] = count
    async with asyncio.TaskGroup() as tg:
        for k in range(count):
            if time.monotonic() >= stop:
                break
            tg.create_task(_one(host, int(port), stop, out))
            if k % 100 == 99:
                await asyncio.sleep(0.1)
