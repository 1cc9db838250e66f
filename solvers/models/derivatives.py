"""Exact first derivatives by complex step: f'(x) h = Im f(x + i h e) / h, no cancellation.

The compiled kernels accept complex128 states, so gradients of integrals and Jacobians of
vector fields come out to round-off (used by the invariant checks and by tests).
"""

import numpy as np

from solvers.kernels.fields import rhs
from solvers.kernels.integrals import integral

H = 1e-30


def field(model: int, p: np.ndarray, y: np.ndarray) -> tuple[np.ndarray, int]:
    d = np.empty(len(y), dtype=np.result_type(y, float))
    status = rhs(model, 0.0, y, p, d)
    return d, status


def integral_gradient(code: int, model: int, p: np.ndarray, y: np.ndarray) -> np.ndarray:
    g = np.empty(len(y))
    for j in range(len(y)):
        yc = y.astype(np.complex128)
        yc[j] += 1j * H
        g[j] = integral(code, model, yc, p).imag / H
    return g


def field_jacobian(model: int, p: np.ndarray, y: np.ndarray) -> np.ndarray:
    n = len(y)
    Jac = np.empty((n, n))
    for j in range(n):
        yc = y.astype(np.complex128)
        yc[j] += 1j * H
        d, _ = field(model, p, yc)
        Jac[:, j] = d.imag / H
    return Jac


def integral_rate(code: int, model: int, p: np.ndarray, y: np.ndarray) -> float:
    """|grad F . v| / (|grad F| |v|): zero to round-off where F is a first integral."""
    v, status = field(model, p, y)
    if status:
        raise ValueError(f"field singular at {y} (status {status})")
    g = integral_gradient(code, model, p, y)
    return float(abs(g @ v) / max(np.linalg.norm(g) * np.linalg.norm(v), 1e-300))
