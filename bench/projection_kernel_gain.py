"""What the small kernel with projection gains a projected run (issue 19, item 1).

A run projected onto the levels of its integrals (integrate(project_codes=...), simulate's
project=True) runs rk.py's general kernel by default, or, when asked
(integrate(kernel="small")), the small kernel with projection (solvers/kernels/small.py:
the generated field inlined, state and stages in locals, rk.py's own projection): the
generated integrator's steps and bits. For one long run per start (T = 1000, rtol 1e-10,
atol 1e-12, projected every step onto the energy level and the case's geometric integral
|gamma|^2, 1001 samples), this times
  general           rk.py's kernel on the general field (the default);
  generated         rk.py's kernel on the case's generated field (opt-in, ~32 s of compile);
  small             the small kernel with projection (10-14 s of compile per structure);
and, for scale, the same run without projection on the small kernel (plain).
Best of 3 timings each, after a warm call; 5 starts per case (the case's state with M
scaled by 0.5-2): milliseconds (steps), median over the starts; the ratio small/general
per start, median (max).

    PYTHONPATH=$PWD .venv/bin/python bench/projection_kernel_gain.py
        -> bench/results/projection_kernel_gain.txt
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
from solvers.kernels.integrals import ENERGY, NAMES  # noqa: E402
from solvers.models.cases import build, get_case  # noqa: E402

OUT = ROOT / "bench" / "results" / "projection_kernel_gain.txt"
CASES = ["plane/chaplygin-ball", "sphere/routh-ball", "plane/rattleback"]
SCALES = (0.5, 0.75, 1.0, 1.5, 2.0)


def main() -> None:
    codes = (ENERGY, NAMES.index("gamma2"))
    t_out = [i * 1.0 for i in range(1001)]
    lines = [f"projection kernel gain, {time.strftime('%Y-%m-%d %H:%M UTC', time.gmtime())}, "
             f"load average {' '.join(f'{x:.2f}' for x in os.getloadavg())}",
             "T = 1000, rtol 1e-10, projected every step onto E and |gamma|^2: ms (steps), "
             "median over 5 starts; small/general per start, median (max)",
             f"{'case':22s} {'general':>15s} {'generated':>15s} {'small':>15s} "
             f"{'small plain':>15s} {'small/general':>15s}"]
    for case in CASES:
        c = get_case(case)
        m = build(case, c.example)
        rows = []
        for k in SCALES:
            y0 = list(c.state)
            y0[:3] = [k * v for v in y0[:3]]
            runs = {}
            for label, kw in (("general", {"project_codes": codes}),
                              ("generated", {"project_codes": codes, "generated": True,
                                             "kernel": "rk"}),
                              ("small", {"project_codes": codes, "kernel": "small"}),
                              ("plain", {})):
                dt, r = warm_best(integrate, m.model, m.p, y0, t_out, rtol=1e-10, atol=1e-12,
                                  **kw)
                runs[label] = (dt, r.steps, r.kernel)
            assert runs["small"][2] == "small-projection" and runs["general"][2] == "rk"
            assert runs["small"][1] == runs["generated"][1], runs
            rows.append(runs)
        med = {k: statistics.median(r[k][0] for r in rows) * 1e3 for k in rows[0]}
        steps = {k: int(statistics.median(r[k][1] for r in rows)) for k in rows[0]}
        ratio = [r["small"][0] / r["general"][0] for r in rows]
        lines.append(f"{case:22s} " + " ".join(
            f"{med[k]:7.1f} ({steps[k]:5d})" for k in ("general", "generated", "small", "plain"))
            + f" {statistics.median(ratio):8.2f} ({max(ratio):.2f})")
    text = "\n".join(lines) + "\n"
    print(text, end="")
    OUT.write_text(text)


if __name__ == "__main__":
    main()
