"""Quantities read off a trajectory (M, gamma) of the full model, for scenes and figures:
the angular velocity, the spin about the vertical, and the times the spin reverses; the
rubber quantities (the no-spin constraint, |gamma| - 1 and the rubber cases' integrals
beyond the energy) under one name each (RUBBER, `series`)."""

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


def spin(model: Model, Y) -> np.ndarray:
    """(omega, gamma), the spin about the normal: the rubber constraint, zero on rubber
    motions (the kernels' integral "spin" is the same number)."""
    Y = np.atleast_2d(np.asarray(Y, dtype=float))
    return np.sum(omega(model, Y) * Y[:, 3:6], axis=1)


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


# --- the rubber quantities ------------------------------------------------------------------
# Each is a function of (model, Y) with Y the rows (M, gamma); the integrals are those the
# rubber tables state (catalogue/rubber_plane.yaml, rubber_sphere.yaml; docs/rubber.md) and
# the place there that proves them exactly.

def _kinematics(model: Model, Y) -> tuple[np.ndarray, np.ndarray]:
    """(omega, r) at every row of Y (NaN where singular)."""
    Y = np.atleast_2d(np.asarray(Y, dtype=float))
    W, R = np.full((len(Y), 3), np.nan), np.full((len(Y), 3), np.nan)
    r, J, w, gd = np.empty(3), np.empty((3, 3)), np.empty(3), np.empty(3)
    for i, y in enumerate(Y):
        y = np.ascontiguousarray(y)
        if full_kinematics(model.p, y[0:3], y[3:6], r, J, w, gd) == L.OK:
            W[i], R[i] = w, r
    return W, R


def gamma_norm_defect(model: Model, Y) -> np.ndarray:
    """|gamma| - 1: zero on every motion (gamma is a unit vector)."""
    Y = np.atleast_2d(np.asarray(Y, dtype=float))
    return np.linalg.norm(Y[:, 3:6], axis=1) - 1.0


def _ball_J(model: Model) -> np.ndarray:
    """J = I + m R^2 of a balanced ball (diagonal): on the rubber manifold M = J omega."""
    p = model.p
    return np.array([p[L.I1 + i] for i in range(3)]) + p[L.MASS] * p[L.BALL_C] ** 2


def rubber_ball_F(model: Model, Y) -> np.ndarray:
    """F = |(M + S) x gamma|^2 - eps det J (gamma, J^-1 gamma) of the rubber Chaplygin ball on
    a plane (rubber_exact.py ball_integral_residual, ball_gyrostat_integral_residual,
    ball_brun_integral_residual): |M x gamma|^2 without gyrostat S and Brun field eps."""
    Y = np.atleast_2d(np.asarray(Y, dtype=float))
    p = model.p
    S = np.array([p[L.S1], p[L.S2], p[L.S3]])
    G = Y[:, 3:6]
    F = np.sum(np.cross(Y[:, 0:3] + S, G) ** 2, axis=1)
    eps = float(p[L.BRUN])
    if eps:
        J = _ball_J(model)
        F = F - eps * np.prod(J) * np.sum(G * G / J, axis=1)
    return F


def rubber_routh_F(model: Model, Y) -> np.ndarray:
    """F = N(gamma) omega3 of a rubber body of revolution (I1 = I2) on a plane, with Koiller's
    'nose' function N^2 = I1 g3^2 + I3 (g1^2 + g2^2) + m (r, gamma)^2 (rubber_exact.py
    routh_nose_squared, routh_integral_residual)."""
    Y = np.atleast_2d(np.asarray(Y, dtype=float))
    p = model.p
    W, R = _kinematics(model, Y)
    G = Y[:, 3:6]
    N2 = (p[L.I1] * G[:, 2] ** 2 + p[L.I3] * (G[:, 0] ** 2 + G[:, 1] ** 2)
          + p[L.MASS] * np.sum(R * G, axis=1) ** 2)
    return np.sqrt(N2) * W[:, 2]


def rubber_shell_F(model: Model, Y) -> np.ndarray:
    """F = P / Q of the rubber ball rolling as a shell over a fixed ball of half its radius
    (k R = 2): P = sum P_ik omega_i^2 g_k^2, Q = (gamma, J^-1 gamma) (rubber_exact.py
    shell_integral_P, shell_integral_residual)."""
    Y = np.atleast_2d(np.asarray(Y, dtype=float))
    J1, J2, J3 = _ball_J(model)
    P = np.array([[J1 * J3 * (J1 - J3), J1 * J3 * (J1 - J3), J1 * J2 * (J1 - J3)],
                  [J2 * J3 * (J2 - J3), J2 * J3 * (J2 - J3), J1 * J2 * (J2 - J3)],
                  [0.0, 0.0, J3 * (J1 - J3) * (J2 - J3)]])
    W, _ = _kinematics(model, Y)
    G = Y[:, 3:6]
    Pv = np.einsum("ni,ik,nk->n", W ** 2, P, G ** 2)
    return Pv / np.sum(G * G / np.array([J1, J2, J3]), axis=1)


# name -> (what a reader calls it, its function)
RUBBER = {
    "spin": ("(ω, γ), the spin about the normal", spin),
    "gamma_norm_defect": ("|γ| − 1", gamma_norm_defect),
    "rubber_ball_F": ("F = |M × γ|²", rubber_ball_F),
    "rubber_routh_F": ("F = N(γ) ω₃", rubber_routh_F),
    "rubber_shell_F": ("F = P / Q (k R = 2)", rubber_shell_F),
}

# the rubber cases' integrals beyond the energy (the rubber tables' `integrals` cells), and
# the parameters that must be zero for each: the tables prove the ball's F with a gyrostat or
# with a Brun field, not with both
RUBBER_INTEGRALS = {
    "rubber-plane/chaplygin-ball": (("rubber_ball_F", ()),),
    "rubber-plane/routh-ball": (("rubber_routh_F", ("S3", "eps")),),
    "rubber-plane/body-of-revolution": (("rubber_routh_F", ("S3", "eps")),),
    "rubber-plane/ellipsoid-of-revolution": (("rubber_routh_F", ("S3", "eps")),),
    "rubber-plane/round-disk": (("rubber_routh_F", ("S3", "eps")),),
    "rubber-sphere/shell-over-half-ball": (("rubber_shell_F", ("S1", "S2", "S3")),),
}


def rubber_integrals(case_id: str, params: dict) -> list[str]:
    """The names (RUBBER) of the integrals beyond the energy that the rubber case carries
    with these parameters."""
    out = []
    for name, zero in RUBBER_INTEGRALS.get(case_id, ()):
        if all(float(params.get(z, 0.0) or 0.0) == 0.0 for z in zero):
            if name == "rubber_ball_F" and any(params.get(s) for s in ("S1", "S2", "S3")) \
                    and params.get("eps"):
                continue
            out.append(name)
    return out


def series(model: Model, Y, names) -> dict[str, np.ndarray]:
    """The named quantities (RUBBER) along the rows of Y; an unknown name raises KeyError
    with the known ones."""
    unknown = [n for n in names if n not in RUBBER]
    if unknown:
        raise KeyError(f"unknown quantities {unknown}; known: {', '.join(RUBBER)}")
    return {n: RUBBER[n][1](model, Y) for n in names}
