"""Section 2, bodies on a plane other than the Chaplygin ball: the unbalanced ball (2.28) (and
its sphere version (3.12)), spherical inertia (2.30)-(2.31), the ellipsoid (2.39)-(2.41) and
(2.42), bodies of revolution (2.1)-(2.5), the disk (2.15), the Routh ball (2.19)-(2.20) and
the gyrostatic integrals (2.35)-(2.37) (Bobylev).

Shapes f1, f2 of a body of revolution come from the model's support function
(solvers.models.revolution.profile) unless the paper prints them (disk (2.15), ball (2.18)),
in which case the printed ones are used.
"""

import numpy as np

from solvers.models.revolution import Profile, profile
from solvers.verify.formulas.general import contact_inertia, dU, omega_of
from solvers.verify.registry import compares, corrected, formula

H = 1e-30


def _cstep(f, u):
    """df/du at a real u by complex step (used only inside identity comparisons, which are
    evaluated at real points)."""
    return np.asarray(f(u + 1j * H)).imag / H


def _prof(P):
    return Profile.from_params(P.p)


def _f(P, u):
    """(f1, f2, f1', f2') of the model's body of revolution at gamma3 = u."""
    return profile(_prof(P), u)[:4]


# --- unbalanced, dynamically nonsymmetric ball: (2.28), (2.29), (3.12) -----------------------

def _unbalanced(P, x, factor):
    M, g = x[:3], x[3:6]
    r = P.r(g)
    w = omega_of(P, M, r)
    rd = factor * np.cross(r - P.a, w)
    return np.concatenate([np.cross(M, w) + P.m * np.cross(rd, np.cross(w, r)), rd / P.R])


@formula("unbalanced_system")
def unbalanced_system(P, x):
    """(2.28): dM/dt = M x omega + m dr/dt x (omega x r), dr/dt = (r - a) x omega,
    r = R gamma + a (so dgamma/dt = dr/dt / R); no potential."""
    return _unbalanced(P, x, 1.0)


@formula("sphere_unbalanced_system")
def sphere_unbalanced_system(P, x):
    """(3.12): as (2.28) with dr/dt = (r - a) x omega / (1 - k R), k signed (CONVENTIONS.md)."""
    return _unbalanced(P, x, 1.0 / (1.0 - P.k * P.R))


@formula("unbalanced_F")
def unbalanced_f(P, x):
    """(2.29) / (3.13): F = M^2 - m r^2 (M, omega)."""
    M, g = x[:3], x[3:6]
    r = P.r(g)
    return M @ M - P.m * (r @ r) * (M @ omega_of(P, M, r))


# --- spherical tensor of inertia, (2.30)-(2.31) -------------------------------------------------

def _mu(P):
    return P.mu if P.mu is not None else P.I[0]


@formula("spherical_inertia_system")
def spherical_inertia_system(P, x):
    """(2.30) in (omega, gamma): (mu + m r^2) domega/dt = m (dr/dt + omega x r)(r, omega)
    - m omega (r, dr/dt) + gamma x dU/dgamma, dgamma/dt = gamma x omega, dr/dt = J dgamma/dt."""
    w, g = x[:3], x[3:6]
    r = P.r(g)
    gd = np.cross(g, w)
    rd = P.J(g) @ gd
    wd = (P.m * (rd + np.cross(w, r)) * (r @ w) - P.m * w * (r @ rd)
          + np.cross(g, dU(P, g))) / (_mu(P) + P.m * (r @ r))
    return np.concatenate([wd, gd])


@formula("invariant_relation")
def invariant_relation(P, x):
    """(domega/dt, r) = 0 along (2.30), as (lhs, rhs) = (sum of the positive products
    domega_i/dt r_i, minus the sum of the negative ones): the residual is then relative to the
    size of the terms. domega/dt from the printed (2.30)."""
    wd = spherical_inertia_system(P, x)[:3]
    t = wd * P.r(x[3:6])
    return np.sum(np.where(t > 0, t, 0.0)), -np.sum(np.where(t < 0, t, 0.0))


