"""Numbers that say what a 3D point map shows (bench/paper_figures.py, tests).

  * `log_det_series`: log |det DP| of the map P: (L/G, H/G, l) -> next crossing, by
    central differences on the section at fixed energy. Where the flow has an invariant
    measure with a smooth positive density, the map keeps a measure on the section, so
    det DP(x) = sigma(x) / sigma(P x) and the mean of log |det DP| along an orbit of n
    points is (log sigma(x_0) - log sigma(x_n)) / n -> 0. A mean that stays away from 0
    as n grows is the contraction (< 0) or expansion (> 0) of phase volume per return: no
    invariant measure with a smooth density along that orbit.
  * `local_dimension`: at each point, the principal spreads s1 >= s2 >= s3 of its k
    nearest neighbours; on a curve s2/s1 is small, on a surface s3/s1, in a volume none.
"""

from __future__ import annotations

import math

import numpy as np

from solvers.integrate.integrator import integrate
from solvers.maps.andoyer import TWO_PI, map_point, on_energy_level
from solvers.maps.poincare import PILOT_TAUS, MapSpec, omega_norm
from solvers.models.cases import Model


def next_point(model: Model, spec: MapSpec, x) -> np.ndarray | None:
    """P(x): the map point of the first crossing after the start x = (L/G, H/G, l) on
    the level spec.energy and the section (None if it does not return)."""
    y0 = on_energy_level(model, x[0], x[1], x[2], spec.g0, spec.energy)
    if y0 is None:
        return None
    w = omega_norm(model, y0)
    if not math.isfinite(w):       # I_Q singular at the start: the field stops there
        return None
    tau = TWO_PI / w
    res = integrate(model.model, model.p, y0, [0.0, PILOT_TAUS * tau], method=spec.method,
                    rtol=spec.rtol, atol=spec.atol, section=spec.section(),
                    max_crossings=2, max_steps=spec.max_steps)
    keep = res.crossings_t > 1e-9 * tau
    if not np.any(keep):
        return None
    return map_point(res.crossings_y[keep][0])


def _wrap(d):
    return (d + np.pi) % TWO_PI - np.pi


def jacobian(model: Model, spec: MapSpec, x, delta: float = 1e-6) -> np.ndarray | None:
    """DP at x by central differences (the angle l wrapped)."""
    x = np.asarray(x, dtype=float)
    J = np.empty((3, 3))
    for j in range(3):
        e = np.zeros(3)
        e[j] = delta
        a, b = next_point(model, spec, x + e), next_point(model, spec, x - e)
        if a is None or b is None:
            return None
        d = a - b
        d[2] = _wrap(d[2])
        J[:, j] = d / (2.0 * delta)
    return J


def log_det_series(model: Model, spec: MapSpec, points, delta: float = 1e-6) -> np.ndarray:
    """log |det DP| at each map point (NaN where the map is undefined nearby)."""
    out = []
    for x in points:
        J = jacobian(model, spec, x, delta)
        out.append(np.nan if J is None else float(np.log(abs(np.linalg.det(J)))))
    return np.asarray(out)


def local_dimension(points, k: int = 12) -> np.ndarray:
    """(s2/s1, s3/s1) at each point from its k nearest neighbours; l is measured as
    l/pi and wrapped, so that the three coordinates have comparable ranges."""
    P = np.asarray(points, dtype=float)
    Q = P * np.array([1.0, 1.0, 1.0 / np.pi])
    out = np.empty((len(P), 2))
    for i, q in enumerate(Q):
        d = Q - q
        d[:, 2] = (d[:, 2] + 1.0) % 2.0 - 1.0
        nn = np.argsort(np.einsum("ij,ij->i", d, d))[1:k + 1]
        X = d[nn] - d[nn].mean(axis=0)
        s = np.linalg.svd(X, compute_uv=False)
        out[i] = s[1] / s[0], s[2] / s[0]
    return out


def correlation_dimension(points, r_lo: float = 0.02, r_hi: float = 0.2,
                          max_points: int = 4000) -> float:
    """Grassberger-Procaccia: the slope of log C(r) against log r on [r_lo, r_hi], C(r)
    the fraction of pairs closer than r (l measured as l/pi, wrapped). About 1 for points
    on a curve, 2 on a surface, 3 for points filling a volume (at these scales)."""
    P = np.asarray(points, dtype=float)[:max_points] * np.array([1.0, 1.0, 1.0 / np.pi])
    n = len(P)
    radii = np.geomspace(r_lo, r_hi, 8)
    counts = np.zeros(len(radii))
    for i in range(n - 1):
        d = P[i + 1:] - P[i]
        d[:, 2] = (d[:, 2] + 1.0) % 2.0 - 1.0
        dist = np.sqrt(np.einsum("ij,ij->i", d, d))
        counts += np.searchsorted(np.sort(dist), radii, side="right")
    ok = counts > 0
    if ok.sum() < 2:
        return float("nan")
    return float(np.polyfit(np.log(radii[ok]), np.log(counts[ok]), 1)[0])
