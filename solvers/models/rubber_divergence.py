"""The divergence of the rubber field along an orbit: evidence for or against a smooth
invariant measure.

If rho > 0 is a smooth invariant density on N (rubber_exact.py explains the quotient by the
first integrals (omega, gamma) and gamma^2 of the R^6 field), then along every orbit
d/dt log rho = -div v, so the integral of div v over [0, T] equals log rho(start) -
log rho(end): it stays bounded on an orbit whose closure is compact. An integral that
grows in proportion to T on a bounded orbit (it settles on an attracting set) rules out a
smooth positive measure on that orbit's closure. This is numerical evidence, not a proof:
the run is finite and its tolerance is that of the integrator.

div v is taken exactly at each point by complex step of the field of rubber_lagrange.py.
"""

from __future__ import annotations

import numpy as np
from scipy.integrate import solve_ivp

from solvers.models import rubber_lagrange as rl
from solvers.models.rubber_bodies import RubberBody

H = 1e-30


def divergence(b: RubberBody, y) -> float:
    y = np.asarray(y, dtype=float)
    return float(sum(rl.field(b, y.astype(complex) + 1j * H * np.eye(6)[j])[j].imag / H
                     for j in range(6)))


def divergence_integral(b: RubberBody, y0, T: float, n_out: int = 9, tol: float = 1e-10):
    """(times, integral of div v from 0 to each time, final state) along the orbit of y0."""
    def rhs(_t, z):
        return np.concatenate([rl.field(b, z[:6]), [divergence(b, z[:6])]])

    t_eval = np.linspace(0.0, T, n_out)
    sol = solve_ivp(rhs, (0.0, T), np.concatenate([y0, [0.0]]), method="DOP853",
                    rtol=tol, atol=tol, t_eval=t_eval)
    if sol.status != 0:
        raise RuntimeError(sol.message)
    return sol.t, sol.y[6], sol.y[:6, -1]
