"""Bodies: how a case's named parameters become the kernel's parameter vector.

Each body kind fills the support-function slots of `p` (solvers/kernels/support.py) and
the inertia; `surface_checks` and `state_checks` reject bodies and states the equations
cannot describe. Bodies know nothing of integrators or the web app.
"""

import math

import numpy as np

from solvers.errors import InputError
from solvers.kernels import layout as L
from solvers.kernels.support import FLAT_DISK, support

STATE_LABELS = {
    L.MODEL_FULL: ("M1", "M2", "M3", "g1", "g2", "g3"),
    L.MODEL_FLAT: ("M1", "M2", "M3", "r1", "r2"),
}


def _positive(params, *names):
    for n in names:
        if not params[n] > 0:
            raise InputError(f"{n} = {params[n]!r}: must be positive")


# The lower bounds fill_body checks, per body kind: one table for the check and for what
# GET /api/cases publishes as each parameter's range (param_bounds).
POSITIVE = {"ball": ("R",), "routh": ("R",), "disk": ("R",), "ellipsoid": ("b1", "b2", "b3"),
            "revolution": ("b1", "b3"), "general": ("b1", "b2", "b3"),
            "rattleback": ("b1", "b2", "b3"), "flat": ()}
NON_NEGATIVE = {"revolution": ("c",), "general": ("c",)}
# the upper bounds, which solvers.models.cases.build checks: a flat base rolls on the
# outside of a fixed ball, k = -1/R0 < 0
NEGATIVE = {"flat": ("k",)}


def param_upper_bounds(kind: str) -> dict[str, dict]:
    """The parameters of a body that have an upper bound: name -> {"max": 0.0,
    "max_inclusive": False}."""
    return {n: {"max": 0.0, "max_inclusive": False} for n in NEGATIVE.get(kind, ())}


def param_bounds(kind: str, symmetry: str) -> dict[str, dict]:
    """The parameters of a body that have a lower bound, as checked by fill_body and
    fill_inertia: name -> {"min": 0.0, "min_inclusive": bool}. The conditions between
    parameters (the triangle inequality, mu + lambda m b_i > 0, the fit of the body to
    the support) are said in words by the glossary's `range`."""
    pos = ["m", *POSITIVE.get(kind, ())]
    if symmetry == "spherical":
        pos.append("mu")
    elif symmetry == "axial":             # I2 must equal I1 (fill_inertia), no bound of its own
        pos += ["I1", "I3"]
    elif kind != "ellipsoid":
        pos += ["I1", "I2", "I3"]
    out = {n: {"min": 0.0, "min_inclusive": False} for n in pos}
    out.update({n: {"min": 0.0, "min_inclusive": True} for n in NON_NEGATIVE.get(kind, ())})
    return out


def _non_negative(params, *names):
    for n in names:
        if params[n] < 0:
            raise InputError(f"{n} = {params[n]!r}: the rounding radius must be >= 0")


def _set_inertia(p, I1, I2, I3):
    p[L.I1], p[L.I2], p[L.I3] = I1, I2, I3


def rattleback_B(b1, b2, b3, delta):
    """(B11, B22, B33, B12, B13, B23) of B = R diag(b1, b2, b3) R^T, R the turn by delta
    about the body axis e3: the geometric axes of the ellipsoid (r, B^-1 r) = 1 turned
    against the principal axes of inertia (the rattleback, the paper's Celtic stone)."""
    c, s = math.cos(delta), math.sin(delta)
    return [b1 * c * c + b2 * s * s, b1 * s * s + b2 * c * c, b3, (b1 - b2) * c * s,
            0.0, 0.0]


def fill_body(kind, prm, p):
    """Write body `kind` with named parameters `prm` into p; return the model code."""
    if kind not in POSITIVE:
        raise InputError(f"unknown body kind {kind!r}")
    _positive(prm, *POSITIVE[kind])
    _non_negative(prm, *NON_NEGATIVE.get(kind, ()))
    if kind == "ball":                    # r = R gamma + a (2.28); a = 0: Chaplygin ball
        p[L.BALL_C] = prm["R"]
        p[L.A1:L.A3 + 1] = [prm.get("a1", 0.0), prm.get("a2", 0.0), prm.get("a3", 0.0)]
    elif kind == "routh":                 # f1 = R, f2 = R gamma3 + a (2.18)
        p[L.BALL_C] = prm["R"]
        p[L.A3] = prm["a"]
    elif kind == "disk":                  # f1 = R / sqrt(1 - gamma3^2), f2 = a (2.15)
        p[L.DISK_D] = prm["R"]
        p[L.A3] = prm["a"]
    elif kind == "ellipsoid":             # r = B gamma / sqrt(B gamma.gamma) (2.39)
        p[L.B11], p[L.B22], p[L.B33] = prm["b1"], prm["b2"], prm["b3"]
    elif kind == "revolution":            # ellipsoid of revolution + ball of radius c
        p[L.B11] = p[L.B22] = prm["b1"]
        p[L.B33] = prm["b3"]
        p[L.BALL_C] = prm["c"]
        p[L.A3] = prm["a"]
    elif kind == "general":               # ellipsoid + ball, any centre-of-mass offset
        p[L.B11], p[L.B22], p[L.B33] = prm["b1"], prm["b2"], prm["b3"]
        p[L.BALL_C] = prm["c"]
        p[L.A1:L.A3 + 1] = [prm["a1"], prm["a2"], prm["a3"]]
    elif kind == "rattleback":            # Celtic stone: ellipsoid turned against the inertia
        # axes by delta about e3, centre at a e3 from G
        p[L.B11:L.B23 + 1] = rattleback_B(prm["b1"], prm["b2"], prm["b3"], prm["delta"])
        p[L.A3] = prm["a"]
    else:                                 # flat: r = (r1, r2, z), gamma = e3 ((3.16)-(3.17))
        p[L.FLAT_Z] = prm.get("z", 0.0)
        return L.MODEL_FLAT
    return L.MODEL_FULL


