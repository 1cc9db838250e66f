"""Section 2, body of revolution on the plane in the reduced variables of (2.5):
(2.6) .. (2.12), the linear systems (2.13), (2.32), (2.34), the disk (2.16), (2.17), (2.33)
and its hypergeometric form, the superposition (2.14) and the quadratic integral of (2.21).

The systems wrap solvers/models/reduced_systems.py (printed and corrected forms, tested
against the full field in tests/test_reduced.py). Contracts of the roles used here:

* system in (gamma3, K1, K2, K3): f(P, x) = dx/dt (dx/dtau for (2.9), (2.12));
* system in (gamma3|theta|u, K1, K2): f(P, x) = dK/ds, s the first variable;
* second-order equation in (theta|x, omega3): f(P, (s, w, w', w'')) returns the TERMS of
  the printed "left-hand side - right-hand side" (their sum is the residual; the check
  normalises it by the sum of their moduli, see checks/ode.py);
* bracket: the antisymmetric matrix J(x); time change: N with d tau = N dt;
* solution in (gamma3|u, K1, K2): f(P, (s, c1, c2)) = K(s) (see reduced_flat.py).

The potential of the drawn models is U = m g (r, gamma) + eps/2 (I gamma, gamma), i.e.
U(gamma3) = m g phi(gamma3) + eps/2 (I1 (1 - gamma3^2) + I3 gamma3^2) on a body of
revolution (phi: the support function on the axis, solvers/models/revolution.py).
"""

import numpy as np
from scipy.integrate import solve_ivp

from solvers.models import reduced_systems as rd
from solvers.models.revolution import phi_derivs, profile
from solvers.verify.registry import corrected, formula


def body(P):
    return rd.RevBody.from_params(P.p)


def potential(P, u):
    """U(gamma3) of the drawn model (gravity and Brun field)."""
    I1, I3 = P.I[0], P.I[2]
    return (P.m * P.g * phi_derivs(body(P).prof, u)[0]
            + 0.5 * P.eps * (I1 * (1 - u * u) + I3 * u * u))


def potential_du(P, u):
    """dU/dgamma3."""
    I1, I3 = P.I[0], P.I[2]
    return P.m * P.g * phi_derivs(body(P).prof, u)[1] + P.eps * (I3 - I1) * u


# --- (2.6) .. (2.8) ----------------------------------------------------------------------

@formula("revolution_reduced")
def revolution_reduced(P, x):
    """(2.6) as printed (no gyrostat); the paper's k is rd.kappa, not the curvature."""
    return rd.field_eq2_star1(body(P), x, potential_du(P, x[0]))


@formula("revolution_reduced_density")
def revolution_reduced_density(P, x):
    """rho = 1/k, k = sqrt((1 - gamma3^2)/(I1 + m r^2)) (sentence after (2.6))."""
    return 1.0 / rd.kappa(body(P), x[0]) + 0.0 * x[1]


@formula("revolution_energy_K")
def revolution_energy_k(P, x):
    """(2.7). The term m f2^2/I1 (K1 - K2/(rho m f1 f2))^2 is evaluated in the identical
    form (m f2 K1 - K2/(rho f1))^2/(m I1), which stays finite where f2 = 0 (a disk with
    a = 0): the same function, not a different formula."""
    return rd.energy(body(P), x, lambda u: potential(P, u))


@formula("revolution_time_change")
def revolution_time_change(P, x):
    """d tau = k dt: N = k = sqrt((1 - gamma3^2)/(I1 + m r^2))."""
    return rd.kappa(body(P), x[0]) + 0.0 * x[1]


@formula("revolution_bracket")
def revolution_bracket(P, x):
    """(2.8): {gamma3, K3} = 1, {K1, K3} = -I3 rho (1 - (f2/f1)') K2,
    {K2, K3} = -m rho f1 (f1 - f2') K1."""
    return rd.bracket(body(P), x)


# --- the antigradient form (2.9) .. (2.12) -------------------------------------------------
# lambda is "an arbitrary function": the default is the constant LAMBDA (the claim that
# J_lambda is not Poisson names constant lambda), and (2.11) uses ALPHA(gamma3) K3 with an
# arbitrary (here fixed, non-constant) alpha. A bracket check that needs another lambda
# calls antigradient_J(P, x, lam=...).
LAMBDA = 0.7


