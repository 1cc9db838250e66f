"""Load test of the explorer on loopback: N concurrent users POST /api/simulate for a fixed
time while a prober measures GET /api/health. Bounded in users and time; it stops itself.

    python bench/load.py                         # 20 users, 60 s, its own server
    python bench/load.py --users 4 --duration 5 --json
    python bench/load.py --url http://127.0.0.1:8000   # an explorer already running

Each user sends the demo run of a case of Tables 1-2 (t_end 100, 201 samples), cycling
through the cases, and honours Retry-After on 503 (the designed answer of a full queue).
Reported: latency p50/p99 of the runs, p50/p99/max of the health probe, answers by status,
and the unplanned 5xx (every 5xx except 503), which must be zero.
"""

from __future__ import annotations

import argparse
import asyncio
import json
import multiprocessing
import os
import platform
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


async def load(url: str, users: int, duration: float) -> dict:
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
        async with asyncio.TaskGroup() as tg:
            for k in range(users):
                tg.create_task(user(client, cases, k, stop, sim_lat, sim_status, errors))
        wall = time.monotonic() - t0
        health_lat, health_status = await asyncio.to_thread(queue.get, True, duration + 60)
        probe.join(10)
        pool = (await client.get("/api/health")).json()["pool"]
    unplanned = sum(n for s, n in {**sim_status, **health_status}.items()
                    if s >= 500 and s != 503) + sim_status.get(0, 0) + health_status.get(0, 0)
    return {
        "users": users, "duration_s": duration, "wall_s": wall, "loadavg_before": load0,
        "simulate": {"ok": len(sim_lat), "throughput_per_s": len(sim_lat) / wall,
                     "p50_ms": 1e3 * pct(sim_lat, 50), "p99_ms": 1e3 * pct(sim_lat, 99),
                     "mean_ms": 1e3 * statistics.fmean(sim_lat) if sim_lat else None,
                     "status": {str(k): v for k, v in sorted(sim_status.items())}},
        "health": {"probes": len(health_lat), "p50_ms": 1e3 * pct(health_lat, 50),
                   "p99_ms": 1e3 * pct(health_lat, 99),
                   "max_ms": 1e3 * max(health_lat) if health_lat else None,
                   "status": {str(k): v for k, v in sorted(health_status.items())}},
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
        f"load: {r['users']} concurrent users for {r['duration_s']:g} s, each POST /api/simulate "
        "(demo run of a case of Tables 1-2, t_end 100, 201 samples), Retry-After honoured",
        "",
        f"simulate: {s['ok']} runs answered 200 ({s['throughput_per_s']:.1f}/s); "
        f"latency p50 {s['p50_ms']:.0f} ms, p99 {s['p99_ms']:.0f} ms",
        f"          answers by status: {s['status']}",
        f"health:   {h['probes']} probes every 0.1 s; p50 {h['p50_ms']:.1f} ms, "
        f"p99 {h['p99_ms']:.1f} ms, max {h['max_ms']:.1f} ms (goal p99 < 100 ms)",
        f"unplanned 5xx (5xx other than 503, or no answer): {r['unplanned_5xx']}",
        f"server pool afterwards: {r['server_pool']}",
    ]
    if r["errors"]:
        lines.append(f"errors: {r['errors']}")
    return "\n".join(lines) + "\n"


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--users", type=int, default=20)
    ap.add_argument("--duration", type=float, default=60.0)
    ap.add_argument("--url", help="an explorer already running (default: start one)")
    ap.add_argument("--json", action="store_true", help="print the figures as JSON")
    ap.add_argument("--out", help="also write the report to this file")
    args = ap.parse_args(argv)
    if not (1 <= args.users <= 200 and 0 < args.duration <= 600):
        ap.error("users in [1, 200], duration in (0, 600] s")

    def run(url: str, settings: dict) -> dict:
        r = asyncio.run(load(url, args.users, args.duration))
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
        settings = {"workers": s.workers, "queue_size": s.queue_size,
                    "deadline_s": s.deadline_s, "max_steps": s.max_steps}
        # the defaults of `rolling serve`, without the background verification
        with live_server(verify_on_start=False, workers=s.workers, queue_size=s.queue_size,
                         deadline_s=s.deadline_s, max_steps=s.max_steps) as url:
            wait_idle(url, timeout=600)
            r = run(url, settings)
    return 1 if r["unplanned_5xx"] else 0


if __name__ == "__main__":
    sys.exit(main())
