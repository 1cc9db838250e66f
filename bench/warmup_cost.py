"""Where the cold warm-up goes (the target: at most 2 minutes on 2 cores).

Three measurements, each on empty caches (ROLLING_KERNEL_CACHE and NUMBA_CACHE_DIR in a
fresh temporary directory, so the shared warm cache is never read or written):

  tasks   every task of `python -m solvers.warmup` (the general kernels, one per pending
          structure) alone in a fresh process, one after the other: the CPU time of the
          task in its own process (time.process_time around solvers.warmup._task, the
          imports apart), so a loaded machine does not inflate it;
  passes  the first call of one small kernel with numba's event API: the CPU time of
          each compiler pass (numba:run_pass, summed by pass), and the time spent under
          the LLVM lock (numba:llvm_lock: LLVM's optimisation and code generation);
  warmup  `python -m solvers.warmup` itself (ROLLING_WARMUP_JOBS parallel processes, default
          2): wall time, the CPU time of the process and its children, and the load average
          before and after (the machine is shared: the wall time holds the others' load).

    PYTHONPATH=$PWD python bench/warmup_cost.py [tasks] [passes] [warmup] [--case ID]
        -> bench/results/warmup.txt (the sections run, in that order; default all three)
"""

import json
import os
import resource
import subprocess
import sys
import tempfile
import time
from pathlib import Path

OUT = Path(__file__).with_name("results") / "warmup.txt"

TASK = r"""
import json, sys, time
c0 = time.process_time()
from solvers import warmup
what = json.loads(sys.argv[1])
what = what if isinstance(what, str) else tuple(what)
imp = time.process_time() - c0
c1, w1 = time.process_time(), time.perf_counter()
warmup._task(what)
print(json.dumps({"cpu": time.process_time() - c1, "wall": time.perf_counter() - w1,
                  "import_cpu": imp}))
"""

PASSES = r"""
import json, sys, time
from collections import defaultdict
from numba.core import event as ev
from solvers.integrate import integrator as I
from solvers.models.cases import build, registry
case, method = sys.argv[1], sys.argv[2]
c = registry()[case]
m = build(case, c.example)
I.small_module(m.model, m.p, method)     # the generated text, outside the timing
passes, llvm = defaultdict(float), [0.0]

class Timer(ev.Listener):
    def __init__(self):
        self.t0 = {}
    def on_start(self, event):
        self.t0[id(event.data) if event.data is not None else 0] = time.process_time()
    def on_end(self, event):
        dt = time.process_time() - self.t0.pop(id(event.data) if event.data is not None else 0)
        if event.kind == "numba:run_pass":
            passes[event.data["name"]] += dt
        elif event.kind == "numba:llvm_lock":
            llvm[0] += dt

tp, tl = Timer(), Timer()
ev.register("numba:run_pass", tp)
ev.register("numba:llvm_lock", tl)
c1, w1 = time.process_time(), time.perf_counter()
r = I.integrate(m.model, m.p, c.state, [0.0, 0.01], method=method)
cpu, wall = time.process_time() - c1, time.perf_counter() - w1
assert r.kernel == "small", r.kernel
print(json.dumps({"cpu": cpu, "wall": wall, "llvm": llvm[0],
                  "passes": sorted(passes.items(), key=lambda kv: -kv[1])}))
"""


def _fresh_env(d: str, **extra) -> dict:
    return {**os.environ, "ROLLING_KERNEL_CACHE": f"{d}/kernels",
            "NUMBA_CACHE_DIR": f"{d}/numba", **extra}


def _load() -> str:
    a = os.getloadavg()
    return f"{a[0]:.2f} {a[1]:.2f} {a[2]:.2f}"


