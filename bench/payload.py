"""Serialization against integration for a 2000-sample simulate (the target: the
answer's serialization should cost no more than 1.5x the integration).

Side by side in one process, interleaved, best of N:
  integrate     simulate() of the Chaplygin ball, T = 100, 2000 samples (the run a worker
                does before serializing);
  json-before   the former answer: ndarray.tolist() then json.dumps (strict, non-finite
                as null), as app/services/jobs.py did before orjson;
  json          app/services/payloads.json_bytes (orjson from the arrays);
  arrow         app/services/payloads.arrow_bytes (Arrow IPC stream).
Then the whole request through the API (TestClient, worker processes), JSON against
Arrow, as a check that the sizes and the end-to-end times follow.

    PYTHONPATH=$PWD python bench/payload.py [--quick]

writes bench/results/payload.txt.
"""

import argparse
import json
import os
import sys
import time
from pathlib import Path

OUT = Path(__file__).resolve().parent / "results" / "payload.txt"
BALL = {"case": "plane/chaplygin-ball", "params": {"I1": 1, "I2": 2, "I3": 3, "m": 1, "R": 1},
        "state": [0.5, -0.3, 0.8, 0.3, 0.4, 0.8660254037844386], "t_end": 100.0,
        "samples": 2000}


def json_before(res, max_steps):
    from app.services.payloads import finite as _finite

    out = res.to_json()
    out["stats"]["max_steps"] = max_steps
    try:
        text = json.dumps(out, allow_nan=False, separators=(",", ":"))
    except ValueError:
        text = json.dumps(_finite(out), allow_nan=False, separators=(",", ":"))
    return text.encode()


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--quick", action="store_true")
    a = ap.parse_args(argv)
    rounds = 15 if a.quick else 60
    from app.services.payloads import arrow_bytes, json_bytes
    from solvers.simulate import simulate

    def run():
        return simulate(BALL["case"], BALL["params"], BALL["state"], BALL["t_end"],
                        samples=BALL["samples"])

    res = run()
    fns = {"integrate": run,
           "json-before": lambda: json_before(res, 10**7),
           "json": lambda: json_bytes(res, 10**7),
           "arrow": lambda: arrow_bytes(res, 10**7)}
    sizes = {k: len(f()) for k, f in fns.items() if k != "integrate"}
    load0 = os.getloadavg()
    best = dict.fromkeys(fns, float("inf"))
    for _ in range(rounds):
        for k, f in fns.items():
            t0 = time.perf_counter()
            f()
            best[k] = min(best[k], time.perf_counter() - t0)
    integ = best["integrate"]
    lines = ["Serialization vs integration, 2000-sample simulate (Chaplygin ball, T = 100, "
             "dop853, rtol 1e-10),",
             f"in one process, interleaved, best of {rounds}; target: serialization <= 1.5x "
             "integration.", "",
             f"{'':12s} {'ms':>8s} {'x integration':>14s} {'bytes':>9s}",
             f"{'integrate':12s} {integ * 1e3:8.2f} {1.0:14.2f} {'':>9s}"
             f"  (field: {res.stats['field']}, {res.stats['steps']} steps)"]
    for k in ("json-before", "json", "arrow"):
        lines.append(f"{k:12s} {best[k] * 1e3:8.2f} {best[k] / integ:14.2f} {sizes[k]:9d}")
    lines.append("")
    for k in ("json", "arrow"):
        r = best[k] / integ
        lines.append(f"{k}: {r:.2f}x integration ({'meets' if r <= 1.5 else 'misses'} the "
                     f"1.5x target); {best['json-before'] / best[k]:.1f}x faster than "
                     "json-before")
    lines += ["", *_through_api(rounds)]
    load1 = os.getloadavg()
    lines += ["", f"load average before/after: {load0[0]:.2f} / {load1[0]:.2f} "
              "(2 cores shared)", f"python {sys.version.split()[0]}",
              f"command: PYTHONPATH=$PWD python bench/payload.py{' --quick' * a.quick}"]
    text = "\n".join(lines) + "\n"
    print(text)
    (OUT.with_name("payload_quick.txt") if a.quick else OUT).write_text(text)


def _through_api(rounds):
    """POST /api/simulate end to end (TestClient, one worker process), JSON vs Arrow."""
    import warnings

    from fastapi.testclient import TestClient

    from app.main import create_app
    from app.testing import settings_for_tests

    warnings.simplefilter("ignore", DeprecationWarning)
    arrow = "application/vnd.apache.arrow.stream"
    best = {"json": float("inf"), "arrow": float("inf")}
    with TestClient(create_app(settings_for_tests(workers=1))) as c:
        for accept in ("application/json", arrow):    # the worker is warm for both
            assert c.post("/api/simulate", json=BALL, headers={"Accept": accept}).is_success
        for _ in range(rounds):
            for k, accept in (("json", "application/json"), ("arrow", arrow)):
                t0 = time.perf_counter()
                r = c.post("/api/simulate", json=BALL, headers={"Accept": accept})
                best[k] = min(best[k], time.perf_counter() - t0)
                assert r.status_code == 200 and r.headers["content-type"] == accept
    return [f"through the API (TestClient -> worker process -> bytes), best of {rounds}:",
            f"  JSON  {best['json'] * 1e3:7.2f} ms",
            f"  Arrow {best['arrow'] * 1e3:7.2f} ms"]


if __name__ == "__main__":
    main()
