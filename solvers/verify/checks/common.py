"""Shared numerics of the checks: tolerance, sampling, complex-step derivatives."""

import numpy as np

from solvers.models.derivatives import field
from solvers.verify.registry import CORRECTED, FORMULAS

# One project-wide threshold on normalised residuals computed with exact derivatives.
# Round-off gives ~1e-15..1e-13; a wrong formula gives O(1e-3..1). Never tuned per claim.
TOL = 1e-9
N_SETTINGS = 3          # parameter draws per claim
N_POINTS = 70           # random phase points per draw (3 x 70 >= 200)
H = 1e-30


def implementation(fid: str, use_corrected: bool = False):
    table = CORRECTED if use_corrected else FORMULAS
    if fid not in table:
        raise LookupError(f"formula {fid!r} has no {'corrected ' if use_corrected else ''}"
                          "implementation")
    return table[fid]


def full_field(P, y):
    v, status = field(P.model.model, P.p, y)
    if status:
        raise FloatingPointError(f"field singular (status {status})")
    return v


def directional(fn, y, v, h=H):
    """d/dt fn(y(t)) along v: Im fn(y + i h v) / h (exact, one evaluation)."""
    return np.asarray(fn(y.astype(np.complex128) + 1j * h * v)).imag / h


def gradient(fn, y, h=H):
    g = np.empty(len(y))
    for j in range(len(y)):
        yc = y.astype(np.complex128)
        yc[j] += 1j * h
        g[j] = np.asarray(fn(yc)).imag / h
    return g


def divergence_terms(fn_field, y, h=H):
    """(div v, sum |d v_i / d y_i|) of a field fn_field at y, by complex step."""
    div, scale = 0.0, 0.0
    for j in range(len(y)):
        yc = y.astype(np.complex128)
        yc[j] += 1j * h
        d = np.asarray(fn_field(yc))[j].imag / h
        div += d
        scale += abs(d)
    return div, scale
