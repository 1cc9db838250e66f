"""Section 3, body of revolution on a sphere in the variables (3.3)
(K1 = (M, r)(1 - k f1)/f1, K2 = omega3/rho0, gamma3): (3.4), the energy after (3.4),
(3.5), (3.6)-(3.15) and Kuleshov's (3.8). Contracts as in reduced_plane.py.

k is the signed curvature of CONVENTIONS.md (+1/R0 inside a cavity, -1/R0 outside a ball);
that is the reading under which (3.4) holds (solvers/models/reduced_systems.py,
tests/test_reduced.py).
rho0 is the first expression of (3.2), (I1 I3 + m (r, I r))^-1/2 (its expanded form there
carries a misprinted gamma3^2; rho0 of (3.2) is not a formula of this module).
"""

import numpy as np

from solvers.models import reduced_systems as rd
from solvers.models.revolution import profile
from solvers.verify.formulas.reduced_plane import body, potential
from solvers.verify.registry import corrected, formula


@formula("sphere_revolution_linear")
def sphere_revolution_linear(P, x):
    """(3.4): (1/rho0) K1' = -[I3 (1 - (f2/f1)') + k f1 (I1 - I3)(1 - k f2')] K2,
    ((1 - k f1)/rho0) K2' = -m f1 (f1 - f2' - k f1 f2') K1
                            + m k rho0 I1 f1^2 (g3 f2' + sqrt(1-g3^2)(f1 sqrt(1-g3^2))') K2."""
    return rd.eq3_3(body(P), x[0], x[1:3])


@formula("sphere_revolution_gyro_linear")
def sphere_revolution_gyro_linear(P, x):
    """(3.14) as printed: (3.4) with + s rho0^-1 (1 - k f2')(1 - k f1) in the K1 equation
    and - s m f1 f2 (1 - k f2')(1 - k f1) in the K2 equation."""
    return rd.eq3_10_printed(body(P), x[0], x[1:3])


@corrected("sphere_revolution_gyro_linear", "the gyrostatic term of the K1 equation is "
           "-s rho0^-1 (1 - k f2')(1 - k f1) (sign; at k = 0 it is then eq2.20's -s)")
def sphere_revolution_gyro_linear_corrected(P, x):
    return rd.eq3_10(body(P), x[0], x[1:3])


def _energy(P, x, corrected_form):
    """The energy after (3.4) in x = (gamma3, K1, K2, dgamma3/dt). The term
    m f2^2/I1 (K1/(1-k f1) - K2/(m rho f1 f2))^2 is evaluated in the identical, regular form
    (m f2 K1/(1-k f1) - K2/(rho f1))^2/(m I1) (rd.energy); rho = rho0 (variables (3.3))."""
    if len(x) < 4:
        raise LookupError("the energy after eq3.3 contains dgamma3/dt, which the variables "
                          "(gamma3, K1, K2) do not carry; pass x = (gamma3, K1, K2, "
                          "dgamma3/dt) (checks/ode.py does)")
    b = body(P)
    u, K1, K2, ud = x[:4]
    f1, f2, _, f2p = profile(b.prof, u)[:4]
    r2 = f1 * f1 * (1 - u * u) + f2 * f2
    fac = (1 - b.k * f2p) ** 2 if corrected_form else 1.0
    kin = 0.5 * (b.I1 + b.m * r2) * fac / (1 - u * u) * ud * ud
    xp = np.array([u, K1 / (1 - b.k * f1), K2, 0.0 * u])
    return kin + rd.energy(b, xp, lambda s: potential(P, s))


@formula("sphere_revolution_energy")
def sphere_revolution_energy(P, x):
    """After (3.4): H = 1/2 (I1 + m r^2)/(1 - g3^2) g3dot^2 + (K1^2/(1-k f1)^2
    - I3 K2^2/(m f1^2) + m f2^2/I1 (K1/(1-k f1) - K2/(m rho f1 f2))^2)/(2 I1 (1-g3^2)) + U."""
    return _energy(P, x, corrected_form=False)


