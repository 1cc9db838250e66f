"""Reduced variables and reduced (linear) systems of a body of revolution, section 2-3.

Maps (complex-safe: the tests differentiate them by complex step along the full field):
  to_reduced   (M, gamma) -> x = (gamma3, K1, K2, K3):  (2.5) on the plane, (3.3) on a
               sphere (K1 = (M, r)(1 - k f1)/f1, K2 = omega3/rho0), K3 as in (2.5) on both;
  from_reduced x -> (M, gamma) in the symmetry gauge gamma2 = 0, gamma1 = sqrt(1-gamma3^2);
  flat_reduced (M, r1, r2) -> (u, K1, K2), u = r1^2 + r2^2 (MODEL_FLAT, (3.22)).

Right-hand sides for scipy (`fun(t, y)` after `functools.partial(f, body)`): linear systems
dK/dgamma3 ((2.13), (2.32), (2.34), (3.4), (3.6), (3.14), (3.15)), dK/dtheta (2.16),
the disk's second-order equations in omega3(theta), state (omega3, d omega3/dtheta)
((2.17), (2.33), (3.5)), and dK/du of the flat base ((3.22), (3.26)).

Sign conventions (CONVENTIONS.md; measured, tests/test_reduced.py):
* the k of (3.2)-(3.15) is the signed curvature of CONVENTIONS.md (+1/R0 inside a cavity,
  -1/R0 outside a ball), i.e. (1.3)/(1.5) with k = 1/R0, not the "-/+" of (3.1) read with
  gamma pointing into the support (that reading makes (3.4) fail);
* the R of (3.22)/(3.26) is 1/k (signed), as in fields.py's (3.17).

Where the printed form fails, `*_printed` keeps it and the unsuffixed function is the
project's correction (derived from (2.5)/(3.3) and the full field, checked to round-off):
* (3.2): rho0 printed with I3 m f2^2 gamma3^2; correct is I3 m f2^2 (= m (r, I r), as the
  same line says and as (2.3));
* (3.14): the gyrostat term of the K1 equation has the wrong sign (-s ..., cf. (2.32));
* (3.15): the gyrostat term of the K1 equation carries a spurious factor R;
* (2.16): K1 and K2 are exchanged with respect to (2.5);
* (2.17), (2.33): the signs of the ctg(theta) omega3' and of the omega3 terms are flipped
  (the paper's own hypergeometric form below (2.17), and (3.5) at k = 0, agree with the
  correction);
* (3.5): the second term is ctg(theta)(1 + kR/(sin theta - kR)) d omega3/dtheta (the
  derivative is missing in print);
* (2.20): the closed form of omega3/rho carries rho^-1 for rho (it is then omega3/rho^3);
  (2.20) also exchanges the labels K1, K2 of (2.5);
* (3.22): the sign of the K2 equation ((3.26) at s = 0 and the integral (3.24) agree with
  the correction; the sign of the product of the two coefficients is reading-independent).
"""

from dataclasses import dataclass

import numpy as np

from solvers.kernels import layout as L
from solvers.kernels.support import support
from solvers.models.revolution import Profile, profile


@dataclass(frozen=True)
class RevBody:
    """The numbers of a body of revolution the reduced systems need (from p)."""

    I1: float
    I3: float
    m: float
    k: float
    s: float
    prof: Profile

    @classmethod
    def from_params(cls, p):
        prof = Profile.from_params(p)
        return cls(float(p[L.I1]), float(p[L.I3]), float(p[L.MASS]), float(p[L.CURV]),
                   float(p[L.S3]), prof)


def rev_body(b):
    """A RevBody, from one or from the parameter vector."""
    return b if isinstance(b, RevBody) else RevBody.from_params(b)


def rho0(b, u):
    """(2.3) / (3.2) (corrected): (I1 I3 + m I1 f1^2 (1-u^2) + m I3 f2^2)^-1/2."""
    f1, f2 = profile(b.prof, u)[:2]
    return 1.0 / np.sqrt(b.I1 * b.I3 + b.m * b.I1 * f1 * f1 * (1 - u * u)
                         + b.m * b.I3 * f2 * f2)


def rho0_printed_eq32(b, u):
    """(3.2) as printed: ... + m I3 f2^2 gamma3^2 (misprint, see module docstring)."""
    f1, f2 = profile(b.prof, u)[:2]
    return 1.0 / np.sqrt(b.I1 * b.I3 + b.m * b.I1 * f1 * f1 * (1 - u * u)
                         + b.m * b.I3 * f2 * f2 * u * u)


