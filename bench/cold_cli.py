"""Cold `rolling simulate` with warm numba caches: a new process each time, wall clock of
the whole command (import, cache load, run, JSON). Prints median and max of N runs.

    python bench/cold_cli.py [N]      (output: bench/results/cold_cli.txt)
"""

import statistics
import subprocess
import sys
import time
from pathlib import Path

CMD = [str(Path(sys.executable).parent / "rolling"), "simulate", "plane/chaplygin-ball",
       "--set", "I1=1", "--set", "I2=2", "--set", "I3=3", "--set", "m=1", "--set", "R=1",
       "--state", "0.5,-0.3,0.8,0.3,0.4,0.8660254037844386", "--t-end", "1000", "--json"]


def main(n=10):
    subprocess.run(CMD, check=True, capture_output=True)          # warm the caches
    times = []
    for _ in range(n):
        t0 = time.perf_counter()
        subprocess.run(CMD, check=True, capture_output=True)
        times.append(time.perf_counter() - t0)
    # the import part alone: python -c "import app.cli" (what every command pays)
    t0 = time.perf_counter()
    subprocess.run([sys.executable, "-c", "import app.cli"], check=True)
    imp = time.perf_counter() - t0
    lines = [
        "cold `rolling simulate plane/chaplygin-ball ... --t-end 1000 --json`, warm caches",
        f"runs: {n}   median {statistics.median(times):.3f} s   max {max(times):.3f} s   "
        f"min {min(times):.3f} s   (goal < 1.5 s)",
        f"python -c 'import app.cli': {imp:.3f} s",
    ]
    text = "\n".join(lines)
    print(text)
    out = Path(__file__).parent / "results" / "cold_cli.txt"
    out.write_text(text + "\n")


if __name__ == "__main__":
    if {"-h", "--help"} & set(sys.argv[1:]):     # what it does, without running it
        print(__doc__)
        sys.exit(0)
    main(int(sys.argv[1]) if len(sys.argv) > 1 else 10)