def alpha(u):
    """The arbitrary alpha(gamma3) of (2.11) (any smooth nonvanishing function)."""
    return 1.0 + 0.5 * u * u


def energy_gradient(P, x):
    """grad H of (2.7) in (gamma3, K1, K2, K3), closed form (complex-safe)."""
    b = body(P)
    u, K1, K2, K3 = x
    f1, f2, f1p, f2p = profile(b.prof, u)[:4]
    I1, I3, m = b.I1, b.I3, b.m
    s2 = 1 - u * u
    Q = I1 * I3 + m * I1 * f1 * f1 * s2 + m * I3 * f2 * f2          # 1/rho^2
    sq = np.sqrt(Q)
    dQ = m * I1 * (2 * f1 * f1p * s2 - 2 * u * f1 * f1) + 2 * m * I3 * f2 * f2p
    W = m * f2 * K1 - K2 * sq / f1                                   # m f2 K1 - K2/(rho f1)
    dW = m * f2p * K1 - K2 * (dQ / (2 * sq) / f1 - sq * f1p / (f1 * f1))
    N = K1 * K1 - I3 / (m * f1 * f1) * K2 * K2 + W * W / (m * I1)
    dN = 2 * I3 * K2 * K2 * f1p / (m * f1**3) + 2 * W * dW / (m * I1)
    H_u = dN / (2 * I1 * s2) + N * u / (I1 * s2 * s2) + potential_du(P, u)
    H_K1 = (K1 + f2 * W / I1) / (I1 * s2)
    H_K2 = (-I3 * K2 / (m * f1 * f1) - W * sq / (f1 * m * I1)) / (I1 * s2)
    return np.array([H_u, H_K1, H_K2, K3])


def _uv(P, x, rIr_over_m):
    b = body(P)
    u, K1, K2, K3 = x
    f1, f2 = profile(b.prof, u)[:2]
    rho = rd.rho0(b, u)
    rIr = b.I1 * f1 * f1 * (1 - u * u) + b.I3 * f2 * f2             # (r, I r)
    c = rIr / b.m if rIr_over_m else rIr
    uu = (c * K2 - f1 * f2 / rho * K1) / (f1 * f1 * b.I1**2 * (1 - u * u) * K3)
    vv = (f2 / (f1 * rho) * K2 - (b.I1 + b.m * f2 * f2) * K1) / (b.I1**2 * (1 - u * u) * K3)
    return uu, vv


def _J_lambda(P, x, lam, printed):
    uu, vv = _uv(P, x, rIr_over_m=printed)
    A = np.zeros((4, 4), dtype=np.result_type(x[0], x[1], uu, lam, float))
    A[1, 2] = 1.0
    A[1, 3] = -uu
    A[2, 3] = -vv
    return revolution_bracket(P, x) + lam * (A - A.T)


@formula("antigradient_J")
def antigradient_j(P, x, lam=None):
    """(2.10) as printed: J_0 (= (2.8)) + lambda (entries 1, -u, -v), with
    u = ((r, I r)/m K2 - f1 f2/rho K1)/(f1^2 I1^2 (1 - gamma3^2) K3)."""
    return _J_lambda(P, x, LAMBDA if lam is None else lam, printed=True)


@corrected("antigradient_J", "u of eq2a-*2 without the factor 1/m: u = ((r, I r) K2 - "
           "f1 f2/rho K1)/(f1^2 I1^2 (1 - gamma3^2) K3) = (dH/dK2)/K3, as J_lambda grad H = "
           "J_0 grad H requires (v = -(dH/dK1)/K3 is right as printed)")
def antigradient_j_corrected(P, x, lam=None):
    return _J_lambda(P, x, LAMBDA if lam is None else lam, printed=False)


@formula("antigradient_form")
def antigradient_form(P, x, lam=None):
    """(2.9): dx/d tau = J_lambda grad H ((2.10) as printed, default lambda)."""
    return antigradient_j(P, x, lam) @ energy_gradient(P, x)


@corrected("antigradient_form", "J_lambda with the corrected u of eq2a-*2 (no 1/m)")
def antigradient_form_corrected(P, x, lam=None):
    return antigradient_j_corrected(P, x, lam) @ energy_gradient(P, x)


@formula("conformal_lambda")
def conformal_lambda(P, x):
    """(2.11): lambda = alpha(gamma3) K3."""
    return alpha(x[0]) * x[3]


