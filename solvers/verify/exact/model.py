"""The rolling field and the paper's named quantities in exact rational arithmetic.

`ExactParams` answers the same names as solvers.verify.params.Params (I, m, R, a, b, S, g,
eps, z, D, mu, lam, k, p, r, J, contact_inertia, omega) with `Jet`s, so the formulas of
solvers/verify/formulas run unchanged on object arrays. `field` is the right-hand side of
(1.1)-(1.3) (MODEL_FULL) and (3.16)-(3.17) (MODEL_FLAT) written after
solvers/models/reference.py, with r(gamma) and J = Hess h in closed form from the support
function (solvers/kernels/support.py), so no derivative of r is ever approximated.
"""

import numpy as np

from solvers.kernels import layout as L
from solvers.models.reduced_systems import profile, rev_body, rho0
from solvers.verify.exact.jet import Jet
from solvers.verify.exact.linalg import solve
from solvers.verify.exact.rational import NotRational

E3 = np.eye(3, dtype=int).astype(object)


def _cross(a, b):
    return np.array([a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2],
                     a[0] * b[1] - a[1] * b[0]], dtype=object)


def support(p, g):
    """(r, J) of h(gamma) = sqrt(gamma.B gamma) + c |gamma| + d sqrt(g1^2+g2^2) + (a, gamma)
    at gamma = g (object arrays of jets); every square root must come out rational."""
    r = np.array([p[L.A1], p[L.A2], p[L.A3]], dtype=object) + 0 * g[0]
    J = np.zeros((3, 3), dtype=object) + 0 * g[0]
    B = np.array([[p[L.B11], p[L.B12], p[L.B13]], [p[L.B12], p[L.B22], p[L.B23]],
                  [p[L.B13], p[L.B23], p[L.B33]]], dtype=object)
    if any(b != 0 for b in B.flat):
        Bg = B @ g
        iq = 1 / (g @ Bg).sqrt()
        r = r + Bg * iq
        J = J + B * iq - np.outer(Bg, Bg) * iq ** 3
    c = p[L.BALL_C]
    if c != 0:
        ci = c / (g @ g).sqrt()
        r = r + ci * g
        J = J + ci * E3 - np.outer(g, g) * (ci ** 3 / c ** 2)
    d = p[L.DISK_D]
    if d != 0:
        s = (g[0] * g[0] + g[1] * g[1]).sqrt()
        di, di3 = d / s, d / s ** 3
        r = r + np.array([di * g[0], di * g[1], 0 * s], dtype=object)
        J[0, 0] = J[0, 0] + di - di3 * g[0] * g[0]
        J[1, 1] = J[1, 1] + di - di3 * g[1] * g[1]
        J[0, 1] = J[0, 1] - di3 * g[0] * g[1]
        J[1, 0] = J[0, 1]
    return r, J


class ExactParams:
    """Duck-typed solvers.verify.params.Params over exact jets."""

    def __init__(self, model, p, extra):
        self.model = model          # the float Model: codes, case, names
        self.p = p                  # object array of Jets, layout solvers.kernels.layout
        self.extra = extra          # {"mu": Jet, "lambda": Jet} when the case has them

    I = property(lambda s: np.array(s.p[L.I1:L.I3 + 1], dtype=object))
    m = property(lambda s: s.p[L.MASS])
    k = property(lambda s: s.p[L.CURV])
    R = property(lambda s: s.p[L.BALL_C] if s.p[L.BALL_C] != 0 else s.p[L.DISK_D])
    a = property(lambda s: np.array(s.p[L.A1:L.A3 + 1], dtype=object))
    b = property(lambda s: np.array([s.p[L.B11], s.p[L.B22], s.p[L.B33]], dtype=object))
    S = property(lambda s: np.array(s.p[L.S1:L.S3 + 1], dtype=object))
    g = property(lambda s: s.p[L.GRAV])
    eps = property(lambda s: s.p[L.BRUN])
    z = property(lambda s: s.p[L.FLAT_Z])
    D = property(lambda s: s.m * s.R ** 2)
    mu = property(lambda s: s.extra.get("mu"))
    lam = property(lambda s: s.extra.get("lambda"))

    def r(self, gamma):
        return support(self.p, np.asarray(gamma, dtype=object))[0]

    def J(self, gamma):
        return support(self.p, np.asarray(gamma, dtype=object))[1]

    def contact_inertia(self, r):
        r = np.asarray(r, dtype=object)
        return np.diag(self.I) + self.m * ((r @ r) * E3 - np.outer(r, r))

    def omega(self, M, gamma_or_r):
        r = gamma_or_r if self.model.model == L.MODEL_FLAT else self.r(gamma_or_r)
        return solve(self.contact_inertia(r), M)


def field(P: ExactParams, y):
    """dy/dt, exact, for MODEL_FULL (M, gamma) and MODEL_FLAT (M, r1, r2)."""
    p = P.p
    m, k = P.m, P.k
    S = P.S
    M = np.asarray(y[:3], dtype=object)
    if P.model.model == L.MODEL_FLAT:
        r = np.array([y[3], y[4], P.z + 0 * y[3]], dtype=object)
        w = solve(P.contact_inertia(r), M)
        rd = np.array([w[1], -w[0], 0 * w[0]], dtype=object) / k        # (3.17), k < 0
        Md = _cross(M + S, w) + m * _cross(rd, _cross(w, r))
        return np.concatenate([Md, rd[:2]])
    if P.model.model != L.MODEL_FULL:
        raise NotRational(f"no exact field for model {P.model.model}")
    g = np.asarray(y[3:6], dtype=object)
    r, J = support(p, g)
    w = solve(P.contact_inertia(r), M)
    gd = solve(E3 - k * J, _cross(g, w))
    rd = J @ gd
    dU = m * P.g * (r + J.T @ g) + P.eps * P.I * g
    MQ = _cross(g, solve(E3 - k * J.T, dU))
    Md = _cross(M + S, w) + m * _cross(rd, _cross(w, r)) + MQ
    return np.concatenate([Md, gd])


def jet_const(x):
    return Jet.const(x)


def to_reduced(p, y):
    """(M, gamma) -> (gamma3, K1, K2, K3) of solvers.models.reduced_systems.to_reduced ((2.5) /
    (3.3)), with this module's exact support function in place of the compiled one."""
    b = rev_body(p)
    M, g = np.asarray(y[:3], dtype=object), np.asarray(y[3:6], dtype=object)
    u = g[2]
    r, _ = support(p, g)
    f1 = profile(b.prof, u)[0]
    IQ = np.diag([b.I1, b.I1, b.I3]) + b.m * ((r @ r) * E3 - np.outer(r, r))
    w = solve(IQ, M)
    K1 = (M @ r) * (1 - b.k * f1) / f1
    K2 = w[2] / rho0(b, u)
    K3 = (M[1] * g[0] - M[0] * g[1]) / np.sqrt((1 - u * u) * (b.I1 + b.m * (r @ r)))
    return np.array([u, K1, K2, K3], dtype=object)