@corrected("sphere_revolution_energy", "the nutation term is 1/2 (I1 + m r^2)(1 - k f2')^2 "
           "/(1 - gamma3^2) (dgamma3/dt)^2: on a sphere dgamma3/dt = k K3/(1 - k f2') "
           "(f2' is the meridional radius of curvature, k the curvature of the support; the "
           "paper's k of eq2-*1 is the multiplier there), while 1/2 K3^2 is the exact share "
           "of the azimuthal rotation in (M, omega)/2")
def sphere_revolution_energy_corrected(P, x):
    return _energy(P, x, corrected_form=True)


def _disk_terms(P, x, printed):
    b = body(P)
    R, a = b.prof.d, b.prof.a
    r0 = 1.0 / np.sqrt(b.I1 * b.I3 + b.m * (b.I1 * R * R + b.I3 * a * a))
    th, w, w1, w2 = x
    k, I1, I3 = b.k, b.I1, b.I3
    sn, ct = np.sin(th), np.cos(th) / np.sin(th)
    c1 = ct * (1 + k * R / (sn - k * R))
    c0 = r0 * r0 * b.m * R * I3 / (1 - k * R / sn) * (R + a * ct + k * R * R * (I1 - I3)
                                                     / (I3 * sn))
    return np.array([w2, c1 * (w if printed else w1), -c0 * w])


@formula("sphere_disk_second_order")
def sphere_disk_second_order(P, x):
    """(3.5) as printed: w'' + ctg(1 + kR/(sin - kR)) w - rho0^2 m R I3/(1 - kR/sin)
    (R + a ctg + k R^2 (I1 - I3)/(I3 sin)) w = 0 (x = (theta, w, w', w''))."""
    return _disk_terms(P, x, printed=True)


@corrected("sphere_disk_second_order", "the second term is ctg(th)(1 + kR/(sin th - kR)) "
           "d omega3/d theta (the derivative is missing in print; at k = 0 this is the "
           "corrected eq2.9)")
def sphere_disk_second_order_corrected(P, x):
    return _disk_terms(P, x, printed=False)


# --- the ball with displaced centre (2.18) on a sphere ------------------------------------

@formula("sphere_routh_linear")
def sphere_routh_linear(P, x):
    """(3.6): (1/rho) K1' = -kR (I1 - I3)(1 - kR) K2, (1/rho) K2' = k m R^3/(1 - kR) K1."""
    return rd.eq3_7(body(P), x[0], x[1:3])


@formula("sphere_routh_gyro_linear")
def sphere_routh_gyro_linear(P, x):
    """(3.15) as printed: K1' has -R (1 - kR)^2 s (i.e. -(1/rho0) R (1-kR)^2 s after 1/rho0)."""
    return rd.eq3_11_printed(body(P), x[0], x[1:3])


@corrected("sphere_routh_gyro_linear", "the gyrostatic term of the K1 equation is "
           "-(1 - kR)^2 s (no factor R); the sign agrees with the corrected eq3.10")
def sphere_routh_gyro_linear_corrected(P, x):
    return rd.eq3_11(body(P), x[0], x[1:3])


def tau(P, u):
    """tau = int rho0 d gamma3 in closed form (any additive constant), complex-safe:
    1/rho0^2 = A u^2 + B u + C, A = m R^2 (I3 - I1), B = 2 I3 m R a,
    C = I1 I3 + I1 m R^2 + I3 m a^2."""
    b = body(P)
    R, a, I1, I3, m = b.prof.c, b.prof.a, b.I1, b.I3, b.m
    A = m * R * R * (I3 - I1)
    B = 2 * I3 * m * R * a
    C = I1 * I3 + I1 * m * R * R + I3 * m * a * a
    Q = A * u * u + B * u + C
    if abs(A) <= 1e-13 * C:
        if abs(B) <= 1e-13 * C:
            return u / np.sqrt(C)
        return 2 * np.sqrt(B * u + C) / B
    if A > 0:
        return np.log(2 * np.sqrt(A) * np.sqrt(Q) + 2 * A * u + B) / np.sqrt(A)
    return -np.arcsin((2 * A * u + B) / np.sqrt(B * B - 4 * A * C)) / np.sqrt(-A)


