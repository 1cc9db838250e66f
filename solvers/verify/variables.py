"""From the full state to the variables a formula is written in (complex-safe).

Full states are the model's: (M, gamma) in R^6, or (M, r1, r2) in R^5 for flat bases.
`to_vars(name, P, y)` returns the point in the formula's variables; where those variables
are a change of coordinates of the same dimension, `jacobian_det(name, P, y)` gives
det d(vars)/d(full) so a density in those variables can be pulled back:
    rho_full(y) = rho_vars(phi(y)) * |det D phi(y)|.
"""

import numpy as np

from solvers.models.reduced_systems import flat_reduced, to_reduced

SAME_DIMENSION = {"(M, gamma)", "(omega, gamma)", "(K, gamma)", "(M, r1, r2)",
                  "(omega, r1, r2)"}


def chaplygin_rho(P, gamma):
    """(2.24): (1 - D (gamma, A gamma))^-1/2, A = (I + D E)^-1, D = m R^2."""
    A = 1.0 / (P.I + P.D)
    return 1.0 / np.sqrt(1.0 - P.D * (gamma @ (A * gamma)))


def to_vars(name: str, P, y):
    if name in ("(M, gamma)", "(M, r1, r2)"):
        return y
    M = y[:3]
    if name == "(omega, gamma)":
        return np.concatenate([P.omega(M, y[3:6]), y[3:6]])
    if name == "(omega, r1, r2)":
        r = np.array([y[3], y[4], P.z + 0.0 * y[3]])
        return np.concatenate([P.omega(M, r), y[3:5]])
    if name == "(K, gamma)":
        return np.concatenate([chaplygin_rho(P, y[3:6]) * M, y[3:6]])
    if name == "(gamma3, K1, K2, K3)":
        return to_reduced(P.p, y)
    if name == "(gamma3, K1, K2)":
        return to_reduced(P.p, y)[:3]
    if name == "(theta, K1, K2)":
        x = to_reduced(P.p, y)
        return np.array([np.arccos(x[0]), x[1], x[2]])
    if name == "(theta, omega3)":
        return np.array([np.arccos(y[5]), P.omega(M, y[3:6])[2]])
    if name == "(x, omega3)":
        return np.array([(1.0 - y[5]) / 2.0, P.omega(M, y[3:6])[2]])
    if name == "(u, K1, K2)":
        return flat_reduced(P.p, y)
    if name == "(u, K1, K2, K3)":
        # K3 = r1 M2 - r2 M1, the axial-rotation momentum conjugate to u in the project's
        # bracket (solvers/verify/formulas/hamiltonian_sphere.py); polynomial, so the exact
        # certificates can evaluate it
        x = flat_reduced(P.p, y)
        return np.array([x[0], x[1], x[2], y[3] * M[1] - y[4] * M[0]])
    if name == "(gamma)":
        return y[3:6]
    if name == "(gamma3)":
        return y[5:6]
    raise KeyError(f"no map from the full state to {name}")


def jacobian(name: str, P, y, h=1e-30):
    """d(vars)/d(full) by complex step."""
    n = len(y)
    cols = []
    for j in range(n):
        yc = y.astype(np.complex128)
        yc[j] += 1j * h
        cols.append(np.asarray(to_vars(name, P, yc)).imag / h)
    return np.stack(cols, axis=1)


def jacobian_det(name: str, P, y) -> float:
    if name not in SAME_DIMENSION:
        raise KeyError(f"{name} is not a change of coordinates of the full state")
    if name in ("(M, gamma)", "(M, r1, r2)"):
        return 1.0
    return float(np.linalg.det(jacobian(name, P, y)))


def log_det(name: str, P, y):
    """log det d(vars)/d(full) in closed form (complex-safe, so it can itself be
    differentiated by complex step): the pull-back factor of a density."""
    if name in ("(M, gamma)", "(M, r1, r2)"):
        return 0.0 * y[0]
    if name == "(omega, gamma)":
        return -np.log(np.linalg.det(P.contact_inertia(P.r(y[3:6]))))
    if name == "(omega, r1, r2)":
        r = np.array([y[3], y[4], P.z + 0.0 * y[3]])
        return -np.log(np.linalg.det(P.contact_inertia(r)))
    if name == "(K, gamma)":
        return 3.0 * np.log(chaplygin_rho(P, y[3:6]))
    raise KeyError(f"{name} is not a change of coordinates of the full state")
