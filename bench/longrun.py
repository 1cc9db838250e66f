"""Long runs, T = 1e5: integrals held by projection, and the drift's growth without it.

For three integrable cases and both compiled methods:
  * with projection onto every integral the case carries (energy, gamma^2 and the case's
    own, after every step): the largest relative deviation of each over 1e5 time units
    and the cost (wall time, steps, right-hand-side calls) next to the same run without;
  * without projection: the energy drift |H(t) - H(0)| / |H(0)| (running maximum) at
    log-spaced times, and the exponent a of a fit drift ~ t^a over t in [1e2, 1e5]: a = 1
    is the linear growth of a non-symplectic adaptive RK whose truncation error dominates
    (rtol 1e-10); at rtol 1e-15 round-off dominates, and with compensated summation the
    growth approaches Brouwer's law a = 1/2 (a random walk of round-off errors);
  * the symmetric method gauss8 (Gauss collocation, constant step h, no projection): the
    same drift curve and exponent, and every integral's largest drift. On these
    reversible systems its truncation error does not accumulate (a ~ 0 while it
    dominates); what grows is round-off, by Brouwer's law.

    .venv/bin/python bench/longrun.py          (or: rolling bench longrun)

Writes bench/results/longrun.txt. The CLI form of the projected run:
    rolling simulate plane/chaplygin-ball --example --t-end 100000 --project
"""

from __future__ import annotations

import sys
import time
from pathlib import Path

import numpy as np

from solvers.integrate.integrator import integrate
from solvers.kernels.integrals import integral_series
from solvers.models.cases import build, initial_state, registry

OUT = Path(__file__).with_name("results")
T_END = 1e5
CASES = ("plane/chaplygin-ball", "sphere/borisov-fedorov", "plane/routh-ball")
FIT = (1e2, 1e5)


def drift_curve(model, Y):
    out = {}
    for name, code in zip(model.integral_names, model.integral_codes, strict=True):
        v = np.empty(len(Y))
        integral_series(code, model.model, np.ascontiguousarray(Y), model.p, v)
        out[name] = np.maximum.accumulate(np.abs(v - v[0]) / max(abs(v[0]), 1.0))
    return out


def fit_exponent(t, d):
    m = (t >= FIT[0]) & (t <= FIT[1]) & (d > 0)
    if m.sum() < 5:
        return None
    return float(np.polyfit(np.log(t[m]), np.log(d[m]), 1)[0])