@formula("conformal_field")
def conformal_field(P, x):
    """(2.12): v = (lambda^-1 J_lambda) grad H with lambda = alpha(gamma3) K3 (as printed)."""
    lam = conformal_lambda(P, x)
    return antigradient_j(P, x, lam) @ energy_gradient(P, x) / lam


@corrected("conformal_field", "J_lambda with the corrected u of eq2a-*2 (no 1/m)")
def conformal_field_corrected(P, x):
    lam = conformal_lambda(P, x)
    return antigradient_j_corrected(P, x, lam) @ energy_gradient(P, x) / lam


@formula("reducing_multiplier_aK3")
def reducing_multiplier(P, x):
    """rho = alpha(gamma3) K3, the invariant measure of (2.12) (alpha as in (2.11)).
    A density is taken positive: on K3 < 0 this returns -alpha K3 (the Liouville equation
    div(rho v) = 0 is linear in rho; the sign comes from the real part, so the complex step
    still differentiates alpha K3 exactly)."""
    return np.sign(np.real(x[3])) * alpha(x[0]) * x[3]


# --- linear systems in gamma3 -----------------------------------------------------------------

@formula("revolution_linear")
def revolution_linear(P, x):
    """(2.13): dK1/dg3 = -rho I3 (1 - (f2/f1)') K2, dK2/dg3 = -m rho f1 (f1 - f2') K1."""
    return rd.eq2_5(body(P), x[0], x[1:3])


@formula("revolution_gyro_linear")
def revolution_gyro_linear(P, x):
    """(2.32): (2.13) with -s and -m rho f1 f2 s (S = (0, 0, s))."""
    return rd.eq2_20(body(P), x[0], x[1:3])


@formula("routh_gyro_linear")
def routh_gyro_linear(P, x):
    """(2.34): dK1/dg3 = -s, dK2/dg3 = -m rho R (R g3 + a) s."""
    return rd.eq2_24(body(P), x[0], x[1:3])


@formula("quadratic_condition")
def quadratic_condition(P, x):
    """(2.21): lambda(gamma3) = I3 (1 - (f2/f1)') / (m f1 (f1 - f2')); x = (gamma3,)."""
    b = body(P)
    c1, c2 = rd.linear_coeffs(b, x[0])
    return c1 / c2


@formula("revolution_quadratic_F")
def revolution_quadratic_f(P, x):
    """F = a K1^2 + b K2^2 with a = 1, b = -a lambda (2.21), a and b CONSTANT.

    (2.21) asks for a meridian along which lambda is constant; no body of the model family
    (ellipsoid + ball + disk + offset) has one but the Routh ball, where lambda is 0/0.
    So the constants are taken as the value of lambda at the real point (x[0].real):
    the complex step then differentiates F with a, b held fixed, which is the statement
    "lambda' = 0 implies dF/dt = 0" tested at each point on any meridian (each point
    gets its own constant lambda). A wrong b (e.g. +a lambda) fails (tests)."""
    u0 = np.real(x[0])
    lam = quadratic_condition(P, np.array([u0]))
    return x[1] * x[1] - lam * x[2] * x[2]


_SUPERPOSITION_RANGE = 0.98    # |gamma3| covered by the cached elementary solutions
_SUPERPOSITION_CACHE: dict[bytes, tuple] = {}


def _elementary(P):
    """Dense elementary solutions of (2.13) on [-0.98, 0.98], g^(i)(0) = e_i (cached per
    parameter vector): scipy DOP853, rtol 1e-12."""
    key = P.p.tobytes()
    if key not in _SUPERPOSITION_CACHE:
        def aug(s, Z):
            G = Z.reshape(2, 2)
            return np.stack([revolution_linear(P, np.array([s, *G[:, j]]))
                             for j in range(2)], axis=1).ravel()

        sols = [solve_ivp(aug, (0.0, end), np.eye(2).ravel(), method="DOP853", rtol=1e-12,
                          atol=1e-14, dense_output=True)
                for end in (-_SUPERPOSITION_RANGE, _SUPERPOSITION_RANGE)]
        if not all(sol.success for sol in sols):
            raise FloatingPointError("eq2.5: elementary solutions failed")
        _SUPERPOSITION_CACHE.clear()            # one parameter set at a time is enough
        _SUPERPOSITION_CACHE[key] = tuple(sol.sol for sol in sols)
    return _SUPERPOSITION_CACHE[key]