def kappa(b, u):
    """The paper's k of (2.6): sqrt((1 - gamma3^2)/(I1 + m r^2)) (reducing multiplier)."""
    f1, f2 = profile(b.prof, u)[:2]
    return np.sqrt((1 - u * u) / (b.I1 + b.m * (f1 * f1 * (1 - u * u) + f2 * f2)))


# --- maps ------------------------------------------------------------------------------
def to_reduced(p, y):
    """(M, gamma) -> (gamma3, K1, K2, K3), (2.5) (k = 0) / (3.3) (k != 0)."""
    b = rev_body(p)
    pv = np.asarray(p, dtype=float)
    M, g = y[:3], y[3:6]
    u = g[2]
    r = np.empty(3, dtype=y.dtype)
    J = np.empty((3, 3), dtype=y.dtype)
    support(pv, np.ascontiguousarray(g), r, J)
    f1 = profile(b.prof, u)[0]
    IQ = (np.diag([b.I1, b.I1, b.I3]).astype(y.dtype)
          + b.m * ((r @ r) * np.eye(3) - np.outer(r, r)))
    w = np.linalg.solve(IQ, M)
    K1 = (M @ r) * (1 - b.k * f1) / f1
    K2 = w[2] / rho0(b, u)
    K3 = (M[1] * g[0] - M[0] * g[1]) / np.sqrt((1 - u * u) * (b.I1 + b.m * (r @ r)))
    return np.array([u, K1, K2, K3])


def from_reduced(p, x):
    """(gamma3, K1, K2, K3) -> (M, gamma) with gamma = (sqrt(1-gamma3^2), 0, gamma3)."""
    b = rev_body(p)
    u, K1, K2, K3 = x
    sig = np.sqrt(1 - u * u)
    f1, f2 = profile(b.prof, u)[:2]
    Kp = K1 / (1 - b.k * f1)                      # (M, r)/f1
    M3 = (K2 / rho0(b, u) - b.m * f1 * f2 * Kp) / b.I1
    M1 = (Kp - f2 / f1 * M3) / sig
    M2 = K3 * np.sqrt(b.I1 + b.m * (f1 * f1 * sig * sig + f2 * f2))
    return np.array([M1, M2, M3, sig, 0.0 * u, u])


def flat_reduced(p, y):
    """MODEL_FLAT (M, r1, r2) -> (u, K1, K2): u = r1^2 + r2^2, K1 = (M, r),
    K2 = omega3/rho, rho = (I1 I3 + m (r, I r))^-1/2 ((3.21)-(3.22))."""
    I1, I3, m, z = p[L.I1], p[L.I3], p[L.MASS], p[L.FLAT_Z]
    M = y[:3]
    r = np.array([y[3], y[4], z + 0.0 * y[3]])
    IQ = np.diag([I1, I1, I3]).astype(y.dtype) + m * ((r @ r) * np.eye(3) - np.outer(r, r))
    w = np.linalg.solve(IQ, M)
    rho = 1.0 / np.sqrt(I1 * I3 + m * (I1 * (r[0] ** 2 + r[1] ** 2) + I3 * z * z))
    return np.array([r[0] ** 2 + r[1] ** 2, M @ r, w[2] / rho])


# --- the reduced field (2.6) (plane), its energy and bracket ---------------------------
def linear_coeffs(b, u):
    """c1 = I3 rho (1 - (f2/f1)'), c2 = m rho f1 (f1 - f2'): (2.13) / (2.8)."""
    f1, f2, f1p, f2p = profile(b.prof, u)[:4]
    rho = rho0(b, u)
    qp = (f2p * f1 - f2 * f1p) / (f1 * f1)
    return b.I3 * rho * (1 - qp), b.m * rho * f1 * (f1 - f2p)


def energy(b, x, U=None):
    """(2.7) in the expanded form m f2^2/I1 (K1 - K2/(rho m f1 f2))^2 =
    (m f2 K1 - K2/(rho f1))^2/(m I1) (regular at f2 = 0). U: callable of gamma3."""
    u, K1, K2, K3 = x
    f1, f2 = profile(b.prof, u)[:2]
    rho = rho0(b, u)
    T = (K1 * K1 - b.I3 / (b.m * f1 * f1) * K2 * K2
         + (b.m * f2 * K1 - K2 / (rho * f1)) ** 2 / (b.m * b.I1)) / (2 * b.I1 * (1 - u * u))
    return T + 0.5 * K3 * K3 + (0.0 if U is None else U(u))


