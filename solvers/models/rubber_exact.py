"""Exact (sympy) checks of the rubber tensor invariants, in the chart (omega, gamma).

On the rubber manifold N = {(omega, gamma) = 0, |gamma| = 1} the angular momentum about
the contact point is M = I~ omega, I~ = I + m (r^2 E - r r^T) (1.6); this module writes the
field in (omega, gamma):

    domega/dt = I~^-1 (N - dI~/dt omega + lambda gamma),   N = M x omega
                + m dr/dt x (omega x r) + gamma x m g r       (rubber_lagrange.py)
    dgamma/dt = (gamma x omega) / (1 - k R)   (ball of radius R on a sphere, J = R(E - gg^T))
    dgamma/dt = gamma x omega                 (plane)

with lambda fixed by (domega/dt, gamma) = 0, so (omega, gamma) is a first integral of this
field on all of R^6, and so is gamma^2. A density rho(omega, gamma) is then an invariant
measure of the rubber flow on N (the volume rho d^3omega d^3gamma divided by
d(gamma^2) ^ d(omega, gamma)) iff div(rho v) = 0 at the points of N; a function F is a
first integral on N iff dF/dt = grad F . v = 0 there. Each residual below is reduced
on N by eliminating omega3 = -(omega1 g1 + omega2 g2)/g3 and returned as a sympy
expression; zero means proved for all parameter values (the symbols stay free).

In the chart (M, gamma) of rubber_lagrange.py the same measure has the density
rho / det I~ (dM = det I~ domega).
"""

from __future__ import annotations

import sympy as sp

w = sp.symbols("w1:4")
g = sp.symbols("g1:4")
W = sp.Matrix(w)
G = sp.Matrix(g)
X = list(w) + list(g)


def _on_manifold(expr, unit=False):
    """Numerator of expr with omega3 eliminated by (omega, gamma) = 0, expanded; with
    unit=True also g3^2 = 1 - g1^2 - g2^2 (the residual then holds on |gamma| = 1 only)."""
    num = sp.numer(sp.together(expr))
    num = num.subs(w[2], -(w[0] * g[0] + w[1] * g[1]) / g[2])
    num = sp.numer(sp.together(num))
    if unit:
        num = sp.expand(num).subs(g[2], sp.sqrt(1 - g[0] ** 2 - g[1] ** 2))
    return sp.expand(num)


def ball_field(kappa, J=None, gyrostat=False, brun=False):
    """Balanced ball (r = R gamma, any inertia) on a sphere with k R = kappa: on N,
    I~ omega = (I + m R^2) omega = J omega and the field reduces to
    J domega/dt = (J omega + S) x omega + gamma x eps I gamma + lambda gamma (the dr/dt term
    vanishes for a ball); S with gyrostat=True, the Brun field (I = J - m R^2, written
    I = J - D) with brun=True (plane only)."""
    J = J or sp.symbols("J1:4", positive=True)
    Jm = sp.diag(*J)
    Ji = sp.diag(*[1 / x for x in J])
    K = Jm * W
    if gyrostat:
        K = K + sp.Matrix(sp.symbols("S1:4"))
    JwXw = K.cross(W)
    if brun:
        D, eps = sp.symbols("D epsilon", positive=True)
        JwXw = JwXw + G.cross(eps * (Jm - D * sp.eye(3)) * G)
    Q = (G.T * Ji * G)[0]
    lam = -(JwXw.dot(Ji * G)) / Q
    wd = Ji * (JwXw + lam * G)
    gd = G.cross(W) / (1 - kappa)
    return list(wd) + list(gd), J, Q


def ball_measure_residual(kappa=None, gyrostat=False, brun=False):
    """div(rho v)/rho on N for rho = (gamma, J^-1 gamma)^((1 - kappa)/2), kappa = k R
    symbolic unless given; 0 means rho is an invariant density for every k, I, m, R."""
    kappa = sp.Symbol("kappa") if kappa is None else kappa
    v, _J, Q = ball_field(kappa, gyrostat=gyrostat, brun=brun)
    p = (1 - kappa) / 2
    expr = sum(sp.diff(v[i], X[i]) for i in range(6)) + p * sum(
        sp.diff(Q, X[i]) * v[i] for i in range(6)) / Q
    return sp.simplify(_on_manifold(expr))


def ball_measure_residual_wrong_power(kappa, power):
    """The same residual for another power: non-zero, so the power is not arbitrary."""
    v, _J, Q = ball_field(kappa)
    expr = sum(sp.diff(v[i], X[i]) for i in range(6)) + power * sum(
        sp.diff(Q, X[i]) * v[i] for i in range(6)) / Q
    return sp.simplify(_on_manifold(expr))


