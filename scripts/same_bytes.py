"""The same-bytes probe: a fixed set of runs whose state bytes are hashed, so that a change of
the kernels' code (not of their numbers) can be checked against the commit before it.

Runs, each hashed as sha256 of (t, states, t_stop, y_stop, status, counters):
  * every example case with dop853 and rk45, the default route (a plain run: the small
    kernel of its structure for dop853, the general loop kernel for rk45), and one ball
    with vern9 (its small kernel: a long compile per structure, so one);
  * every example case with dop853 on the general loop kernel (generated=False) with
    projection onto the energy, and with a section (the loop kernel's crossing code);
  * every example case with gauss4 (the collocation kernel, fixed step);
  * one ball with the small kernel with sections, with projection, and with dense output
    off and compensated sums on the general kernel;
  * an ensemble of two starts on the general kernel (the compiled parallel loop);
  * --generated: also one case on the generated loop integrator (generated=True,
    kernel="rk") and its ensemble twin (a long compile).

    PYTHONPATH=$PWD python scripts/same_bytes.py OUT.txt [--generated]

OUT.txt gets one line per run (name, hash) and a last line with the hash of them all;
compare two such files with diff.
"""

import hashlib
import sys

import numpy as np

from solvers.integrate.ensemble import integrate_ensemble
from solvers.integrate.integrator import Section, integrate
from solvers.kernels.integrals import ENERGY
from solvers.models.cases import build, registry

T_END = 5.0
SAMPLES = 11


def digest(r) -> str:
    d = hashlib.sha256()
    for a in (r.t, r.y, [r.t_stop], r.y_stop, r.crossings_t, r.crossings_y):
        d.update(np.ascontiguousarray(a, dtype=np.float64).tobytes())
    d.update(repr((int(r.status), r.steps, r.rejected, r.rhs_calls, r.kernel,
                   r.vector_field)).encode())
    return d.hexdigest()


def runs(generated: bool):
    t = np.linspace(0.0, T_END, SAMPLES)
    for cid, case in registry().items():
        m = build(cid, case.example)
        y0 = np.asarray(case.state, dtype=float)
        for method in ("dop853", "rk45"):
            yield f"{cid} {method} default", integrate(m.model, m.p, y0, t, method=method)
        yield f"{cid} dop853 general projected", integrate(
            m.model, m.p, y0, t, generated=False, project_codes=(ENERGY,))
        n = y0.size
        sec = Section(coef=tuple(1.0 if i == 0 else 0.0 for i in range(n)),
                      offset=float(y0[0]), direction=0)
        yield f"{cid} dop853 general section", integrate(
            m.model, m.p, y0, [0.0, 20.0], generated=False, section=sec, max_crossings=6)
        yield f"{cid} gauss4", integrate(m.model, m.p, y0, t, method="gauss4", h_fixed=0.01)
    c = registry()["plane/chaplygin-ball"]
    m = build(c.id, c.example)
    y0 = np.asarray(c.state, dtype=float)
    sec = Section(coef=(0.0, 0.0, 0.0, 0.0, 0.0, 1.0), offset=float(y0[5]), direction=1)
    yield "ball vern9 default", integrate(m.model, m.p, y0, t, method="vern9")
    yield "ball small sections", integrate(m.model, m.p, y0, [0.0, 30.0], section=sec,
                                           max_crossings=5, kernel="small")
    yield "ball small projection", integrate(m.model, m.p, y0, t, project_codes=(ENERGY,),
                                             kernel="small")
    yield "ball small compensated", integrate(m.model, m.p, y0, t, compensated=True)
    yield "ball general clipped compensated", integrate(
        m.model, m.p, y0, t, generated=False, dense_output=False, compensated=True)
    yield "ball general fixed", integrate(m.model, m.p, y0, t, generated=False, h_fixed=0.01)
    Y0 = np.array([y0, y0 * (1 + 1e-3)])
    for i, r in enumerate(integrate_ensemble(m.model, m.p, Y0, t, generated=False,
                                             section=sec, max_crossings=3, workers=2)):
        yield f"ball ensemble general {i}", r
    if generated:
        yield "ball generated loops", integrate(m.model, m.p, y0, t, generated=True,
                                                kernel="rk", project_codes=(ENERGY,))
        for i, r in enumerate(integrate_ensemble(m.model, m.p, Y0, t, generated=True,
                                                 section=sec, max_crossings=3, workers=2)):
            yield f"ball ensemble generated {i}", r


def main(argv):
    out = argv[0]
    lines = [f"{name}\t{digest(r)}" for name, r in runs("--generated" in argv)]
    total = hashlib.sha256("\n".join(lines).encode()).hexdigest()
    with open(out, "w") as f:
        f.write("\n".join([*lines, f"ALL\t{total}"]) + "\n")
    print(f"{len(lines)} runs, ALL {total}")


if __name__ == "__main__":
    main(sys.argv[1:])
