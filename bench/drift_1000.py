"""Relative drift of energy and gamma^2 over T = 1000 at rtol 1e-12 for every case and
every compiled method (no projection): the solver core's done-when figure.

    python bench/drift_1000.py        (output: bench/results/drift_1000.txt)
"""

from pathlib import Path

from solvers.models.cases import registry
from solvers.simulate import simulate


def main():
    rows = [f"{'case':32s} {'method':7s} {'steps':>7s} {'rhs':>8s} {'wall_s':>7s} "
            f"{'energy':>9s} {'gamma2':>9s}  integrals"]
    for cid, c in registry().items():
        for method in ("dop853", "vern9"):
            r = simulate(cid, c.example, c.state, 1000.0, method=method, rtol=1e-12,
                         atol=1e-14, samples=2001)
            s = r.stats
            g2 = f"{r.drift('gamma2'):9.1e}" if "gamma2" in r.invariants else f"{'-':>9s}"
            others = " ".join(f"{k}={v:.1e}" for k, v in s["drift"].items()
                              if k not in ("energy", "gamma2"))
            rows.append(f"{cid:32s} {method:7s} {s['steps']:7d} {s['rhs_calls']:8d} "
                        f"{s['wall_s']:7.3f} {r.drift('energy'):9.1e} {g2}  {others}"
                        + ("" if r.ok else f"  [{r.status}: {r.message}]"))
    text = ("T = 1000, rtol 1e-12, atol 1e-14, no projection; drift = max|F(t)-F(0)| / "
            "max(|F(0)|, 1)\n" + "\n".join(rows))
    print(text)
    (Path(__file__).parent / "results" / "drift_1000.txt").write_text(text + "\n")


if __name__ == "__main__":
    main()
