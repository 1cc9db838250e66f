"""What the small kernel with sections gains a Poincare map (issue 19, item 1).

A map's trajectory runs, by its size (solvers/maps/poincare.py map_kernel), the general
kernel (rk.py on the general field) or the small kernel with sections (solvers/kernels/
small.py: the generated field inlined, state and stages in locals, rk.py's section code;
integrate(kernel="small")). For one trajectory of the default map (E = 1, 200 crossings,
rtol 1e-10, atol 1e-12), from the same start, this times:
  map general / map small   the whole trajectory as maps run it (solvers.maps.poincare.
                  trace: the section, 32 dense samples per crossing, the crossings' check)
                  on either kernel;
and over the same span [0, T] (T: the trajectory's last crossing), the section only (no
samples):
  general+section   rk.py's kernel on the general field;
  generated+section rk.py's kernel on the case's generated field (the generated
                    integrator, ~32 s of compile per structure, opt-in);
  small+section     the small kernel with sections (same steps as generated+section).
Best of 3 timings each, after a warm call; 5 sampled starts per case (starts_for, seed 0):
milliseconds (steps), median over the starts; the ratios per start, median (max).
The compile is not in these times: the small kernel with sections compiles once per case
structure (10-14 s of CPU on 2 cores, then numba's disk cache), which is why only maps of
at least SMALL_MAP_CROSSINGS crossings take it.

    PYTHONPATH=$PWD .venv/bin/python bench/map_kernel_gain.py
        -> bench/results/map_kernel_gain.txt
"""

import os
import statistics
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path[:0] = [str(ROOT)]

from bench.limit import warm_best  # noqa: E402
from solvers.integrate.integrator import integrate  # noqa: E402
from solvers.maps.poincare import MapSpec, map_model, starts_for, trace  # noqa: E402
from solvers.models.cases import get_case  # noqa: E402

OUT = ROOT / "bench" / "results" / "map_kernel_gain.txt"
CASES = ["plane/chaplygin-ball", "sphere/routh-ball", "sphere/chaplygin-ball"]
STARTS = 5


def main() -> None:
    from dataclasses import replace

    spec = MapSpec(energy=1.0, points=200)
    lines = [f"map kernel gain, {time.strftime('%Y-%m-%d %H:%M UTC', time.gmtime())}, load "
             f"average {' '.join(f'{x:.2f}' for x in os.getloadavg())}",
             "per trajectory of the default map (E = 1, 200 crossings, rtol 1e-10): ms "
             "(steps), median over the starts; ratios per start, median (max)",
             f"{'case':24s} {'map general':>12s} {'map small':>10s} {'small/gen':>12s}  "
             f"{'general+section':>17s} {'generated+section':>18s} {'small+section':>15s}"
             f" {'small/general':>14s}"]
    for case in CASES:
        m = map_model(case, get_case(case).example)
        rows = []
        for y0 in starts_for(m, spec, trajectories=STARTS, seed=0):
            t_gen, tr = warm_best(trace, m, y0, replace(spec, kernel="general"))
            t_small, tr_small = warm_best(trace, m, y0, replace(spec, kernel="small"))
            assert len(tr.t) == len(tr_small.t) == spec.points
            T = float(tr.t[-1])
            opts = {"rtol": spec.rtol, "atol": spec.atol, "section": spec.section(),
                    "max_crossings": 10**6}
            runs = {}
            for label, kw in (("sec", {}), ("gsec", {"generated": True}),
                              ("ssec", {"kernel": "small"})):
                dt, r = warm_best(integrate, m.model, m.p, y0, [0.0, T], **opts, **kw)
                runs[label] = (dt, r.steps, r.kernel, r.vector_field)
            assert runs["sec"][2:] == ("rk", "general"), runs
            assert runs["gsec"][2:] == ("rk", "generated"), runs["gsec"]
            assert runs["ssec"][2:] == ("small-sections", "generated"), runs["ssec"]
            assert runs["ssec"][1] == runs["gsec"][1], runs
            rows.append((t_gen, t_small, runs))
        med = {k: statistics.median(r[2][k][0] for r in rows) * 1e3 for k in runs}
        steps = {k: int(statistics.median(r[2][k][1] for r in rows)) for k in runs}
        m_gen = statistics.median(r[0] for r in rows) * 1e3
        m_small = statistics.median(r[1] for r in rows) * 1e3
        r_map = [r[1] / r[0] for r in rows]
        r_sec = [r[2]["ssec"][0] / r[2]["sec"][0] for r in rows]
        lines.append(
            f"{case:24s} {m_gen:12.1f} {m_small:10.1f} {statistics.median(r_map):6.2f} "
            f"({max(r_map):.2f})  {med['sec']:8.1f} ({steps['sec']:5d}) "
            f"{med['gsec']:9.1f} ({steps['gsec']:5d}) {med['ssec']:6.1f} ({steps['ssec']:5d})"
            f" {statistics.median(r_sec):6.2f} ({max(r_sec):.2f})")
    text = "\n".join(lines) + "\n"
    print(text, end="")
    OUT.write_text(text)


if __name__ == "__main__":
    main()