def ball_integral_residual(kappa=0):
    """dF/dt on N for F = |M x gamma|^2 = (M, M) - (M, gamma)^2, M = J omega."""
    v, J, _Q = ball_field(kappa)
    M = sp.diag(*J) * W
    F = M.dot(M) - M.dot(G) ** 2
    return _on_manifold(sum(sp.diff(F, X[i]) * v[i] for i in range(6)), unit=True)


def ball_gyrostat_integral_residual():
    """Plane, gyrostat S: dF/dt on N for F = |(M + S) x gamma|^2."""
    v, J, _Q = ball_field(0, gyrostat=True)
    K = sp.diag(*J) * W + sp.Matrix(sp.symbols("S1:4"))
    F = K.dot(K) - K.dot(G) ** 2
    return _on_manifold(sum(sp.diff(F, X[i]) * v[i] for i in range(6)), unit=True)


def ball_brun_integral_residual():
    """Plane, Brun field eps: dF/dt on N for F = |M x gamma|^2 - eps det J (gamma, J^-1 gamma).
    (The torque gamma x eps I gamma equals gamma x eps J gamma, and for diagonal J,
    J (a x J a) = det J (J^-1 a x a).)"""
    v, J, Q = ball_field(0, brun=True)
    eps = sp.Symbol("epsilon", positive=True)
    M = sp.diag(*J) * W
    F = M.dot(M) - M.dot(G) ** 2 - eps * J[0] * J[1] * J[2] * Q
    return _on_manifold(sum(sp.diff(F, X[i]) * v[i] for i in range(6)), unit=True)


def shell_integral_P(J):
    """P of the second integral F = P / Q of the ball at kR = 2 (a shell of twice the radius
    of a fixed internal ball): P = sum P_ik omega_i^2 g_k^2. Found here by solving the linear
    equations for the nine coefficients exactly (the solutions form a plane spanned by this P
    and H Q); any J."""
    J1, J2, J3 = J
    P = sp.Matrix([[J1 * J3 * (J1 - J3), J1 * J3 * (J1 - J3), J1 * J2 * (J1 - J3)],
                   [J2 * J3 * (J2 - J3), J2 * J3 * (J2 - J3), J1 * J2 * (J2 - J3)],
                   [0, 0, J3 * (J1 - J3) * (J2 - J3)]])
    return sum(P[i, k] * w[i] ** 2 * g[k] ** 2 for i in range(3) for k in range(3))


def shell_integral_residual(kappa=2):
    """dF/dt on N (|gamma| = 1) for F = P / Q of shell_integral_P: Q dP/dt - P dQ/dt."""
    v, J, Q = ball_field(kappa)
    P = shell_integral_P(J)
    expr = (Q * sum(sp.diff(P, X[i]) * v[i] for i in range(6))
            - P * sum(sp.diff(Q, X[i]) * v[i] for i in range(6)))
    return sp.simplify(_on_manifold(expr, unit=True))


def routh_field(values=None):
    """Routh ball on a plane: r = R gamma + a e3, I = diag(I1, I1, I3), gravity g; the
    parameters stay symbols unless `values` (name -> exact number) fixes some of them."""
    I1, I3, m, R, a, gr = sp.symbols("I1 I3 m R a g", positive=True)
    if values:
        fixed = {"I1": I1, "I3": I3, "m": m, "R": R, "a": a, "g": gr}
        I1, I3, m, R, a, gr = (sp.nsimplify(values.get(k, s)) for k, s in fixed.items())
    r = R * G + a * sp.Matrix([0, 0, 1])
    return body_field((I1, I1, I3), m, gr, r), dict(I1=I1, I3=I3, m=m, R=R, a=a, r=r)


def routh_nose_squared(prm):
    """N^2 = I1 g3^2 + I3 (g1^2 + g2^2) + m (r, gamma)^2 (Koiller's 'nose' function,
    written in gamma; on |gamma| = 1 it is I1 cos^2 + I3 sin^2 + m z_G^2)."""
    return (prm["I1"] * g[2] ** 2 + prm["I3"] * (g[0] ** 2 + g[1] ** 2)
            + prm["m"] * prm["r"].dot(G) ** 2)


def routh_integral_residual(v=None, prm=None):
    """dF/dt on N for F = N omega3: its square F^2 = N^2 omega3^2 is checked, rational."""
    if v is None:
        v, prm = routh_field()
    F2 = routh_nose_squared(prm) * w[2] ** 2
    return _on_manifold(sum(sp.diff(F2, X[i]) * v[i] for i in range(6)))