def fill_inertia(kind, symmetry, prm, p, allow_any_inertia):
    """Inertia and mass; the ellipsoid of Table 1 has I = mu E + lambda m B (2.40)."""
    _positive(prm, "m")
    p[L.MASS] = prm["m"]
    if symmetry == "spherical":
        _positive(prm, "mu")
        _set_inertia(p, prm["mu"], prm["mu"], prm["mu"])
    elif kind == "ellipsoid":
        lam, mu, m = prm["lambda"], prm["mu"], prm["m"]
        I = [mu + lam * m * prm[b] for b in ("b1", "b2", "b3")]
        for i, v in enumerate(I, 1):
            if not v > 0:
                raise InputError(f"I{i} = mu + lambda m b{i} = {v!r}: must be positive")
        _set_inertia(p, *I)
    else:
        if symmetry == "axial":
            if prm.get("I2") is None:
                prm["I2"] = prm["I1"]
            elif prm["I2"] != prm["I1"]:
                raise InputError(f"I2 = {prm['I2']!r} but I1 = {prm['I1']!r}: this case needs "
                                 "axial dynamical symmetry I1 = I2")
        _positive(prm, "I1", "I2", "I3")
        _set_inertia(p, prm["I1"], prm["I2"], prm["I3"])
    I = [float(v) for v in p[L.I1:L.I3 + 1]]
    if not allow_any_inertia:
        for i in range(3):
            j, k = (i + 1) % 3, (i + 2) % 3
            if I[i] > I[j] + I[k] * (1 + 1e-12):
                raise InputError(
                    f"I{i + 1} = {I[i]!r} > I{j + 1} + I{k + 1} = {I[j] + I[k]!r}: principal "
                    "moments of a body satisfy the triangle inequality",
                    option="allow_any_inertia")


def tangent_fit(p, gamma):
    """Smallest eigenvalue of (E - k J) on the tangent plane at gamma: 1 - k * (largest
    radius of curvature) for k > 0. The body fits the sphere there iff it is positive."""
    k = p[L.CURV]
    if k == 0.0:
        return 1.0
    r = np.empty(3)
    J = np.empty((3, 3))
    support(p, np.asarray(gamma, dtype=float), r, J)
    g = np.asarray(gamma, dtype=float)
    # orthonormal tangent basis
    e = np.eye(3)[np.argmin(abs(g))]
    t1 = np.cross(g, e)
    t1 /= np.linalg.norm(t1)
    t2 = np.cross(g, t1)
    T = np.stack([t1, t2], axis=1)
    Jt = T.T @ J @ T
    return float(np.min(np.linalg.eigvalsh(np.eye(2) - k * 0.5 * (Jt + Jt.T))))


def check_state(model, p, state, *, shell=False):
    """Reject states the equations cannot describe; the message names the field."""
    if model == L.MODEL_FLAT:
        return
    g = np.asarray(state[3:6], dtype=float)
    n = math.hypot(*g)   # no overflow warning for huge components: inf, refused below
    if abs(n - 1.0) > 1e-9:
        raise InputError(f"|gamma| = {n!r}: gamma is a unit vector, |gamma| must be 1 "
                         "(normalise g1, g2, g3)")
    if p[L.DISK_D] != 0.0 and math.hypot(g[0], g[1]) < FLAT_DISK:
        raise InputError("gamma = (0, 0, +-1): the disk lies flat and its contact point is "
                         "undefined (tilt it: g1^2 + g2^2 > 0)")
    if not shell and p[L.CURV] != 0.0:
        fit = tangent_fit(p, g)
        if not fit > 0.0:
            raise InputError(
                f"1 - k * radius of curvature = {fit:.6g} <= 0 at the initial contact point: "
                f"the body does not fit the sphere of curvature k = {p[L.CURV]!r}")
