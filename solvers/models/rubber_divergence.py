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


def _log_det_It(b: RubberBody, y):
    r, _ = b.support_grad_hess(y[3:])
    return np.log(np.linalg.det(np.diag(b.I) + b.m * ((r @ r) * np.eye(3) - np.outer(r, r))))


def log_density_rate(b: RubberBody, gamma, omega) -> float:
    """d/dt log f along the field at (omega, gamma) on N that a density f(gamma) in the
    chart (omega, gamma) would need: -div v + d/dt log det I~ (the chart (M, gamma) has
    density f / det I~)."""
    y = rl.state_on_manifold(b, omega, gamma)
    v = rl.field(b, y)
    return -divergence(b, y) + _log_det_It(b, y.astype(complex) + 1j * H * v).imag / H


def loop_integral(b: RubberBody, axis, angle: float, n: int = 400) -> float:
    """The loop integral, over the circle of gamma at `angle` from `axis`, of the 1-form
    alpha(u) = log_density_rate(gamma, u x gamma) (omega = u x gamma is the tangent omega
    with dgamma/dt = u on the plane). A density depending on gamma alone exists iff alpha
    is exact on the sphere of gamma, so a non-zero loop integral excludes it. On a sphere
    the rubber cases are balls, for which dgamma/dt = (gamma x omega)/(1 - k c), so there
    omega = (1 - k c) u x gamma. The trapezoid rule on a smooth periodic integrand converges
    geometrically in n."""
    axis = np.asarray(axis, dtype=float)
    axis /= np.linalg.norm(axis)
    e1 = np.cross(axis, [0.3, 0.5, 0.8])
    e1 /= np.linalg.norm(e1)
    e2 = np.cross(axis, e1)
    scale = 1.0 - b.k * b.c
    total = 0.0
    for t in np.linspace(0.0, 2.0 * np.pi, n, endpoint=False):
        g = np.cos(angle) * axis + np.sin(angle) * (np.cos(t) * e1 + np.sin(t) * e2)
        u = np.sin(angle) * (-np.sin(t) * e1 + np.cos(t) * e2)
        total += log_density_rate(b, g, scale * np.cross(u, g))
    return total * 2.0 * np.pi / n