def routh_measure_residual(v=None, prm=None):
    """div(rho v)/rho on N for rho = (I1 + m r^2) N (chart (omega, gamma))."""
    if v is None:
        v, prm = routh_field()
    r = prm["r"]
    logrho_grad = [sp.diff(prm["m"] * r.dot(r), x) / (prm["I1"] + prm["m"] * r.dot(r))
                   + sp.diff(routh_nose_squared(prm), x) / (2 * routh_nose_squared(prm))
                   for x in X]
    expr = sum(sp.diff(v[i], X[i]) for i in range(6)) + sum(
        logrho_grad[i] * v[i] for i in range(6))
    return _on_manifold(expr)


def body_field(I, m, gravity, r, scale=1, at=None, Jr=None):
    """Any rubber body in the chart (omega, gamma), exact parameters: inertia I (3 numbers),
    mass m, gravity (plane only), the support point r as a sympy Matrix in g (any
    extension off |gamma| = 1: on N only its tangential derivative enters), and
    dgamma/dt = scale (gamma x omega) (scale = 1/(1 - k R) for a ball on a sphere, whose
    r = a + R gamma has J = R E). The same equations as rubber_lagrange.py. With `at` (a
    Matrix in other symbols) gamma is replaced by it before the field is assembled, so
    that the field along a line of gamma stays small. With `Jr` (dr/dgamma) r may hold
    symbols for radicals (revolution_density_residuals)."""
    Jr = r.jacobian(G) if Jr is None else Jr
    Gm = G if at is None else at
    if at is not None:
        put = dict(zip(g, at, strict=True))
        r, Jr = r.subs(put), Jr.subs(put)
    It = sp.diag(*I) + m * (r.dot(r) * sp.eye(3) - r * r.T)
    gd = scale * Gm.cross(W)
    rd = Jr * gd
    N = (It * W).cross(W) + m * rd.cross(W.cross(r)) + Gm.cross(m * gravity * r)
    Itd = m * (2 * r.dot(rd) * sp.eye(3) - rd * r.T - r * rd.T)
    Iti = It.adjugate() / It.det()
    base = Iti * (N - Itd * W)
    Ag = Iti * Gm
    lam = -base.dot(Gm) / Ag.dot(Gm)
    return list(base + lam * Ag) + list(gd)


def gamma_density_obstruction(field, gamma0):
    """Exact obstruction to an invariant density f(gamma) depending on gamma alone, at the
    rational point gamma0 of |gamma| = 1 (gamma0[2] != 0); `field(at)` is body_field with
    its body's parameters.

    If f existed, div v + grad log f . dgamma/dt = 0 on N; with dgamma/dt = s gamma x omega
    this says div v = c(gamma) . omega on N with c x gamma = s grad_tan log f, so the
    1-form alpha = (c x gamma) . dgamma would be closed on the sphere of gamma: the curl of
    c x gamma would have no component along gamma. With omega3 eliminated by
    (omega, gamma) = 0, div v = A1 w1 + A2 w2 and c = (A1, A2, 0) (any c with these A
    differs by a multiple of gamma, which changes nothing). Each derivative along gamma is
    taken on the line gamma0 + t e_j. Returns (div v at omega = 0, the curl's component
    along gamma), exact numbers at gamma0: either non-zero proves that no f(gamma) exists,
    not even near gamma0, for these parameters. Densities depending on omega are not
    concerned."""
    t = sp.Symbol("t")
    g0 = sp.Matrix(gamma0)
    dF, div0 = [], None
    for j in range(3):
        line = g0 + t * sp.eye(3)[:, j]
        v = field(line)
        div = sum(sp.diff(v[i], X[i]) for i in range(3))    # d(gamma x omega)_j/dg_j = 0
        div = div.subs(w[2], -(w[0] * line[0] + w[1] * line[1]) / line[2])
        zero = {w[0]: 0, w[1]: 0}
        c = sp.Matrix([sp.diff(div, w[0]).subs(zero), sp.diff(div, w[1]).subs(zero), 0])
        dF.append(sp.diff(c.cross(line), t).subs(t, 0))
        if div0 is None:
            div0 = div.subs(zero).subs(t, 0)
    D = sp.Matrix.hstack(*dF)          # D[k, j] = d(c x gamma)_k / d gamma_j at gamma0
    curl = sp.Matrix([D[2, 1] - D[1, 2], D[0, 2] - D[2, 0], D[1, 0] - D[0, 1]])
    return (sp.nsimplify(sp.radsimp(div0)),
            sp.nsimplify(sp.radsimp(sp.expand(curl.dot(g0)))))


