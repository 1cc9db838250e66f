"""Run a rubber case with scipy DOP853 and report how well the constraint, |gamma| = 1 and
the energy hold: python -m solvers.models.rubber_run CASE T [TOL].

The plain-NumPy field of rubber_lagrange.py is integrated as it is, with no projection, so
the drifts printed are the integrator's own errors at the given tolerance.
"""

from __future__ import annotations

import sys
import time

import numpy as np
from scipy.integrate import solve_ivp

from solvers.models import rubber_bodies as rb
from solvers.models import rubber_lagrange as rl


def drifts(case_id: str, T: float, tol: float = 1e-12, n_out: int = 2001):
    """(max |(omega, gamma)|, max ||gamma| - 1|, max |H - H0| / |H0|, wall seconds) over [0, T]
    from the case's demonstration state."""
    b = rb.body(case_id)
    y0 = rl.state_on_manifold(b, [0.3, -0.5, 0.7], [0.2, 0.3, 0.9])
    t0 = time.perf_counter()
    sol = solve_ivp(lambda _t, y: rl.field(b, y), (0.0, T), y0, method="DOP853", rtol=tol,
                    atol=tol, t_eval=np.linspace(0.0, T, n_out))
    if sol.status != 0:
        raise RuntimeError(sol.message)
    wall = time.perf_counter() - t0
    Y = sol.y.T
    H0 = rl.energy(b, y0)
    return (max(abs(rl.spin(b, y)) for y in Y),
            float(np.max(np.abs(np.linalg.norm(Y[:, 3:], axis=1) - 1.0))),
            max(abs(rl.energy(b, y) - H0) for y in Y) / abs(H0), wall)


def main(argv=None):
    argv = sys.argv[1:] if argv is None else argv
    case_id, T = argv[0], float(argv[1])
    tol = float(argv[2]) if len(argv) > 2 else 1e-12
    spin, unit, energy, wall = drifts(case_id, T, tol)
    print(f"{case_id} T={T:g} tol={tol:g}: max|(omega,gamma)|={spin:.1e} "
          f"max||gamma|-1|={unit:.1e} max|dH/H|={energy:.1e} ({wall:.0f} s)")


if __name__ == "__main__":
    main()