@formula("yaroschuk_density")
def yaroschuk_density(P, x):
    """(2.31) as printed: rho = (mu + r^2)^(3/2) in (omega, gamma) (no m)."""
    r = P.r(x[3:6])
    return (_mu(P) + r @ r) ** 1.5


@formula("yaroschuk_density_table")
def yaroschuk_density_table(P, x):
    """Table 1's measure cell of the spherical-inertia body as printed: rho = (mu + m r^2)^(3/2)
    in (omega, gamma); the table keeps the m that the text's (2.31) drops."""
    r = P.r(x[3:6])
    return (_mu(P) + P.m * (r @ r)) ** 1.5


@corrected("yaroschuk_density", "(μ + m r²)^(3/2): the mass is missing in eq2.19 (Table 1 "
           "prints it); = ρ_M det I_Q / μ with ρ_M = (μ + m r²)^(−1/2) of eq2.30")
def yaroschuk_density_corrected(P, x):
    r = P.r(x[3:6])
    return (_mu(P) + P.m * (r @ r)) ** 1.5


# --- ellipsoid: (2.39)-(2.41), (2.42); the Gauss map (1.4) -------------------------------------

def _B(P):
    return P.b


@formula("ellipsoid_r")
def ellipsoid_r(P, x):
    """(2.39): r = B gamma / sqrt(B gamma, gamma), B = diag(b1, b2, b3)."""
    Bg = _B(P) * x
    return Bg / np.sqrt(Bg @ x)


def _ellipsoid_normal(P, r):
    """-grad f / |grad f| for the ellipsoid f = 1 - (r, B^-1 r) (f > 0 inside)."""
    n = r / _B(P)
    return n / np.sqrt(n @ n)


@formula("gauss_map")
def gauss_map(P, x):
    """(1.4): gamma = -grad f / |grad f| at the model's support point r(gamma), for the
    ellipsoid with f = 1 - (r, B^-1 r). The printed minus sign needs f > 0 inside the body;
    with the usual f = (r, B^-1 r) - 1 (< 0 inside) -grad f/|grad f| is the inward normal,
    -gamma under CONVENTIONS.md."""
    return _ellipsoid_normal(P, P.r(x))


@compares("ellipsoid_r", "gauss_map")
def ellipsoid_r_vs_gauss_map(P, x, corrected=False):
    """r = (2.39) lies on (r, B^-1 r) = 1 and (1.4) gives back gamma there."""
    r = ellipsoid_r(P, x)
    return (np.concatenate([x, [r @ (r / _B(P))]]),
            np.concatenate([_ellipsoid_normal(P, r), [1.0]]))


@formula("ellipsoid_inertia")
def ellipsoid_inertia(P, x=None):
    """(2.40) (a condition on parameters): (I, mu E + lambda m B) as diagonals."""
    return P.I, P.mu + P.lam * P.m * _B(P)


@formula("ellipsoid_density")
def ellipsoid_density(P, x):
    """(2.41) (first form): rho = (mu + m r^2)^(-1/2), variables (M, gamma)."""
    r = P.r(x[3:6])
    return (_mu(P) + P.m * (r @ r)) ** -0.5


@compares("ellipsoid_density")
def ellipsoid_density_forms(P, x, corrected=False):
    """(2.41)'s two printed forms: mu + m r^2 = ((mu + m B) r, B^-1 r) on the ellipsoid."""
    r = P.r(x[3:6])
    B = _B(P)
    return _mu(P) + P.m * (r @ r), ((_mu(P) + P.m * B) * r) @ (r / B)


def _cyclic(I, b, j_of):
    """sum over cyclic (i, j, k) of I_i (b_j_of - b_k)."""
    s = 0.0
    for i, j, k in ((0, 1, 2), (1, 2, 0), (2, 0, 1)):
        s = s + I[i] * (b[{"i": i, "j": j}[j_of]] - b[k])
    return s


@formula("karapetyan_condition")
def karapetyan_condition(P, x=None):
    """(2.42) as printed: sum_ijk I_i (b_i - b_k) = 0, read over cyclic (i, j, k) (the sum
    over all permutations, 2 sum I_i b_i - ..., fails the same way). Returns the sum."""
    return _cyclic(P.I, _B(P), "i")