def revolution_density_residuals(I, m, gravity, B=(0, 0, 0), c=0, a=(0, 0, 0), d=0,
                                 density=None):
    """Exact proof that rho = (I1 + m r^2) N(gamma), N^2 = I1 g3^2 + I3 (g1^2 + g2^2)
    + m (r, gamma)^2, is an invariant density on N for the body with exact parameters I, m,
    gravity and surface r = a + B gamma / q + c gamma + d (g1, g2, 0) / s (the parts of
    rubber_bodies.RubberBody; the ball part extended off |gamma| = 1 as c gamma, which
    changes nothing on N). The radicals q = sqrt(g.B g), s = sqrt(g1^2 + g2^2) are symbols
    with their derivatives. div(rho v)/rho on N is affine in (w1, w2) (the field is
    quadratic in omega), so it vanishes iff its value and its two slopes at omega = 0 do;
    each is reduced modulo q^2 - g.B g, s^2 - g1^2 - g2^2 and |gamma|^2 - 1 (a Groebner
    basis: the leading terms q^2, s^2, g3^2 are coprime). Returns the three remainders:
    all zero proves the density for these parameters. `density(r, P1, N2)` replaces
    log rho (a control: a wrong density leaves a remainder)."""
    q, s = sp.symbols("q s", positive=True)
    Bm = sp.diag(*B)
    BG = Bm * G
    u = sp.Matrix([g[0], g[1], 0])
    P = sp.diag(1, 1, 0)
    r = sp.Matrix(a) + c * G
    Jr = c * sp.eye(3)
    if any(B):
        r, Jr = r + BG / q, Jr + Bm / q - BG * BG.T / q ** 3
    if d:
        r, Jr = r + d * u / s, Jr + d * (P / s - u * u.T / s ** 3)
    v = body_field(I, m, gravity, r, Jr=Jr)

    def total(f, j):   # d/dg_j with q and s functions of gamma
        return sp.diff(f, g[j]) + BG[j] / q * sp.diff(f, q) + u[j] / s * sp.diff(f, s)

    P1 = I[0] + m * r.dot(r)
    N2 = I[0] * g[2] ** 2 + I[2] * (g[0] ** 2 + g[1] ** 2) + m * r.dot(G) ** 2
    log_rho = density(r, P1, N2) if density else sp.log(P1) + sp.log(N2) / 2
    expr = sum(sp.diff(v[i], X[i]) for i in range(3)) + sum(
        total(log_rho, j) * v[3 + j] for j in range(3))
    expr = expr.subs(w[2], -(w[0] * g[0] + w[1] * g[1]) / g[2])
    zero = {w[0]: 0, w[1]: 0}
    basis = [q ** 2 - G.dot(BG), s ** 2 - g[0] ** 2 - g[1] ** 2,
             g[2] ** 2 + g[0] ** 2 + g[1] ** 2 - 1]
    out = []
    for part in (expr.subs(zero), sp.diff(expr, w[0]).subs(zero),
                 sp.diff(expr, w[1]).subs(zero)):
        num = sp.expand(sp.numer(sp.together(part)))
        out.append(sp.reduced(num, basis, q, s, g[2], g[0], g[1])[1] if num != 0 else 0)
    return out


def main():
    """Every exact check with all parameters symbolic (the Routh measure takes minutes)."""
    checks = [
        ("rubber ball on a sphere, rho = (gamma, J^-1 gamma)^((1 - kR)/2)",
         ball_measure_residual),
        ("rubber ball on the plane, F = |M x gamma|^2", lambda: ball_integral_residual(0)),
        ("Routh ball on the plane, F = N omega3 (as F^2)", routh_integral_residual),
        ("Routh ball on the plane, rho = (I1 + m r^2) N", routh_measure_residual),
        ("ball with a gyrostat, any sphere, same rho",
         lambda: ball_measure_residual(gyrostat=True)),
        ("ball with a gyrostat on the plane, F = |(M + S) x gamma|^2",
         ball_gyrostat_integral_residual),
        ("ball in a Brun field on the plane, same rho",
         lambda: ball_measure_residual(0, brun=True)),
        ("ball in a Brun field on the plane, F = |M x gamma|^2 - eps det J Q",
         ball_brun_integral_residual),
        ("ball at kR = 2, F = P / Q", shell_integral_residual),
    ]
    for name, check in checks:
        print(f"{name}: residual on N = {check()}")


if __name__ == "__main__":
    main()
