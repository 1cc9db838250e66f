"""Where a command's CPU goes, by kind of process (issue 19, CI time).

Runs a command and samples /proc every second: each process started after the command
(or before it, from its value at the start) is counted in a kind read from its command
line: chromium's renderer, GPU process and the rest of chromium; Playwright's node driver;
pytest-xdist's workers (`python -u -c`, execnet); pytest's own process; the explorer's
servers (`app.core.server`) and their worker processes (anyio.to_process); other
multiprocessing children (the kernel warm-up's tasks, verify_parallel);
the `rolling` command line; the set-up (uv, pip); other. A process that lives less than a
second between two samples is missed, and one that exits loses its last second: the
figures are lower bounds, good for shares.

    python bench/cpu_by_process.py [--out FILE] -- ./dev test
        -> CPU seconds per kind, and the machine's busy CPU over the run (from /proc/stat)
"""

import argparse
import os
import subprocess
import sys
import time
from collections import Counter
from pathlib import Path

KINDS = (("--type=renderer", "chromium renderer"), ("--type=gpu-process", "chromium GPU"),
         ("chromium", "chromium other"), ("playwright", "playwright driver"),
         ("app.core.server", "explorer servers"),
         ("anyio.to_process", "explorer servers' worker processes"),
         ("multiprocessing", "multiprocessing (warm-up, verify_parallel)"),
         ("execnet", "pytest-xdist workers"), ("-u -c import sys;exec", "pytest-xdist workers"),
         ("pytest", "pytest"), ("app.cli", "rolling command line"),
         ("solvers.warmup", "kernel warm-up"), ("/uv ", "set-up"), ("pip", "set-up"))


def kind(pid: str) -> str | None:
    try:
        cmd = Path(f"/proc/{pid}/cmdline").read_bytes().replace(b"\0", b" ").decode(
            errors="replace")
    except OSError:
        return None
    if not cmd:
        return None                    # a kernel thread
    return next((k for key, k in KINDS if key in cmd), "other: " + cmd[:60])


def snapshot(comm: str | None = None) -> dict:
    """(pid, start time) -> CPU seconds (user + system) of every process alive (comm: only
    those whose /proc/<pid>/comm holds it, e.g. "chrom")."""
    tick = os.sysconf("SC_CLK_TCK")
    out = {}
    for pid in filter(str.isdigit, os.listdir("/proc")):
        try:
            if comm is not None and comm not in Path(f"/proc/{pid}/comm").read_text():
                continue
            f = Path(f"/proc/{pid}/stat").read_text().rsplit(")", 1)[1].split()
        except (OSError, IndexError):
            continue
        out[pid, f[19]] = (int(f[11]) + int(f[12])) / tick
    return out


def busy() -> float:
    v = list(map(int, Path("/proc/stat").read_text().split("\n", 1)[0].split()[1:9]))
    return (sum(v) - v[3] - v[4]) / os.sysconf("SC_CLK_TCK")


def main() -> int:
    ap = argparse.ArgumentParser()
    ap.add_argument("--out", type=Path)
    ap.add_argument("command", nargs=argparse.REMAINDER)
    a = ap.parse_args()
    cmd = a.command[1:] if a.command[:1] == ["--"] else a.command
    before = snapshot()
    last, kinds, per = before, {}, Counter()
    b0, t0 = busy(), time.monotonic()
    proc = subprocess.Popen(cmd)
    while proc.poll() is None:
        time.sleep(1.0)
        now = snapshot()
        for key, cpu in now.items():
            if key not in kinds:
                kinds[key] = kind(key[0])
            if kinds[key] is not None:
                per[kinds[key]] += cpu - last.get(key, 0.0)
        last = now
    wall, machine = time.monotonic() - t0, busy() - b0
    lines = [f"{' '.join(cmd)}: exit {proc.returncode}, {wall:.0f} s wall, the machine "
             f"busy {machine:.0f} CPU s ({machine / wall / (os.cpu_count() or 1):.0%} "
             f"of {os.cpu_count()} cores)"]
    kinds_total = Counter()
    for k, v in per.items():
        kinds_total["other" if k.startswith("other: ") else k] += v
    lines += [f"  {v:8.1f} s  {k}" for k, v in kinds_total.most_common()]
    lines += ["  the largest of other:"]
    lines += [f"  {v:8.1f} s    {k[7:]}" for k, v in per.most_common()
              if k.startswith("other: ")][:8]
    text = "\n".join(lines) + "\n"
    print(text, end="", file=sys.stderr)
    if a.out:
        a.out.write_text(text)
    return proc.returncode


if __name__ == "__main__":
    sys.exit(main())