def main(argv=None):
    lines, rows = [], []

    def say(s=""):
        print(s, flush=True)
        lines.append(s)

    t_out = np.r_[0.0, np.geomspace(1.0, T_END, 401)]
    say(f"T = {T_END:g}; drift = running max of |F(t) - F(0)| / max(|F(0)|, 1); "
        f"exponent a: fit drift ~ t^a on [{FIT[0]:g}, {FIT[1]:g}]")
    say("\n-- with projection after every step (rtol 1e-10, atol 1e-12) vs without")
    say(f"{'case':24s} {'method':7s} {'proj':>5s} {'steps':>7s} {'rhs':>8s} {'wall s':>7s}"
        f"  max drift of each integral")
    for cid in CASES:
        spec = registry()[cid]
        model = build(cid, spec.example)
        y0 = initial_state(model, spec.state)
        for method in ("dop853", "vern9"):
            integrate(model.model, model.p, y0, [0, 1], method=method,
                      project_codes=model.integral_codes)     # warm
            for proj in (True, False):
                r = integrate(model.model, model.p, y0, t_out, method=method, rtol=1e-10,
                              atol=1e-12, project_codes=model.integral_codes if proj else ())
                d = drift_curve(model, r.y)
                worst = {k: float(v[-1]) for k, v in d.items()}
                rows.append({"case": cid, "method": method, "project": proj, "rtol": 1e-10,
                             "compensated": False, "steps": r.steps,
                             "rhs_calls": r.rhs_calls, "wall_s": r.wall_s, "drift": worst,
                             "status": r.status})
                say(f"{cid:24s} {method:7s} {'yes' if proj else 'no':>5s} {r.steps:7d} "
                    f"{r.rhs_calls:8d} {r.wall_s:7.2f}  "
                    + " ".join(f"{k}={v:.1e}" for k, v in worst.items()))
    say("\n-- energy drift without projection: growth with t")
    probe = (1e1, 1e2, 1e3, 1e4, 1e5)
    say(f"{'case':24s} {'method':7s} {'rtol':>6s} {'comp':>5s} "
        + " ".join(f"{f't={p:g}':>9s}" for p in probe) + f" {'a':>6s} {'wall s':>7s}")
    for cid in CASES:
        spec = registry()[cid]
        model = build(cid, spec.example)
        y0 = initial_state(model, spec.state)
        for method in ("dop853", "vern9"):
            for rtol, comp in ((1e-10, False), (1e-15, False), (1e-15, True)):
                r = integrate(model.model, model.p, y0, t_out, method=method, rtol=rtol,
                              atol=rtol, compensated=comp)
                d = drift_curve(model, r.y)["energy"]
                a = fit_exponent(t_out, d)
                at = [float(d[np.searchsorted(t_out, p)]) for p in probe]
                rows.append({"case": cid, "method": method, "project": False, "rtol": rtol,
                             "compensated": comp, "steps": r.steps, "rhs_calls": r.rhs_calls,
                             "wall_s": r.wall_s, "energy_drift_at": dict(zip(probe, at,
                                                                            strict=True)),
                             "exponent": a, "status": r.status})
                say(f"{cid:24s} {method:7s} {rtol:6.0e} {'yes' if comp else 'no':>5s} "
                    + " ".join(f"{v:9.1e}" for v in at)
                    + f" {a if a is not None else float('nan'):6.2f} {r.wall_s:7.2f}")
    say("\n-- symmetric method, constant step, no projection (output every 0.8, a multiple of h)")
    say(f"{'case':24s} {'method':7s} {'h':>6s}      "
        + " ".join(f"{f't={p:g}':>9s}" for p in probe) + f" {'a':>6s} {'wall s':>7s}"
        + "  rhs calls  max drift of each integral")
    t_sym = np.arange(0.0, T_END + 0.4, 0.8)
    for cid in CASES:
        spec = registry()[cid]
        model = build(cid, spec.example)
        y0 = initial_state(model, spec.state)
        integrate(model.model, model.p, y0, [0, 1], method="gauss8", h_fixed=0.1)  # warm
        for h in (0.4, 0.2):
            r = integrate(model.model, model.p, y0, t_sym, method="gauss8", h_fixed=h)
            d = drift_curve(model, r.y)
            a = fit_exponent(t_sym, d["energy"])
            at = [float(d["energy"][min(np.searchsorted(t_sym, p), len(t_sym) - 1)])
                  for p in probe]
            worst = {k: float(v[-1]) for k, v in d.items()}
            rows.append({"case": cid, "method": "gauss8", "project": False, "step": h,
                         "steps": r.steps, "rhs_calls": r.rhs_calls, "wall_s": r.wall_s,
                         "energy_drift_at": dict(zip(probe, at, strict=True)), "exponent": a,
                         "drift": worst, "status": r.status})
            say(f"{cid:24s} {'gauss8':7s} {h:6.2f}      " + " ".join(f"{v:9.1e}" for v in at)
                + f" {a if a is not None else float('nan'):6.2f} {r.wall_s:7.2f}"
                + f"  {r.rhs_calls:9d}  " + " ".join(f"{k}={v:.1e}" for k, v in worst.items()))
    OUT.mkdir(exist_ok=True)
    (OUT / "longrun.txt").write_text("\n".join(lines) + "\n")
    return 0


if __name__ == "__main__":
    if {"-h", "--help"} & set(sys.argv[1:]):     # what it does, without running it
        print(__doc__)
        sys.exit(0)
    t0 = time.perf_counter()
    code = main(sys.argv[1:])
    print(f"total {time.perf_counter() - t0:.0f} s")
    sys.exit(code)