@corrected("karapetyan_condition", "sum over cyclic (i, j, k) of I_i (b_j - b_k) = 0, i.e. "
           "det[I_i, b_i, 1] = 0: the printed b_i must be b_j (this form holds for eq2.29, "
           "for b1 = b2 = b3 and for I1 = I2, b1 = b2, as the text says)")
def karapetyan_condition_corrected(P, x=None):
    return _cyclic(P.I, _B(P), "j")


# --- body of revolution on a plane: (2.1)-(2.5) -------------------------------------------------

@formula("revolution_r")
def revolution_r(P, x):
    """(2.1): r = (f1(gamma3) gamma1, f1(gamma3) gamma2, f2(gamma3)), f1, f2 of the model."""
    f1, f2 = _f(P, x[2])[:2]
    return np.array([f1 * x[0], f1 * x[1], f2])


@formula("meridian")
def meridian(P, x):
    """(2.2) for the model's meridian: (df2/dgamma3, f1 - (1 - gamma3^2)/gamma3 df1/dgamma3)."""
    u = x[0]
    f1, _, f1p, f2p = _f(P, u)
    return f2p, f1 - (1.0 - u * u) / u * f1p


def _meridian_sides(f1, f2, u):
    """(2.2)'s two sides for printed shape functions f1(u), f2(u) (complex step)."""
    return _cstep(f2, u), f1(u) - (1.0 - u * u) / u * _cstep(f1, u)


@compares("revolution_r", "meridian")
def revolution_r_vs_meridian(P, x, corrected=False):
    """r(gamma) of (2.1) has normal gamma, i.e. (dr, gamma) = 0 along the meridian direction
    t = d gamma/d theta (split as gamma3 dr3 = -(gamma1 dr1 + gamma2 dr2)), and (2.2) holds
    for the model's f1, f2 (f2' by complex step of f2, not the closed form)."""
    g = x
    s = np.sqrt(g[0] ** 2 + g[1] ** 2)
    t = np.array([g[0] * g[2] / s, g[1] * g[2] / s, -s])
    dr = revolution_r(P, g + 1j * H * t).imag / H
    lhs2, rhs2 = _meridian_sides(lambda u: _f(P, u)[0], lambda u: _f(P, u)[1], g[2])
    return np.array([g[2] * dr[2], lhs2]), np.array([-(g[0] * dr[0] + g[1] * dr[1]), rhs2])


def _shape_vs_meridian(P, x, shape):
    """A printed shape (f1, f2) is the model's meridian and satisfies (2.2)."""
    u = x[0]
    f1p, f2p = shape(P, x)
    f1m, f2m = _f(P, u)[:2]
    l2, r2 = _meridian_sides(lambda v: shape(P, [v])[0], lambda v: shape(P, [v])[1], u)
    return np.array([f1p, f2p, l2]), np.array([f1m, f2m, r2])


@formula("revolution_density")
def revolution_density(P, x):
    """(2.3) (first form): rho = 1/sqrt(I1 I3 + m (r, I r))."""
    r = P.r(x[3:6])
    return (P.I[0] * P.I[2] + P.m * (r @ (P.I * r))) ** -0.5


@compares("revolution_density")
def revolution_density_forms(P, x, corrected=False):
    """(2.3)'s two printed forms: I1 I3 + m (r, I r) = I1 I3 + I1 m f1^2 (1 - g3^2) + I3 m f2^2."""
    g = x[3:6]
    r = P.r(g)
    f1, f2 = _f(P, g[2])[:2]
    I1, I3, m = P.I[0], P.I[2], P.m
    return (I1 * I3 + m * (r @ (P.I * r)),
            I1 * I3 + I1 * m * f1**2 * (1 - g[2] ** 2) + I3 * m * f2**2)


