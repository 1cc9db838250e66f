"""The rubber cases: which body, on which support, with which parameters.

A rubber body rolls without slipping and without spinning about the normal: the marble
constraint v_Q = 0 plus (omega, gamma) = 0. The bodies and surfaces are the project's
(solvers/models/cases.yaml, CONVENTIONS.md): gamma is the unit normal pointing from the body
into the support, r(gamma) runs from the centre of mass G to the contact point, k is the
signed curvature (k = 0 plane, k < 0 outside a fixed ball of radius 1/|k|, k > 0 inside a
cavity of radius 1/k).

Two independent descriptions of the same surface are given, so the two derivations of the
equations (rubber_newton.py, rubber_lagrange.py) share no geometry code:

- `r_paper(g)`: the support point summed from the paper's per-body formulas
  ((2.28) ball, (2.39) ellipsoid, (2.15) disk), complex-safe so that J = dr/dgamma can be
  taken by complex step;
- `support_grad_hess(g)`: r = grad h and J = Hess h of the support function
  h = sqrt(g.B g) + c |g| + d sqrt(g1^2 + g2^2) + (a, g), differentiated by hand.

This module knows nothing of integrators, kernels or the web app. Bad input raises
solvers.errors.InputError and builds nothing.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from solvers.errors import InputError
from solvers.kernels import layout as L


@dataclass(frozen=True)
class RubberBody:
    """One rubber case's parameters. Inertia about G in principal axes, mass m, gravity g
    (plane only: U = m g (r, gamma)), Brun field eps (U = eps (I gamma, gamma) / 2), gyrostat
    S, signed curvature k. Surface: B (ellipsoid part, diagonal), c (ball part), d (disk
    edge radius), a (offset from G of the surface's centre)."""

    I: tuple[float, float, float]
    m: float
    k: float = 0.0
    g: float = 0.0
    eps: float = 0.0
    S: tuple[float, float, float] = (0.0, 0.0, 0.0)
    B: tuple[float, float, float] = (0.0, 0.0, 0.0)
    c: float = 0.0
    d: float = 0.0
    a: tuple[float, float, float] = (0.0, 0.0, 0.0)
    title: str = ""
    tags: tuple[str, ...] = field(default_factory=tuple)

    def __post_init__(self):
        if not self.m > 0:
            raise InputError(f"m = {self.m!r}: the mass must be positive")
        if not all(v > 0 for v in self.I):
            raise InputError(f"I = {self.I!r}: principal moments must be positive")
        if any(v < 0 for v in self.B) or self.c < 0 or self.d < 0:
            raise InputError("B, c, d must be >= 0: they are semi-axes and radii")
        if not (any(self.B) or self.c or self.d):
            raise InputError("the body has no surface: give B, c or d")
        if self.k != 0.0 and (self.g != 0.0 or self.eps != 0.0):
            raise InputError("a potential on a sphere is not modelled for rubber bodies: "
                             "set g = 0 and eps = 0 when k != 0")

    # -- the paper's per-body formulas (used by the Newton-Euler derivation) ---------
    def r_paper(self, g):
        """Support point r(gamma); complex-safe (the type follows gamma)."""
        r = np.array(self.a, dtype=complex if np.iscomplexobj(g) else float) + 0.0 * g
        if any(self.B):
            Bg = np.array(self.B) * g
            r = r + Bg / np.sqrt(g @ Bg)                             # (2.39)
        if self.c:
            r = r + self.c * g / np.sqrt(g @ g)                      # (2.28)
        if self.d:
            s = np.sqrt(g[0] ** 2 + g[1] ** 2)
            r = r + self.d * np.array([g[0] / s, g[1] / s, 0.0 * s])  # (2.15)
        return r

    def jacobian_cs(self, g, h=1e-30):
        """J = dr/dgamma by complex step of r_paper."""
        g = np.asarray(g, dtype=float)
        J = np.empty((3, 3))
        for j in range(3):
            gc = g.astype(complex)
            gc[j] += 1j * h
            J[:, j] = self.r_paper(gc).imag / h
        return J

    # -- the support function (used by the Lagrange-d'Alembert derivation) ----------
    def support_grad_hess(self, g):
        """(r, J) = (grad h, Hess h) at gamma, written out by hand."""
        g = np.asarray(g)
        r = np.array(self.a, dtype=g.dtype) + 0.0 * g
        J = np.zeros((3, 3), dtype=g.dtype)
        if any(self.B):
            b = np.array(self.B)
            q = np.sqrt(np.sum(b * g * g))
            r = r + b * g / q
            J = J + np.diag(b) / q - np.outer(b * g, b * g) / q ** 3
        if self.c:
            n = np.sqrt(np.sum(g * g))
            r = r + self.c * g / n
            J = J + self.c * (np.eye(3) / n - np.outer(g, g) / n ** 3)
        if self.d:
            s = np.sqrt(g[0] ** 2 + g[1] ** 2)
            u = np.array([g[0], g[1], 0.0 * s])
            r = r + self.d * u / s
            P = np.diag([1.0, 1.0, 0.0])
            J = J + self.d * (P / s - np.outer(u, u) / s ** 3)
        return r, J


def _tup(v, n=3):
    v = tuple(float(x) for x in v)
    if len(v) != n:
        raise InputError(f"{v!r}: expected {n} numbers")
    return v


# The rubber cases: the bodies of Tables 1 and 2 with the no-spin constraint added.
# Parameters are demonstration values (dimensionless); every case also takes others.
CASES: dict[str, dict] = {
    "rubber-plane/chaplygin-ball": dict(
        title="Rubber Chaplygin ball (balanced, dynamically nonsymmetric) on a plane",
        I=(1.0, 2.0, 2.5), m=1.0, c=1.0),
    "rubber-plane/unbalanced-ball": dict(
        title="Rubber unbalanced ball on a plane (centre of mass off the centre)",
        I=(1.0, 2.0, 2.5), m=1.0, c=1.0, a=(0.1, 0.2, -0.15), g=1.0),
    "rubber-plane/routh-ball": dict(
        title="Rubber Routh ball (I1 = I2, centre of mass on the symmetry axis)",
        I=(2.0, 2.0, 3.0), m=1.0, c=1.0, a=(0.0, 0.0, 0.3), g=1.0),
    "rubber-plane/body-of-revolution": dict(
        title="Rubber body of revolution (ellipsoid of revolution rounded by a ball)",
        I=(1.0, 1.0, 1.5), m=1.0, B=(1.0, 1.0, 0.25), c=0.2, a=(0.0, 0.0, 0.1), g=1.0),
    "rubber-plane/ellipsoid-of-revolution": dict(
        title="Rubber ellipsoid of revolution (Kilin-Pivovarova setting)",
        I=(1.0, 1.0, 1.5), m=1.0, B=(1.0, 1.0, 0.25), g=1.0),
    "rubber-plane/round-disk": dict(
        title="Rubber round disk with a sharp edge",
        I=(0.25, 0.25, 0.5), m=1.0, d=1.0, g=1.0),
    "rubber-plane/spherical-inertia": dict(
        title="Rubber body with spherical inertia I = mu E (triaxial ellipsoid, offset)",
        I=(1.0, 1.0, 1.0), m=1.0, B=(1.0, 2.0, 3.0), a=(0.05, -0.1, 0.2), g=1.0),
    "rubber-plane/ellipsoid": dict(
        title="Rubber triaxial ellipsoid, dynamically nonsymmetric",
        I=(1.0, 1.5, 2.0), m=1.0, B=(1.0, 2.0, 3.0), g=1.0),
    "rubber-sphere/ball-over": dict(
        title="Rubber Chaplygin ball over a fixed sphere (k < 0)",
        I=(1.0, 2.0, 2.5), m=1.0, c=1.0, k=-0.5),
    "rubber-sphere/ball-inside": dict(
        title="Rubber Chaplygin ball inside a spherical cavity (k > 0)",
        I=(1.0, 2.0, 2.5), m=1.0, c=1.0, k=0.4),
    "rubber-sphere/shell-over-half-ball": dict(
        title="Rubber Chaplygin ball of twice the radius of a fixed internal ball (k R = 2)",
        I=(1.0, 2.0, 2.5), m=1.0, c=1.0, k=2.0),
    "rubber-sphere/unbalanced-ball": dict(
        title="Rubber unbalanced ball over a fixed sphere (no potential)",
        I=(1.0, 2.0, 2.5), m=1.0, c=1.0, a=(0.1, 0.2, -0.15), k=-0.5),
}


def from_vector(p) -> RubberBody:
    """The RubberBody of a kernel parameter vector p (solvers/kernels/layout.py), as
    solvers.models.cases.build fills it for a rubber case: the NumPy derivations then run
    the registry's cases (simulate's reference route, the comparison tests)."""
    p = [float(x) for x in p]
    if any(p[s] != 0.0 for s in (L.B12, L.B13, L.B23)) or p[L.FLAT_Z] != 0.0:
        raise InputError("only principal-axes ellipsoids, balls and disks are rubber bodies here")
    return RubberBody(I=tuple(p[L.I1:L.I3 + 1]), m=p[L.MASS], k=p[L.CURV], g=p[L.GRAV],
                      eps=p[L.BRUN], S=tuple(p[L.S1:L.S3 + 1]),
                      B=(p[L.B11], p[L.B22], p[L.B33]), c=p[L.BALL_C], d=p[L.DISK_D],
                      a=tuple(p[L.A1:L.A3 + 1]))


def body(case_id: str, **override) -> RubberBody:
    """The RubberBody of a named case, with any parameter overridden."""
    if case_id not in CASES:
        raise InputError(f"unknown rubber case {case_id!r}; known: {sorted(CASES)}")
    prm = dict(CASES[case_id])
    unknown = set(override) - set(RubberBody.__dataclass_fields__)
    if unknown:
        raise InputError(f"unknown parameter(s) {sorted(unknown)} for {case_id!r}")
    prm.update(override)
    for key in ("I", "S", "B", "a"):
        if key in prm:
            prm[key] = _tup(prm[key])
    return RubberBody(**prm)
