"""What a small kernel with sections could gain a Poincare map (issue 19, item 1: not built).

A map's trajectory runs the general kernel (rk.py on the general field) with the section
g = g0, its step control near the section, dense samples and the check. A small kernel
(solvers/kernels/small.py: the generated field inlined, state and stages in locals) exists
for plain runs only. For one trajectory of the default map (E = 1, 200 crossings, rtol
1e-10, atol 1e-12) this times, over the same span [0, T] (T: the trajectory's last
crossing) from the same start:
  map trace       the whole trajectory as maps run it (solvers.maps.poincare.trace: the
                  section, 32 dense samples per crossing, the crossings' check);
  general+section the general kernel with the section only (no samples);
  generated+section rk.py's kernel on the case's generated field with the section (the
                  generated integrator: ~32 s of compile per structure on first use);
  general plain   the general kernel, no section (integrate(kernel="rk"));
  small plain     the small kernel, no section (integrate's default for a plain run).
So general+section -> generated+section is what the field gains, generated+section -> small
plain what the kernel's shape gains (and the section's cost, which a small kernel with
sections would keep). A small kernel with sections would take at least the small plain
run's steps and calls, so small plain / general+section bounds what it could gain on the
integration, and small plain / map trace what it could gain on the whole trajectory.
Best of 3 timings each, after a warm call; 5 sampled starts per case (starts_for, seed 0).

    PYTHONPATH=$PWD .venv/bin/python bench/map_kernel_gain.py
        -> bench/results/map_kernel_gain.txt
"""

import os
import statistics
import sys
import time
from functools import partial
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path[:0] = [str(ROOT)]

from bench.limit import best_of  # noqa: E402
from solvers.integrate.integrator import integrate  # noqa: E402
from solvers.maps.poincare import MapSpec, map_model, starts_for, trace  # noqa: E402
from solvers.models.cases import get_case  # noqa: E402

OUT = ROOT / "bench" / "results" / "map_kernel_gain.txt"
CASES = ["plane/chaplygin-ball", "sphere/routh-ball", "sphere/chaplygin-ball"]
STARTS = 5


def best(f, *args, **kw):
    """(best wall time of 3, the last result) after a warm call: bench/limit.py's best_of."""
    run = partial(f, *args, **kw)
    run()
    return best_of(run, 3)


def main() -> None:
    spec = MapSpec(energy=1.0, points=200)
    lines = [f"map kernel gain, {time.strftime('%Y-%m-%d %H:%M UTC', time.gmtime())}, load "
             f"average {' '.join(f'{x:.2f}' for x in os.getloadavg())}",
             "per trajectory of the default map (E = 1, 200 crossings, rtol 1e-10): ms "
             "(steps), median over the starts; ratios per start, median (max)",
             f"{'case':24s} {'map trace':>12s} {'general+section':>18s} {'generated+section':>19s} "
             f"{'general plain':>18s} "
             f"{'small plain':>16s}  {'small/gen+sec':>14s} {'small/map':>12s}"]
    for case in CASES:
        m = map_model(case, get_case(case).example)
        rows = []
        for y0 in starts_for(m, spec, trajectories=STARTS, seed=0):
            t_map, tr = best(trace, m, y0, spec)
            T = float(tr.t[-1])
            opts = {"rtol": spec.rtol, "atol": spec.atol}
            runs = {}
            sec = {"section": spec.section(), "max_crossings": 10**6}
            for label, kw in (("sec", sec), ("gsec", {**sec, "generated": True}),
                              ("gen", {"kernel": "rk"}), ("small", {})):
                dt, r = best(integrate, m.model, m.p, y0, [0.0, T], **opts, **kw)
                runs[label] = (dt, r.steps, r.kernel, r.vector_field)
            assert runs["small"][2:] == ("small", "generated"), runs["small"]
            assert runs["gen"][2:] == runs["sec"][2:] == ("rk", "general"), runs
            assert runs["gsec"][2:] == ("rk", "generated"), runs["gsec"]
            rows.append((t_map, runs))
        med = {k: statistics.median(r[1][k][0] for r in rows) * 1e3 for k in runs}
        steps = {k: int(statistics.median(r[1][k][1] for r in rows)) for k in runs}
        t_map = statistics.median(r[0] for r in rows) * 1e3
        r_sec = [r[1]["small"][0] / r[1]["sec"][0] for r in rows]
        r_map = [r[1]["small"][0] / r[0] for r in rows]
        lines.append(
            f"{case:24s} {t_map:12.1f} {med['sec']:9.1f} ({steps['sec']:5d}) "
            f"{med['gsec']:10.1f} ({steps['gsec']:5d}) "
            f"{med['gen']:9.1f} ({steps['gen']:5d}) {med['small']:7.1f} ({steps['small']:5d})  "
            f"{statistics.median(r_sec):6.2f} ({max(r_sec):.2f}) "
            f"{statistics.median(r_map):5.2f} ({max(r_map):.2f})")
    text = "\n".join(lines) + "\n"
    print(text, end="")
    OUT.write_text(text)


if __name__ == "__main__":
    main()