def bracket(b, x):
    """Poisson tensor of (2.8) in x = (gamma3, K1, K2, K3) (4x4, antisymmetric)."""
    c1, c2 = linear_coeffs(b, x[0])
    P = np.zeros((4, 4), dtype=np.result_type(x[0], x[1], float))
    P[0, 3] = 1.0
    P[1, 3] = -c1 * x[2]
    P[2, 3] = -c2 * x[1]
    return P - P.T


# --- linear systems in gamma3 ------------------------------------------------------------
def eq2_5(b, u, K):
    """Plane: dK1/dg3 = -rho I3 (1 - (f2/f1)') K2, dK2/dg3 = -m rho f1 (f1 - f2') K1."""
    c1, c2 = linear_coeffs(b, u)
    return np.array([-c1 * K[1], -c2 * K[0]])


def eq2_20(b, u, K):
    """Plane, gyrostat s: (2.13) with -s and -m rho f1 f2 s."""
    c1, c2 = linear_coeffs(b, u)
    f1, f2 = profile(b.prof, u)[:2]
    return np.array([-c1 * K[1] - b.s, -c2 * K[0] - b.m * rho0(b, u) * f1 * f2 * b.s])


def eq2_24(b, u, K):
    """Routh ball (f1 = R, f2 = R g3 + a) with gyrostat: dK1 = -s, dK2 = -m rho R f2 s."""
    R, a = b.prof.c, b.prof.a
    return np.array([-b.s + 0.0 * K[0], -b.m * rho0(b, u) * R * (R * u + a) * b.s])


def _sphere_terms(b, u, rho=rho0):
    f1, f2, f1p, f2p = profile(b.prof, u)[:4]
    k, I1, I3, m = b.k, b.I1, b.I3, b.m
    r0 = rho(b, u)
    qp = (f2p * f1 - f2 * f1p) / (f1 * f1)
    sig = np.sqrt(1 - u * u)
    dsig = f1p * sig - f1 * u / sig                 # (f1 sqrt(1 - g3^2))'
    A = I3 * (1 - qp) + k * f1 * (I1 - I3) * (1 - k * f2p)
    B = k * m * r0 * I1 * f1 * f1 * (u * f2p + sig * dsig)
    C = m * f1 * (f1 - f2p - k * f1 * f2p)
    return f1, f2, f2p, r0, A, B, C


def eq3_3(b, u, K, rho=rho0):
    """Sphere (variables (3.3)): (1/rho0) K1' = -[I3(1-(f2/f1)') + k f1 (I1-I3)(1-k f2')] K2,
    ((1 - k f1)/rho0) K2' = -m f1 (f1 - f2' - k f1 f2') K1
                            + m k rho0 I1 f1^2 (g3 f2' + sqrt(1-g3^2)(f1 sqrt(1-g3^2))') K2.
    `rho` selects rho0 (rho0_printed_eq32 gives the printed reading of (3.2))."""
    f1, _, _, r0, A, B, C = _sphere_terms(b, u, rho)
    return np.array([-r0 * A * K[1], r0 / (1 - b.k * f1) * (B * K[1] - C * K[0])])


def _eq3_10(b, u, K, sign1):
    f1, f2, f2p, r0, A, B, C = _sphere_terms(b, u)
    k, s, m = b.k, b.s, b.m
    a1, a2 = 1 - k * f1, 1 - k * f2p
    return np.array([r0 * (-A * K[1] + sign1 * s / r0 * a2 * a1),
                     r0 / a1 * (B * K[1] - C * K[0] - s * m * f1 * f2 * a2 * a1)])


def eq3_10(b, u, K):
    """Sphere, gyrostat (corrected): the K1 equation has -s rho0^-1 (1-k f2')(1-k f1)."""
    return _eq3_10(b, u, K, -1.0)


def eq3_10_printed(b, u, K):
    """(3.14) as printed: +s rho0^-1 (1-k f2')(1-k f1) in the K1 equation."""
    return _eq3_10(b, u, K, +1.0)


