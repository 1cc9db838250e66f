"""Ready in a minute: a fresh clone, an empty HOME and caches,
`./dev serve --port N`, and the time from the end of the set-up (pip) to the first 200 on /.

    python bench/cold_start.py [--port 8731] [--watch 900] [--out bench/results/cold_start.txt]

What it does:
  1. `git clone` of this checkout's HEAD (its committed state: commit first) into a
     temporary directory, so nothing compiled (no __pycache__, no .venv) comes along;
  2. runs `./dev serve --port N` there with HOME set to an empty directory (pip's cache,
     numba's, ~/.cache/rolling-hierarchy: all empty) and no ROLLING_KERNEL_CACHE,
     NUMBA_CACHE_DIR or XDG_CACHE_HOME; ROLLING_SEED (the paper's text, data, not a cache)
     is passed on;
  3. timestamps every line the server prints; the set-up ends at the dev script's line
     "set-up done" (pip in a fresh venv from the registry: not counted by the target);
  4. polls GET / every 0.1 s from then on: "first 200 at X s after pip" (target <= 90 s);
  5. keeps watching until the background warm-up's "done" line (or --watch seconds): when
     each part compiled, and when a first simulate of the home page's example answered;
  6. stops the server (its process group: the warm-up's compile processes too).
The load average (1 min) is printed at the first 200 and at the end: the machine is shared.
"""

from __future__ import annotations

import argparse
import os
import shutil
import signal
import subprocess
import sys
import tempfile
import threading
import time
from pathlib import Path

import httpx

ROOT = Path(__file__).resolve().parents[1]


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--port", type=int, default=8731)
    ap.add_argument("--watch", type=float, default=900.0,
                    help="seconds to watch the background warm-up after the first 200")
    ap.add_argument("--out", default=str(ROOT / "bench" / "results" / "cold_start.txt"))
    ap.add_argument("--keep", action="store_true", help="keep the temporary clone")
    a = ap.parse_args()

    tmp = Path(tempfile.mkdtemp(prefix="rolling-cold-"))
    repo, home = tmp / "repo", tmp / "home"
    home.mkdir()
    head = subprocess.run(["git", "rev-parse", "HEAD"], cwd=ROOT, capture_output=True,
                          text=True, check=True).stdout.strip()
    subprocess.run(["git", "clone", "-q", str(ROOT), str(repo)], check=True)
    subprocess.run(["git", "checkout", "-q", head], cwd=repo, check=True)
    env = {k: v for k, v in os.environ.items()
           if not k.startswith(("ROLLING_", "NUMBA_", "PIP_", "VIRTUAL_ENV", "PYTHON"))
           and k not in ("XDG_CACHE_HOME", "HOME")}
    env["HOME"] = str(home)
    if os.environ.get("ROLLING_SEED"):
        env["ROLLING_SEED"] = os.environ["ROLLING_SEED"]

    lines: list[tuple[float, str]] = []
    t0 = time.monotonic()
    log = open(tmp / "serve.log", "w")
    proc = subprocess.Popen(["./dev", "serve", "--port", str(a.port)], cwd=repo, env=env,
                            stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True,
                            start_new_session=True)

    def reader():
        for line in proc.stdout:
            t = time.monotonic() - t0
            lines.append((t, line.rstrip()))
            log.write(f"{t:8.2f} {line}")
            log.flush()

    threading.Thread(target=reader, daemon=True).start()

    def when(text: str) -> float | None:
        return next((t for t, line in list(lines) if text in line), None)

    url = f"http://127.0.0.1:{a.port}"
    t_setup = t_200 = load_200 = t_sim = None
    try:
        while t_setup is None:
            if proc.poll() is not None:
                raise SystemExit(f"./dev serve exited with {proc.returncode}; log: "
                                 f"{tmp / 'serve.log'}")
            t_setup = when("set-up done")
            time.sleep(0.05)
        while t_200 is None:
            if proc.poll() is not None:
                raise SystemExit(f"the server exited with {proc.returncode}")
            try:
                if httpx.get(url + "/", timeout=2.0).status_code == 200:
                    t_200, load_200 = time.monotonic() - t0, os.getloadavg()
            except httpx.TransportError:
                pass
            if t_200 is None:
                time.sleep(0.1)
        health = httpx.get(url + "/api/health", timeout=5.0).json()
        # a first run of the home page's example while the kernels warm: it compiles first
        # (outside its deadline) or loads what the warm-up compiled
        body = {"case": "plane/chaplygin-ball", "example": True, "t_end": 10.0,
                "samples": 101}
        t1 = time.monotonic()
        r = httpx.post(url + "/api/simulate", json=body, timeout=600.0)
        t_sim = (time.monotonic() - t1, r.status_code, time.monotonic() - t0)
        end = time.monotonic() + a.watch
        while time.monotonic() < end and when("compiling kernels: done") is None \
                and when("warm-up exited") is None:
            time.sleep(1.0)
        health_end = httpx.get(url + "/api/health", timeout=5.0).json()
        load_end = os.getloadavg()
    finally:
        try:
            os.killpg(proc.pid, signal.SIGTERM)
            proc.wait(20)
        except (ProcessLookupError, subprocess.TimeoutExpired):
            try:
                os.killpg(proc.pid, signal.SIGKILL)
            except ProcessLookupError:
                pass
        log.close()

    k = health_end["kernels"]
    parts = [line for t, line in lines if "compiling kernels" in line]
    out = [
        f"cold start of a fresh clone (commit {head[:12]}), {os.cpu_count()} CPUs, "
        f"{time.strftime('%Y-%m-%d %H:%M UTC', time.gmtime())}",
        f"  command: python bench/cold_start.py --port {a.port}",
        f"set-up (venv + pip install -e .[dev] from the registry): {t_setup:.1f} s "
        "(not counted)",
        f"first 200 on / at {t_200 - t_setup:.1f} s after pip (target <= 90 s); load "
        f"average at that moment {load_200[0]:.2f} {load_200[1]:.2f} {load_200[2]:.2f}",
        f"  /api/health then: kernels {health['kernels']['state']}, "
        f"{health['kernels']['parts_done']} of {health['kernels']['parts_total']} parts",
        f"first POST /api/simulate (plane/chaplygin-ball example, t_end 10): "
        f"{t_sim[1]} in {t_sim[0]:.1f} s, answered at {t_sim[2] - t_setup:.1f} s after pip",
        f"background warm-up: {k['state']}, {k['parts_done']} of {k['parts_total']} parts, "
        f"{k['elapsed_s']} s; load average at the end {load_end[0]:.2f} {load_end[1]:.2f} "
        f"{load_end[2]:.2f}",
        f"prepare jobs the requests waited for (outside their deadlines): {k['prepared']}",
        "the server's kernel lines (seconds since ./dev serve started):",
        *[f"  {t:7.1f}  {line}" for t, line in lines if "compiling kernels" in line
          or "set-up done" in line or "Uvicorn running" in line],
    ]
    del parts
    text = "\n".join(out) + "\n"
    print(text)
    Path(a.out).write_text(text)
    if a.keep:
        print(f"kept {tmp}")
    else:
        shutil.rmtree(tmp, ignore_errors=True)


if __name__ == "__main__":
    sys.exit(main())