@formula("sphere_routh_lambda_tau")
def sphere_routh_lambda_tau(P, x):
    """(3.7): lambda^2 = m k^2 R^4 (I3 - I1), tau = int rho0 d gamma3; x = (gamma3,).
    Only lambda^2 is printed: the root is lambda = -k R^2 sqrt(m (I3 - I1)), the one for
    which F2 and F3 (with the same lambda) are integrals of (3.6) (imaginary for I1 > I3).
    Returns (lambda, tau)."""
    b = body(P)
    lam = -b.k * b.prof.c**2 * np.sqrt(complex(b.m * (b.I3 - b.I1)))
    return np.array([lam + 0.0 * x[0], tau(P, x[0])])


ALPHA = 0.7     # phase of the real combination Re(exp(i ALPHA) F) used when F is complex


def _F23(P, x, sign):
    """(sqrt(m(I3-I1)) K2 + sign m R/(1-kR) K1) exp(sign lambda tau), real-valued: for
    I1 > I3 the printed F2, F3 are complex (sqrt(m (I3-I1)) = i beta, lambda = -i k R^2 beta)
    and F is an integral iff its real and imaginary parts are; the function then returns
    Re(exp(i ALPHA) F) = cos(ALPHA) Re F - sin(ALPHA) Im F, a generic real combination,
    written with real-analytic parts so that the complex step differentiates it exactly."""
    b = body(P)
    R, k = b.prof.c, b.k
    u, K1, K2 = x[0], x[1], x[2]
    Bc = b.m * R / (1 - k * R)
    t = tau(P, u)
    d = b.m * (b.I3 - b.I1)
    if d >= 0:
        A = np.sqrt(d)
        return (A * K2 + sign * Bc * K1) * np.exp(-sign * k * R * R * A * t)
    beta = np.sqrt(-d)
    om = k * R * R * beta                       # lambda = -i om
    c, s = np.cos(om * t), np.sin(om * t)
    # F = (i beta K2 + sign Bc K1)(cos(om t) - i sign sin(om t))
    re = sign * Bc * K1 * c + beta * K2 * sign * s
    im = beta * K2 * c - Bc * K1 * s
    return np.cos(ALPHA) * re - np.sin(ALPHA) * im


@formula("sphere_routh_F2")
def sphere_routh_f2(P, x):
    """(3.7): F2 = (sqrt(m (I3 - I1)) K2 + m R K1/(1 - kR)) e^(lambda tau) (see _F23)."""
    return _F23(P, x, +1.0)


@formula("sphere_routh_F3")
def sphere_routh_f3(P, x):
    """(3.7): F3 = (sqrt(m (I3 - I1)) K2 - m R K1/(1 - kR)) e^(-lambda tau) (see _F23)."""
    return _F23(P, x, -1.0)


@formula("kuleshov_quadratic")
def kuleshov_quadratic(P, x):
    """(3.8) (right-hand side): F = m R^2 K1^2/(1 - kR)^2 + (I1 - I3) K2^2."""
    b = body(P)
    R, k = b.prof.c, b.k
    return b.m * R * R / (1 - k * R) ** 2 * x[1] ** 2 + (b.I1 - b.I3) * x[2] ** 2


@formula("sphere_routh_spherical_second")
def sphere_routh_spherical_second(P, x):
    """(3.9) (I1 = I3): (1 - kR) K2 - k m R^3 K1 int rho d gamma3 (rho = rho0 of (2.18))."""
    b = body(P)
    R, k = b.prof.c, b.k
    return (1 - k * R) * x[2] - k * b.m * R**3 * x[1] * tau(P, x[0])
