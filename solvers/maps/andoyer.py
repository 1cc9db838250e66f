"""Andoyer-Deprit variables (L, G, H, l, g) of a state (M, gamma): the paper's (2.22).

    M = (sqrt(G^2 - L^2) sin l, sqrt(G^2 - L^2) cos l, L)
    gamma = (H/G) m + sqrt(1 - (H/G)^2) (cos g u + sin g v),   m = M/G,
    u = (L/G sin l, L/G cos l, -sqrt(1 - (L/G)^2)),  v = (cos l, -sin l, 0)

((2.22) written with the orthonormal frame (m, u, v); expanding it gives the printed
components). Inverse: G = |M|, L = M3, H = (M, gamma)/|gamma|, l = atan2(M1, M2),
g = atan2(Sg, Cg) with Sg, Cg of solvers/kernels/sections.py. The angles are returned
in [0, 2 pi). g is undefined where M is along the body axis e3 (L/G = +-1) or gamma is
along M (H/G = +-1); l where L/G = +-1.

The energy E = (M, omega)/2 + U(gamma), omega = I_Q(gamma)^-1 M, is quadratic in M at
fixed gamma, and gamma depends on (L/G, H/G, l, g) only: on the level E = E0 the modulus
is G = sqrt((E0 - U) / E_kin(m, gamma)), no root finding needed.
"""

import numpy as np

from solvers.kernels import integrals as Q
from solvers.kernels.rk import model_integral

TWO_PI = 2.0 * np.pi


def unit_frame(lam, l):
    """m, u, v of the module docstring (arrays broadcast over the last axis)."""
    lam = np.asarray(lam, dtype=float)
    l = np.asarray(l, dtype=float)
    c = np.sqrt(np.clip(1.0 - lam * lam, 0.0, None))
    sl, cl = np.sin(l), np.cos(l)
    m = np.stack([c * sl, c * cl, lam], axis=-1)
    u = np.stack([lam * sl, lam * cl, -c], axis=-1)
    v = np.stack([cl, -sl, np.zeros_like(l)], axis=-1)
    return m, u, v


def from_andoyer(lam, h, l, g, G=1.0):
    """State(s) (M, gamma) of L/G = lam, H/G = h, l, g and |M| = G (2.22)."""
    m, u, v = unit_frame(lam, l)
    h = np.asarray(h, dtype=float)[..., None]
    g = np.asarray(g, dtype=float)[..., None]
    s = np.sqrt(np.clip(1.0 - h * h, 0.0, None))
    gamma = h * m + s * (np.cos(g) * u + np.sin(g) * v)
    return np.concatenate([np.asarray(G, dtype=float)[..., None] * m, gamma], axis=-1)


def to_andoyer(Y):
    """(L, G, H, l, g) of state(s) Y = (M, gamma): arrays over the leading axes."""
    Y = np.asarray(Y, dtype=float)
    M, gam = Y[..., 0:3], Y[..., 3:6]
    G = np.linalg.norm(M, axis=-1)
    L = M[..., 2]
    H = np.sum(M * gam, axis=-1) / np.linalg.norm(gam, axis=-1)
    l = np.mod(np.arctan2(M[..., 0], M[..., 1]), TWO_PI)
    Sg = G * (gam[..., 0] * M[..., 1] - gam[..., 1] * M[..., 0])
    Cg = M[..., 2] * (M[..., 0] * gam[..., 0] + M[..., 1] * gam[..., 1]) \
        - (M[..., 0] ** 2 + M[..., 1] ** 2) * gam[..., 2]
    g = np.mod(np.arctan2(Sg, Cg), TWO_PI)
    return L, G, H, l, g


def map_point(Y):
    """The paper's map coordinates (L/G, H/G, l) of state(s) Y, shape (..., 3)."""
    L, G, H, l, _ = to_andoyer(Y)
    return np.stack([L / G, H / G, l], axis=-1)


def g_angle(Y):
    """g of state(s) Y in [0, 2 pi)."""
    return to_andoyer(Y)[4]


def energy_parts(model, y):
    """(E_kin at |M| = 1, U) of the direction m = M/|M| and gamma of y."""
    y = np.array(y, dtype=float)
    m = y[:3] / np.linalg.norm(y[:3])
    unit = np.concatenate([m, y[3:6]])
    rest = np.concatenate([np.zeros(3), y[3:6]])
    U = float(model_integral(Q.ENERGY, model.model, rest, model.p))
    E1 = float(model_integral(Q.ENERGY, model.model, unit, model.p))
    return E1 - U, U


def on_energy_level(model, lam, h, l, g, energy):
    """The state with map coordinates (lam, h, l), angle g and energy E0, or None when
    E0 <= U(gamma) there (the level has no point with this direction)."""
    y = from_andoyer(lam, h, l, g, 1.0)
    ek, U = energy_parts(model, y)
    if not (ek > 0.0 and energy > U):
        return None
    y[:3] *= np.sqrt((energy - U) / ek)
    return y