@formula("linear_superposition")
def linear_superposition(P, x):
    """(2.14): K = c1 g^(1)(gamma3) + c2 g^(2)(gamma3), x = (gamma3, c1, c2), with the
    elementary solutions g^(i) of (2.13) normalised by g^(i)(0) = e_i, integrated
    numerically (dense DOP853 output, rtol 1e-12, |gamma3| <= 0.98): real x only (the
    checks that use it, checks/ode.py, never differentiate it)."""
    s = float(np.real(x[0]))
    if abs(s) > _SUPERPOSITION_RANGE:
        raise ValueError(f"eq2.7 is tabulated for |gamma3| <= {_SUPERPOSITION_RANGE}")
    neg, pos = _elementary(P)
    G = (neg if s < 0 else pos)(s).reshape(2, 2)
    return G @ np.real(x[1:3])


# --- the round disk (2.15), gamma3 = cos(theta) ----------------------------------------------

@formula("disk_linear")
def disk_linear(P, x):
    """(2.16) as printed: dK1/dth = rho m R^2/sin th K2, dK2/dth = I3 rho (sin + a/R cos) K1."""
    return rd.eq2_8_printed(body(P), x[0], x[1:3])


@corrected("disk_linear", "K1 and K2 exchanged with respect to eq2.4 (what eq2.5 gives for "
           "eq2.71): dK1/dth = I3 rho (sin th + a/R cos th) K2, dK2/dth = rho m R^2/sin th K1")
def disk_linear_corrected(P, x):
    return rd.eq2_8(body(P), x[0], x[1:3])


def _disk(P):
    b = body(P)
    R, a = b.prof.d, b.prof.a
    rho = 1.0 / np.sqrt(b.I1 * b.I3 + b.m * (b.I1 * R * R + b.I3 * a * a))
    return b, R, a, rho


def _eq2_21_terms(P, x, s, sign):
    """Terms of w'' + sign (ctg w' - rho^2 m R (R + a ctg) I3 w) - s m R rho^2 (R + a ctg):
    sign = -1 is the printed (2.17)/(2.33), sign = +1 the corrected form (reduced.eq2_21)."""
    b, R, a, rho = _disk(P)
    th, w, w1, w2 = x
    ct = np.cos(th) / np.sin(th)
    lam = rho * rho * b.m * R * (R + a * ct)
    return np.array([w2, sign * ct * w1, -sign * lam * b.I3 * w, -lam * s + 0.0 * th])


@formula("disk_second_order")
def disk_second_order(P, x):
    """(2.17) as printed: w'' - ctg(th) w' + rho^2 m R (R + a ctg th) I3 w = 0."""
    return _eq2_21_terms(P, x, 0.0, -1.0)


@corrected("disk_second_order", "signs of the ctg and omega3 terms: w'' + ctg(th) w' - "
           "rho^2 m R (R + a ctg th) I3 w = 0 (what eq2.8/eq2.5 give; the paper's own "
           "hypergeometric form and eq3.4 at k = 0 agree)")
def disk_second_order_corrected(P, x):
    return _eq2_21_terms(P, x, 0.0, +1.0)


@formula("disk_gyro_second_order")
def disk_gyro_second_order(P, x):
    """(2.33) as printed: w'' - ctg w' + m R I3 (R + a ctg) rho^2 w = s m R rho^2 (R + a ctg)."""
    return _eq2_21_terms(P, x, P.S[2], -1.0)


@corrected("disk_gyro_second_order", "signs of the ctg and omega3 terms as in the corrected "
           "eq2.9, right-hand side as printed: w'' + ctg w' - m R I3 (R + a ctg) rho^2 w = "
           "s m R rho^2 (R + a ctg)")
def disk_gyro_second_order_corrected(P, x):
    return _eq2_21_terms(P, x, P.S[2], +1.0)


@formula("disk_hypergeometric")
def disk_hypergeometric(P, x):
    """After (2.17) (a = 0, cos th = 1 - 2x): x(1-x) w'' + (1-2x) w' - rho^2 I3 m R^2 w = 0."""
    b, R, _, rho = _disk(P)
    xx, w, w1, w2 = x
    return np.array([xx * (1 - xx) * w2, (1 - 2 * xx) * w1, -rho * rho * b.I3 * b.m * R * R * w])