@formula("det_IQ_axisymmetric")
def det_iq_axisymmetric(P, x):
    """Remark after (2.3): det I_Q = (I1 + m r^2)(I1 I3 + m (r, I r)) for I1 = I2."""
    r = P.r(x)
    lhs = np.linalg.det(contact_inertia(P, r))
    return lhs, (P.I[0] + P.m * (r @ r)) * (P.I[0] * P.I[2] + P.m * (r @ (P.I * r)))


@formula("symmetry_field")
def symmetry_field(P, x):
    """(2.4): v = M1 d/dM2 - M2 d/dM1 + gamma1 d/dgamma2 - gamma2 d/dgamma1 (a vector field)."""
    z = 0.0 * x[0]
    return np.array([-x[1], x[0], z, -x[4], x[3], z])


def _revolution_K_sides(P, x):
    M, g = x[:3], x[3:6]
    r = P.r(g)
    f1, f2 = _f(P, g[2])[:2]
    rho = revolution_density(P, x)
    w = omega_of(P, M, r)
    Mg = M[0] * g[0] + M[1] * g[1]
    K3 = (M[1] * g[0] - M[0] * g[1]) / np.sqrt((1 - g[2] ** 2) * (P.I[0] + P.m * (r @ r)))
    first = np.array([(M @ r) / f1, w[2] / rho, K3])
    second = np.array([Mg + f2 / f1 * M[2],
                       rho * (P.m * f1 * f2 * Mg + (P.I[0] + P.m * f2**2) * M[2]), K3])
    return first, second


@formula("revolution_K")
def revolution_k(P, x):
    """(2.5) (first forms): K1 = (M, r)/f1, K2 = omega3/rho, K3 = (M2 g1 - M1 g2) /
    sqrt((1 - g3^2)(I1 + m r^2))."""
    return _revolution_K_sides(P, x)[0]


@compares("revolution_K")
def revolution_k_forms(P, x, corrected=False):
    """(2.5)'s printed second forms of K1 and K2."""
    return _revolution_K_sides(P, x)


# --- round disk (2.15), Routh ball (2.18) / (2.19)-(2.20) ---------------------------------------

@formula("disk_shape")
def disk_shape(P, x):
    """(2.15): f1 = R / sqrt(1 - gamma3^2), f2 = a."""
    u = x[0]
    return np.array([P.R / np.sqrt(1 - u * u), P.a[2] + 0.0 * u])


@compares("disk_shape", "meridian")
def disk_shape_vs_meridian(P, x, corrected=False):
    return _shape_vs_meridian(P, x, disk_shape)


@formula("disk_density")
def disk_density(P, x):
    """Round disk: rho = (I1 I3 + I1 m R^2 + I3 m a^2)^(-1/2) = const."""
    I1, I3, m, R, a = P.I[0], P.I[2], P.m, P.R, P.a[2]
    return (I1 * I3 + I1 * m * R**2 + I3 * m * a**2) ** -0.5 + 0.0 * x[0]


@formula("ball_shape")
def ball_shape(P, x):
    """(2.18): f1 = R, f2 = R gamma3 + a."""
    u = x[0]
    return np.array([P.R + 0.0 * u, P.R * u + P.a[2]])


@compares("ball_shape", "meridian")
def ball_shape_vs_meridian(P, x, corrected=False):
    return _shape_vs_meridian(P, x, ball_shape)


def _routh_rho(P, u):
    I1, I3, m, R, a = P.I[0], P.I[2], P.m, P.R, P.a[2]
    return (I1 * I3 + I1 * m * R**2 * (1 - u * u) + I3 * m * (R * u + a) ** 2) ** -0.5


@formula("routh_density")
def routh_density(P, x):
    """(2.19): rho = (I1 I3 + I1 m R^2 (1 - g3^2) + I3 m (R g3 + a)^2)^(-1/2)."""
    return _routh_rho(P, x[5])


def _routh_bracket(P, x):
    M, g = x[:3], x[3:6]
    m, R, a, I1 = P.m, P.R, P.a[2], P.I[0]
    Mg = M @ g
    return m * R**2 * g[2] * Mg + I1 * M[2] + m * a * R * (Mg + M[2] * g[2]) + m * a**2 * M[2]


