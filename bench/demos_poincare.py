"""The /poincare page's default map for every case it offers, on a warm server: the time
of POST /api/poincare with the form's defaults (app/static/data/poincare_defaults.json:
the numbers the page fills in) and how many of its trajectories give no return.

    PYTHONPATH=$PWD python bench/demos_poincare.py [--repeat 3]

"Warm": each case's map runs once before it is timed (its kernels compiled, a worker
ready); then the median of --repeat runs is printed. The server has the page's limits
(deadline 20 s, 2 workers).
"""

from __future__ import annotations

import argparse
import json
import statistics
import time
from pathlib import Path

import httpx

from app.testing import live_server, wait_idle

ROOT = Path(__file__).resolve().parents[1]
DEFAULTS = ROOT / "app" / "static" / "data" / "poincare_defaults.json"


def form_defaults() -> dict:
    """The page's defaults: the shared ones and each case's own (energy, section...)."""
    return json.loads(DEFAULTS.read_text())


def request_for(case: str, d: dict) -> dict:
    f = {**d["form"], **d["cases"].get(case, {})}
    return {"case": case, "energy": float(f["energy"]), "section": f"g={float(f['g0'])}",
            "direction": int(f["direction"]), "trajectories": int(f["trajectories"]),
            "points": int(f["points"]), "rtol": float(f["rtol"]), "seed": int(f["seed"]),
            "params": {}, "example": True}


def run(client: httpx.Client, url: str, body: dict) -> tuple[float, dict]:
    t0 = time.perf_counter()
    r = client.post(url + "/api/poincare", json=body, timeout=120)
    took = time.perf_counter() - t0
    r.raise_for_status()
    return took, r.json()


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--case", action="append", help="only these cases")
    a = ap.parse_args()
    d = form_defaults()
    # kernels_warm=False: a first use compiles outside the deadline (kernel_prepare), as on
    # a real server; the timed runs come after the warm-up run
    with (live_server(max_steps=10**9, deadline_s=20.0, kernels_warm=False) as url,
          httpx.Client() as client):
        wait_idle(url, timeout=600)
        cases = [c["id"] for c in client.get(url + "/api/cases").json() if c["body"] != "flat"]
        print(f"{'case':34s} {'E0':>6s} {'g0':>5s} {'dir':>3s} {'N x P':>9s} {'median s':>9s} "
              f"{'runs s':>18s} {'no return':>9s} statuses")
        for case in a.case or cases:
            body = request_for(case, d)
            try:
                run(client, url, body)                         # warm: kernels, a worker
                runs = [run(client, url, body) for _ in range(a.repeat)]
            except httpx.HTTPStatusError as e:
                print(f"{case:34s} {body['energy']:6g} {body['section'][2:]:>5s} "
                      f"failed: {e.response.status_code} {e.response.text[:160]}", flush=True)
                continue
            res = runs[-1][1]
            empty = sum(1 for t in res["trajectories"] if not t["points"])
            statuses = sorted({t["status"] for t in res["trajectories"]})
            times = [r[0] for r in runs]
            print(f"{case:34s} {body['energy']:6g} {body['section'][2:]:>5s} "
                  f"{body['direction']:>3d} {body['trajectories']:>3d} x {body['points']:<4d} "
                  f"{statistics.median(times):9.2f} "
                  f"{' '.join(f'{t:.2f}' for t in times):>18s} "
                  f"{empty:>5d} of {len(res['trajectories'])} {','.join(statuses)}", flush=True)


if __name__ == "__main__":
    main()