def eq3_7(b, u, K):
    """Routh ball on a sphere: K1'/rho = -kR(I1-I3)(1-kR) K2, K2'/rho = k m R^3/(1-kR) K1."""
    R, k = b.prof.c, b.k
    r0 = rho0(b, u)
    return np.array([-r0 * k * R * (b.I1 - b.I3) * (1 - k * R) * K[1],
                     r0 * k * b.m * R**3 / (1 - k * R) * K[0]])


def _eq3_11(b, u, K, fac):
    R, a, k, s = b.prof.c, b.prof.a, b.k, b.s
    r0 = rho0(b, u)
    return np.array([r0 * (-k * R * (b.I1 - b.I3) * (1 - k * R) * K[1])
                     - fac * (1 - k * R) ** 2 * s,
                     r0 * (b.m * R**3 * k / (1 - k * R) * K[0]
                           - b.m * R * (1 - k * R) * (R * u + a) * s)])


def eq3_11(b, u, K):
    """Routh ball on a sphere with gyrostat (corrected): K1' has -(1-kR)^2 s."""
    return _eq3_11(b, u, K, 1.0)


def eq3_11_printed(b, u, K):
    """(3.15) as printed: K1' has -R (1-kR)^2 s."""
    return _eq3_11(b, u, K, b.prof.c)


# --- round disk: theta with gamma3 = cos(theta) -------------------------------------------
def _disk(b):
    return b.prof.d, b.prof.a, 1.0 / np.sqrt(b.I1 * b.I3 + b.m * (b.I1 * b.prof.d**2
                                                                   + b.I3 * b.prof.a**2))


def eq2_8(b, th, K):
    """Disk on the plane, d(K1, K2)/dtheta in the labels of (2.5) (corrected):
    dK1/dth = I3 rho (sin th + a/R cos th) K2, dK2/dth = rho m R^2/sin th K1."""
    R, a, rho = _disk(b)
    return np.array([b.I3 * rho * (np.sin(th) + a / R * np.cos(th)) * K[1],
                     rho * b.m * R * R / np.sin(th) * K[0]])


def eq2_8_printed(b, th, K):
    """(2.16) as printed (K1 and K2 exchanged with respect to (2.5))."""
    R, a, rho = _disk(b)
    return np.array([rho * b.m * R * R / np.sin(th) * K[1],
                     b.I3 * rho * (np.sin(th) + a / R * np.cos(th)) * K[0]])


def _eq2_21(b, th, w, sgn):
    R, a, rho = _disk(b)
    ct = np.cos(th) / np.sin(th)
    lam = rho * rho * b.m * R * (R + a * ct)
    return np.array([w[1], sgn * (ct * w[1] - lam * b.I3 * w[0]) + lam * b.s])


def eq2_21(b, th, w):
    """Disk, plane, gyrostat (corrected; s = 0 is (2.17)):
    w'' + ctg w' - rho^2 m R I3 (R + a ctg) w = s m R rho^2 (R + a ctg)."""
    return _eq2_21(b, th, w, -1.0)


def eq2_21_printed(b, th, w):
    """(2.33) as printed: w'' - ctg w' + m R I3 (R + a ctg) rho^2 w = s m R rho^2 (R + a ctg)."""
    return _eq2_21(b, th, w, +1.0)


def eq2_9(b, th, w):
    """Disk, plane (corrected): w'' + ctg w' - rho^2 m R (R + a ctg) I3 w = 0."""
    return _eq2_21(RevBody(b.I1, b.I3, b.m, b.k, 0.0, b.prof), th, w, -1.0)


def eq2_9_printed(b, th, w):
    """(2.17) as printed: w'' - ctg w' + rho^2 m R (R + a ctg) I3 w = 0."""
    return _eq2_21(RevBody(b.I1, b.I3, b.m, b.k, 0.0, b.prof), th, w, +1.0)


def _eq3_4(b, th, w, deriv):
    R, a, r0 = _disk(b)
    k, I1, I3 = b.k, b.I1, b.I3
    sn, ct = np.sin(th), np.cos(th) / np.sin(th)
    c1 = ct * (1 + k * R / (sn - k * R))
    c0 = r0 * r0 * b.m * R * I3 / (1 - k * R / sn) * (R + a * ct + k * R * R * (I1 - I3)
                                                     / (I3 * sn))
    return np.array([w[1], -c1 * (w[1] if deriv else w[0]) + c0 * w[0]])