@formula("routh_K1")
def routh_k1(P, x):
    """(2.20), third member as printed: rho^-1 (m R^2 g3 (M, g) + I1 M3 + m a R ((M, g) + M3 g3)
    + m a^2 M3)."""
    return _routh_bracket(P, x) / _routh_rho(P, x[5])


@corrected("routh_K1", "omega3/rho = rho (m R^2 g3 (M,g) + I1 M3 + m a R ((M,g) + M3 g3) + "
           "m a^2 M3): the printed prefactor rho^-1 must be rho (omega3 = rho^2 (...), eq2.4)")
def routh_k1_corrected(P, x):
    return _routh_bracket(P, x) * _routh_rho(P, x[5])


@formula("routh_omega3_over_rho")
def routh_omega3_over_rho(P, x):
    """Table 1: omega3 / rho = const (Routh), rho of (2.19)."""
    return omega_of(P, x[:3], P.r(x[3:6]))[2] / _routh_rho(P, x[5])


@formula("jellett")
def jellett(P, x):
    """(2.20): K2 = (M, r)/R = (M, gamma) + (a/R) M3 (Jellett)."""
    M, g = x[:3], x[3:6]
    return M @ g + P.a[2] / P.R * M[2]


@formula("gyro_jellett")
def gyro_jellett(P, x):
    """(2.35): F = K1 + s gamma3, K1 = (M, r)/R ((2.5) with f1 = R), S = (0, 0, s)."""
    return jellett(P, x) + P.S[2] * x[5]


@formula("kuleshov_gyro_routh")
def kuleshov_gyro_routh(P, x):
    """(2.36) (I1 > I3): (I1 - I3) omega3/rho - s {1/rho - I1 sqrt(m a^2/(I1 - I3))
    arctg(sqrt(m/(I1 - I3)) rho (R g3 (I1 - I3) - a I3))}."""
    I1, I3, m, R, a, s = P.I[0], P.I[2], P.m, P.R, P.a[2], P.S[2]
    u = x[5]
    rho = _routh_rho(P, u)
    w3 = omega_of(P, x[:3], P.r(x[3:6]))[2]
    d = I1 - I3
    return d * w3 / rho - s * (1 / rho - I1 * np.sqrt(m * a**2 / d)
                               * np.arctan(np.sqrt(m / d) * rho * (R * u * d - a * I3)))


@formula("gyro_routh_spherical")
def gyro_routh_spherical(P, x):
    """(2.37) (I1 = I3 = mu): rho^-1 (3 mu omega3 - s (mu + m R^2 - 2 m a^2 - m a R g3)/(m a^2))."""
    mu, m, R, a, s = P.I[0], P.m, P.R, P.a[2], P.S[2]
    u = x[5]
    w3 = omega_of(P, x[:3], P.r(x[3:6]))[2]
    return (3 * mu * w3 - s * (mu + m * R**2 - 2 * m * a**2 - m * a * R * u) / (m * a**2)) \
        / _routh_rho(P, u)


@formula("bobylev")
def bobylev(P, x):
    """Bobylev (a = 0, I = mu E) as printed: omega3 + m R^2 g3^2 / (2 sqrt(mu (mu + m R^2)))."""
    mu, m, R = P.I[0], P.m, P.R
    w3 = omega_of(P, x[:3], P.r(x[3:6]))[2]
    return w3 + 0.5 * m * R**2 * x[5] ** 2 / np.sqrt(mu * (mu + m * R**2))


@corrected("bobylev", "omega3 + s m R^2 g3^2 / (2 mu (mu + m R^2)): the gyrostatic constant s "
           "is missing and the square root is spurious (the printed term is not even of the "
           "dimension of omega3); derived from mu d(omega, gamma)/dt = (S x omega, gamma) and "
           "(mu + m R^2) d omega3/dt = m R^2 g3 d(omega, gamma)/dt")
def bobylev_corrected(P, x):
    mu, m, R, s = P.I[0], P.m, P.R, P.S[2]
    w3 = omega_of(P, x[:3], P.r(x[3:6]))[2]
    return w3 + 0.5 * s * m * R**2 * x[5] ** 2 / (mu * (mu + m * R**2))