def tasks() -> list[str]:
    from solvers import warmup

    with tempfile.TemporaryDirectory() as d:      # what an empty cache has pending
        env = _fresh_env(d)
        out = subprocess.run(
            [sys.executable, "-c", "import json; from solvers import warmup; print(json.dumps("
             "[[str(k), v[0]] for k, v in warmup.pending().items()]))"],
            env=env, capture_output=True, text=True, check=True)
    todo = [(warmup.GENERAL, warmup.GENERAL)] + \
        [(key, list(target)) for key, target in json.loads(out.stdout.splitlines()[-1])]
    lines = [f"tasks: each warm-up task alone in a fresh process on empty caches "
             f"(load average at the start {_load()}, {os.cpu_count()} cores)",
             f"{'task':58s} {'CPU s':>7s} {'wall s':>7s}"]
    total = 0.0
    for key, what in todo:
        with tempfile.TemporaryDirectory() as d:
            out = subprocess.run([sys.executable, "-c", TASK, json.dumps(what)],
                                 env=_fresh_env(d), capture_output=True, text=True)
        if out.returncode:
            raise SystemExit(out.stderr)
        r = json.loads(out.stdout.splitlines()[-1])
        name = key if what == warmup.GENERAL else f"{what[0]} {key}"
        line = f"{name[:58]:58s} {r['cpu']:7.1f} {r['wall']:7.1f}"
        print(line, flush=True)
        lines.append(line)
        total += r["cpu"]
    lines += [f"sum of the tasks' CPU: {total:.1f} s ({len(todo)} tasks); a lower bound of "
              f"the wall time on 2 cores: {total / 2:.0f} s",
              f"load average at the end {_load()}"]
    return lines


def passes(case: str, method: str = "dop853") -> list[str]:
    with tempfile.TemporaryDirectory() as d:
        out = subprocess.run([sys.executable, "-c", PASSES, case, method],
                             env=_fresh_env(d), capture_output=True, text=True)
    if out.returncode:
        raise SystemExit(out.stderr)
    r = json.loads(out.stdout.splitlines()[-1])
    lines = [f"passes: the first call of the small {method} kernel of {case} (compile + a "
             f"0.01 s run), CPU time per numba compiler pass (load average {_load()})",
             f"first call: {r['cpu']:.1f} s CPU, {r['wall']:.1f} s wall; under the LLVM lock "
             f"(LLVM optimisation and code generation): {r['llvm']:.1f} s"]
    for name, dt in r["passes"][:8]:
        lines.append(f"  {name:40s} {dt:6.2f} s")
    lines.append("  (NativeLowering holds the LLVM work of its function; the nested "
                 "function's passes are counted again inside its caller's)")
    return lines


def warmup() -> list[str]:
    with tempfile.TemporaryDirectory() as d:
        before = resource.getrusage(resource.RUSAGE_CHILDREN)
        load0 = _load()
        w0 = time.perf_counter()
        out = subprocess.run([sys.executable, "-m", "solvers.warmup"], env=_fresh_env(d),
                             capture_output=True, text=True)
        wall = time.perf_counter() - w0
        after = resource.getrusage(resource.RUSAGE_CHILDREN)
    if out.returncode:
        raise SystemExit(out.stderr)
    cpu = (after.ru_utime + after.ru_stime) - (before.ru_utime + before.ru_stime)
    jobs = os.environ.get("ROLLING_WARMUP_JOBS", "default")
    return [f"warmup: python -m solvers.warmup on empty caches, ROLLING_WARMUP_JOBS={jobs}, "
            f"{os.cpu_count()} cores",
            f"wall {wall:.1f} s, CPU of all its processes {cpu:.1f} s; load average before "
            f"{load0}, after {_load()}; it printed: {out.stdout.strip().splitlines()[-1]}"]


def main():
    args = sys.argv[1:]
    case = "plane/chaplygin-ball"
    if "--case" in args:
        case = args.pop(args.index("--case") + 1)
        args.remove("--case")
    run = [a for a in args if a in ("tasks", "passes", "warmup")] or \
        ["tasks", "passes", "warmup"]
    lines = [f"bench/warmup_cost.py {' '.join(sys.argv[1:])}".rstrip(), ""]
    for what in run:
        part = {"tasks": tasks, "passes": lambda: passes(case), "warmup": warmup}[what]()
        print("\n".join(part), flush=True)
        lines += [*part, ""]
    OUT.parent.mkdir(exist_ok=True)
    OUT.write_text("\n".join(lines))


if __name__ == "__main__":
    if {"-h", "--help"} & set(sys.argv[1:]):     # what it does, without running it
        print(__doc__)
        sys.exit(0)
    main()