def eq3_4(b, th, w):
    """Disk on a sphere (corrected): w'' + ctg (1 + kR/(sin - kR)) w'
    - rho0^2 m R I3/(1 - kR/sin) (R + a ctg + k R^2 (I1-I3)/(I3 sin)) w = 0."""
    return _eq3_4(b, th, w, True)


def eq3_4_printed(b, th, w):
    """(3.5) as printed: the ctg(...) term multiplies w, not w'."""
    return _eq3_4(b, th, w, False)


# --- flat base on a sphere, u = r1^2 + r2^2, R = 1/k ------------------------------------
def _flat(p):
    I1, I3, m, z = p[L.I1], p[L.I3], p[L.MASS], p[L.FLAT_Z]
    R = 1.0 / p[L.CURV]
    return I1, I3, m, z, R


def eq3_21(p, u, K):
    """2R dK1/du = (I1-I3)/sqrt(I3(I1+m z^2) + I1 m u) K2 - s,
    2R dK2/du = -m (K1 + z s)/sqrt(...)."""
    I1, I3, m, z, R = _flat(p)
    s = p[L.S3]
    sq = np.sqrt(I3 * (I1 + m * z * z) + I1 * m * u)
    return np.array([((I1 - I3) / sq * K[1] - s) / (2 * R), -m * (K[0] + z * s) / sq / (2 * R)])


def eq3_19(p, u, K):
    """Flat base without gyrostat (corrected = (3.26) at s = 0): dK2/du = -m K1/(2R sqrt)."""
    I1, I3, m, z, R = _flat(p)
    sq = np.sqrt(I3 * (I1 + m * z * z) + I1 * m * u)
    return np.array([(I1 - I3) / (2 * R * sq) * K[1], -m / (2 * R * sq) * K[0]])


def eq3_19_printed(p, u, K):
    """(3.22) as printed: dK2/du = +m K1/(2R sqrt(...))."""
    I1, I3, m, z, R = _flat(p)
    sq = np.sqrt(I3 * (I1 + m * z * z) + I1 * m * u)
    return np.array([(I1 - I3) / (2 * R * sq) * K[1], m / (2 * R * sq) * K[0]])


# --- the printed (2.6) in Python (the compiled field is solvers.kernels.reduced) -------
def field_eq2_star1(b, x, dU=0.0):
    """(2.6) as printed (plane, no gyrostat); dU = dU/dgamma3 at x[0]."""
    u, K1, K2, K3 = x
    f1, f2 = profile(b.prof, u)[:2]
    I1, I3, m = b.I1, b.I3, b.m
    rho, kap = rho0(b, u), kappa(b, u)
    c1, c2 = linear_coeffs(b, u)
    s2 = 1 - u * u
    k3 = (f2 * (f1 * s2 + u * f2) * (m * f1**2 * K1**2 + I3 * K2**2)
          + u * f1**2 * I1 * K1**2 - f1 * (f1 * s2 + 2 * u * f2) * K1 * K2 / rho
          + m * f1**2 * rho * f2 * s2 * (u * f1 * I1 - f2 * I3) * K1 * K2)
    return np.array([kap * K3, -kap * K3 * c1 * K2, -kap * K3 * c2 * K1,
                     -kap / (I1**2 * f1**2 * s2**2) * k3 - kap * dU])


# --- Routh ball on the plane (2.18): the integrals (2.20) -------------------------------
def routh_integrals(p, y):
    """(omega3/rho, (M, r)/R) of the Routh ball: (2.20) with its K1, K2 labels (exchanged
    with respect to (2.5)). omega3/rho = rho (m R^2 g3 (M,g) + I1 M3 + m a R ((M,g) + M3 g3)
    + m a^2 M3): the printed prefactor rho^-1 is a misprint (see routh_integrals_printed)."""
    b = rev_body(p)
    R, a = b.prof.c, b.prof.a
    M, g = y[:3], y[3:6]
    Mg = M @ g
    rho = rho0(b, g[2])
    br = (b.m * R * R * g[2] * Mg + b.I1 * M[2] + b.m * a * R * (Mg + M[2] * g[2])
          + b.m * a * a * M[2])
    return np.array([rho * br, Mg + a / R * M[2]])


def routh_integrals_printed(p, y):
    """(2.20) as printed: K1 = rho^-1 (...), which is omega3/rho^3, not an integral."""
    b = rev_body(p)
    I = routh_integrals(p, y)
    rho = rho0(b, y[5])
    return np.array([I[0] / rho**2, I[1]])
