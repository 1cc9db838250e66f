"""A few seconds of bench/load.py (the full bench is 20 users for 60 s, kept out of the
test run): a handful of users (simulate, pages, 50 MB bodies), zero unplanned 5xx, every
big body refused with 413, /api/health answering meanwhile."""

import json
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]


def test_short_load_has_no_unplanned_5xx_and_a_responsive_health():
    out = subprocess.run([sys.executable, str(ROOT / "bench" / "load.py"), "--users", "4",
                          "--duration", "4", "--json"],
                         capture_output=True, text=True, timeout=600, cwd=ROOT)
    assert out.returncode == 0, out.stdout[-2000:] + out.stderr[-2000:]
    r = json.loads(out.stdout)
    assert r["unplanned_5xx"] == 0, r["errors"]
    assert r["simulate"]["ok"] > 20
    assert set(r["simulate"]["status"]) <= {"200", "503"}
    assert r["health"]["probes"] >= 20
    assert r["pages"]["ok"] > 0 and set(r["pages"]["status"]) == {"200"}
    big = r["big_body"]
    assert big["sent"] > 0 and all(k.endswith(":413") for k in big["status"]), big
    # generous for a loaded CI machine (the bench's goal is p99 < 100 ms)
    assert r["health"]["p99_ms"] < 500, r["health"]


def test_slow_bodies_at_the_cap_drop_no_ordinary_request():
    """bench/load.py's slow-body mode scaled down: a cap of 100 connections and 104 bodies
    held open, one byte every 0.5 s, while 4 users and the health prober run (the slow
    bodies and the ordinary connections exceed the cap by about a tenth, as 1,100 slow
    bodies do a cap of 1000): the server evicts slow bodies, and no ordinary request goes
    unanswered."""
    out = subprocess.run([sys.executable, str(ROOT / "bench" / "load.py"), "--users", "4",
                          "--duration", "5", "--slow-bodies", "104", "--max-connections",
                          "100", "--json"], capture_output=True, text=True, timeout=600,
                         cwd=ROOT)
    assert out.returncode == 0, out.stdout[-2000:] + out.stderr[-2000:]
    r = json.loads(out.stdout)
    assert r["ordinary"]["requests"] > 20 and r["ordinary"]["dropped"] == 0, r["ordinary"]
    assert r["unplanned_5xx"] == 0, (r["errors"], r["big_body"])
    assert r["slow_bodies"]["opened"] > 104 and r["slow_bodies"]["closed_by_server"] > 0
    guards = r["server_connections"]
    assert guards["peak"] == 100 and guards["evicted_by"]["slowest"] > 0, guards
    assert guards["evicted_by"]["idle"] == 0 and guards["refused"] == 0, guards
