"""The CPU a test server costs from start to idle, with and without warm workers (issue 19,
CI time).

A server the tests start (app.testing.live_server) warms its two worker processes by
default: each runs a short simulation of every case, loading the kernels from numba's
cache. A test that runs no job does not need that. Here one server is started, waited
for until idle (app.testing.wait_idle), asked /api/health and stopped, four times,
warm_workers on and off alternately; the CPU is that of the server and its workers,
read from this process's children's rusage after the server exited (it reaps its workers
first).

    PYTHONPATH=$PWD .venv/bin/python bench/server_start_cost.py
        -> bench/results/server_start_cost.txt
"""

import os
import resource
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path[:0] = [str(ROOT)]

import httpx  # noqa: E402

from app.testing import live_server, wait_idle  # noqa: E402

OUT = ROOT / "bench" / "results" / "server_start_cost.txt"


def children_cpu() -> float:
    r = resource.getrusage(resource.RUSAGE_CHILDREN)
    return r.ru_utime + r.ru_stime


def main() -> None:
    load = os.getloadavg()
    lines = ["bench/server_start_cost.py: a test server (app.testing.live_server, two "
             "workers) started, waited for until idle, asked /api/health and stopped; CPU of "
             "the server and its workers; "
             f"{time.strftime('%Y-%m-%d %H:%M UTC', time.gmtime())}, load average "
             f"{load[0]:.2f} {load[1]:.2f} {load[2]:.2f}"]
    for warm in (True, False, True, False):
        c0, t0 = children_cpu(), time.monotonic()
        with live_server(warm_workers=warm) as url:
            wait_idle(url, timeout=300)
            ready = time.monotonic() - t0
            assert httpx.get(url + "/api/health", timeout=10).status_code == 200
        lines.append(f"  warm_workers={warm!s:5s}: {children_cpu() - c0:5.1f} s of CPU, "
                     f"idle {ready:4.1f} s after the start")
        print(lines[-1], flush=True)
    OUT.write_text("\n".join(lines) + "\n")


if __name__ == "__main__":
    main()
