"""Bodies of revolution: the support family of `solvers.kernels.support` on the axis.

For a body whose surface and central ellipsoid of inertia are coaxial surfaces of
revolution about e3, the support function restricted to the unit sphere depends on
u = gamma3 only:

    phi(u) = sqrt(b1 (1 - u^2) + b3 u^2) + c + d sqrt(1 - u^2) + a u

(B = diag(b1, b1, b3), ball part c, disk part d, centre offset a along the axis).
Since h is homogeneous of degree one, h(g) = |g| phi(g3/|g|) and r = grad h gives the
paper's (2.1), r = (f1 g1, f1 g2, f2), with

    f1 = phi - u phi',        f2 = u phi + (1 - u^2) phi'.

Then f1' = -u phi'' and f2' = f1 + (1 - u^2) phi'' = f1 - (1 - u^2)/u f1', which is
(2.2) identically (the meridian condition). Per part:
  ellipsoid  f1 = b1/sqrt(q), f2 = b3 u/sqrt(q), q = b1 (1-u^2) + b3 u^2    (2.39)
  ball       f1 = c,          f2 = c u                                      (2.18)
  disk       f1 = d/sqrt(1-u^2), f2 = 0                                     (2.15)
  offset     f1 = 0,          f2 = a

All functions accept real or complex u (complex step), scalars or arrays.
"""

from dataclasses import dataclass

import numpy as np

from solvers.kernels import layout as L
from solvers.kernels.support import support


@dataclass(frozen=True)
class Profile:
    """Parameters of phi read from p: b1, b3 (ellipsoid), c (ball), d (disk), a (axis)."""

    b1: float
    b3: float
    c: float
    d: float
    a: float

    @classmethod
    def from_params(cls, p):
        check_revolution(p)
        return cls(float(p[L.B11]), float(p[L.B33]), float(p[L.BALL_C]),
                   float(p[L.DISK_D]), float(p[L.A3]))


def check_revolution(p, tol=0.0):
    """Raise ValueError unless p describes a body of revolution about e3 (I1 = I2,
    B = diag(b1, b1, b3), a and S on the axis)."""
    bad = []
    if abs(p[L.I1] - p[L.I2]) > tol:
        bad.append("I1 != I2")
    if abs(p[L.B11] - p[L.B22]) > tol:
        bad.append("B11 != B22")
    for name in ("B12", "B13", "B23", "A1", "A2", "S1", "S2"):
        if abs(p[getattr(L, name)]) > tol:
            bad.append(f"{name} != 0")
    if bad:
        raise ValueError("not a body of revolution: " + ", ".join(bad))


def phi_derivs(prof, u):
    """phi, phi', phi'', phi''' at u (closed form, per part)."""
    u = np.asarray(u)
    z = 0.0 * u
    ph, d1, d2, d3 = z + prof.c + prof.a * u, z + prof.a, z, z
    if prof.b1 != 0.0 or prof.b3 != 0.0:
        e = prof.b3 - prof.b1
        q = prof.b1 + e * u * u
        sq = np.sqrt(q)
        ph = ph + sq
        d1 = d1 + e * u / sq
        d2 = d2 + e * prof.b1 / (q * sq)
        d3 = d3 - 3.0 * e * e * prof.b1 * u / (q * q * sq)
    if prof.d != 0.0:
        s = np.sqrt(1.0 - u * u)
        ph = ph + prof.d * s
        d1 = d1 - prof.d * u / s
        d2 = d2 - prof.d / s**3
        d3 = d3 - 3.0 * prof.d * u / s**5
    return ph, d1, d2, d3


def phi(prof, u):
    return phi_derivs(prof, u)[0]


def profile(prof, u):
    """f1, f2 and their first and second derivatives in u = gamma3:
    returns (f1, f2, f1', f2', f1'', f2'')."""
    ph, d1, d2, d3 = phi_derivs(prof, u)
    u = np.asarray(u)
    f1 = ph - u * d1
    f2 = u * ph + (1.0 - u * u) * d1
    f1p = -u * d2
    f2p = f1 + (1.0 - u * u) * d2
    f1pp = -d2 - u * d3
    f2pp = -3.0 * u * d2 + (1.0 - u * u) * d3
    return f1, f2, f1p, f2p, f1pp, f2pp


def f1(prof, u):
    return profile(prof, u)[0]


def f2(prof, u):
    return profile(prof, u)[1]


def meridian_residual(prof, u):
    """(2.2): f2' - (f1 - (1 - u^2)/u f1'); zero for every profile of the family."""
    f1_, _, f1p, f2p, _, _ = profile(prof, u)
    u = np.asarray(u)
    return f2p - (f1_ - (1.0 - u * u) / u * f1p)


def support_residual(p, gamma):
    """max |r_kernel(gamma) - (f1 g1, f1 g2, f2)| at a unit gamma ((2.1) vs support.py)."""
    prof = Profile.from_params(p)
    g = np.asarray(gamma, dtype=float)
    r = np.empty(3)
    J = np.empty((3, 3))
    support(p, g, r, J)
    f1_, f2_ = profile(prof, g[2])[:2]
    return float(np.max(np.abs(r - np.array([f1_ * g[0], f1_ * g[1], f2_]))))
