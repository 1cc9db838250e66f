"""Quantities read off a trajectory (M, gamma) of the full model, for scenes and figures:
the angular velocity, the spin about the vertical, and the times the spin reverses."""

from __future__ import annotations

import numpy as np

from solvers.kernels import layout as L
from solvers.kernels.fields import full_kinematics
from solvers.models.cases import Model


def omega(model: Model, Y) -> np.ndarray:
    """omega = I_Q^-1 M (body axes) at every row of Y = (M, gamma); NaN where singular."""
    Y = np.atleast_2d(np.asarray(Y, dtype=float))
    out = np.full((len(Y), 3), np.nan)
    r, J, w, gd = np.empty(3), np.empty((3, 3)), np.empty(3), np.empty(3)
    for i, y in enumerate(Y):
        y = np.ascontiguousarray(y)
        if full_kinematics(model.p, y[0:3], y[3:6], r, J, w, gd) == L.OK:
            out[i] = w
    return out


def vertical_spin(model: Model, Y) -> np.ndarray:
    """The spin about the upward vertical, -(omega, gamma) (gamma points down into the
    support): positive is counterclockwise seen from above."""
    Y = np.atleast_2d(np.asarray(Y, dtype=float))
    return -np.sum(omega(model, Y) * Y[:, 3:6], axis=1)


def spin_reversals(t, spin, window: float) -> list[float]:
    """Times where the spin, averaged over a sliding `window` (to remove the rocking
    oscillation on top of it), changes sign."""
    t = np.asarray(t, dtype=float)
    spin = np.asarray(spin, dtype=float)
    dt = float(t[1] - t[0])
    k = max(1, round(window / dt))
    if len(spin) < k:
        return []
    avg = np.convolve(spin, np.ones(k) / k, mode="valid")
    ta = t[k // 2: k // 2 + len(avg)]
    idx = np.flatnonzero(np.sign(avg[1:]) * np.sign(avg[:-1]) < 0)
    return [float(0.5 * (ta[i] + ta[i + 1])) for i in idx]


# --- the one name of each first integral in every output of a run ------------------------
# JSON (SimulationResult.invariants, stats["drift"], POST /api/simulate), CSV and Arrow
# columns all use these names. They are the kernels' code names (solvers/kernels/integrals.py
# NAMES) except where a code name reads as a state component: |M|^2 is "M_squared", never
# "M2", which is the component M2 of the state.
PUBLIC_NAMES = {"gamma2": "gamma_squared", "M2": "M_squared", "gyro_M2": "M_plus_S_squared"}
KERNEL_NAMES = {v: k for k, v in PUBLIC_NAMES.items()}


def public_name(name: str) -> str:
    """The output name of the integral the kernels call `name` (itself unless renamed)."""
    return PUBLIC_NAMES.get(name, name)


def kernel_name(name: str) -> str:
    """The kernels' code name of the integral an output calls `name`."""
    return KERNEL_NAMES.get(name, name)


class Invariants(dict):
    """A run's integrals by their output names. A lookup by a kernel code name that was
    renamed ("M2" for "M_squared") finds the same series, so code written in the kernels'
    vocabulary (catalogue/scenes.yaml's checks) still reads it; keys, iteration and every
    output carry the output names only."""

    def __missing__(self, key):
        alias = PUBLIC_NAMES.get(key)
        if alias is not None and dict.__contains__(self, alias):
            return dict.__getitem__(self, alias)
        raise KeyError(key)

    def __contains__(self, key) -> bool:
        return dict.__contains__(self, key) or dict.__contains__(self, PUBLIC_NAMES.get(key))

    def get(self, key, default=None):
        return self[key] if key in self else default
