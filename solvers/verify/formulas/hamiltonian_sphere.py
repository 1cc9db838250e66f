"""The project's Hamiltonian forms of the reduced systems on a sphere (Table 2, "Hamiltonian
form" row, columns 6-9). The paper asserts them ("we do not present the corresponding
calculations because of their bulkiness", after (3.4)) but prints no bracket; every formula
here is the PROJECT's, derived in docs/hamiltonian-sphere.md, by analogy with the plane's
theorem on (2.8).

The construction. Reduced variables x = (s, K1, K2, K3): s = gamma3 (body of revolution, disk,
Routh ball; K1, K2 of (3.3), K3 of (2.5)) or s = u = r1^2 + r2^2 (flat base; K1, K2 after
(3.21), K3 = (r1 M2 - r2 M1)/sqrt(u (I1 + m z^2 + m u))). In them

  * the energy is H = K3^2/2 + T(s, K1, K2) + U(s)     (K3 carries the whole ds/dt share),
  * ds/dt = N(s) K3                                      (N is read off the full field),
  * dK/ds = A(s) K + b(s)                                ((3.4) / (3.14) corrected / (3.6) /
                                                          (3.15) corrected / (3.26)).

Take the bivector J = X ^ d/dK3 with X = d/ds + (A K + b) . d/dK, i.e.

  {s, K3} = 1,  {K1, K3} = (dK/ds)_1,  {K2, K3} = (dK/ds)_2,  all others 0

(on the plane this IS (2.8): its entries are the right members of (2.13)). It is Poisson for
any A, b: [X, d/dK3] = 0. After d tau = N dt the reduced field is {x, H}: the first three
components by construction, the K3 component because H is conserved. The Casimirs are the
two integrals linear in K (solutions of the linear system); rank 2.

N is the reducing multiplier: A(s) is trace-free in every case here (on a body of
revolution the K2 coefficient of (3.4)'s K2 equation, g3 f2' + sqrt(1-g3^2)(f1
sqrt(1-g3^2))', vanishes identically by the meridian relation (2.2)), so the
tau-field J grad H is divergence-free and 1/N is an invariant density of the reduced system,
exactly as on the plane (N = k of (2.6), density 1/k).

k is CONVENTIONS.md's signed curvature; on the flat base R = 1/k (signed), as in reduced.py.
"""

import functools

import numpy as np

from solvers.models import reduced_systems as rd
from solvers.models.revolution import profile
from solvers.verify.formulas.chaplygin import eps_dot, g_eq2_25
from solvers.verify.formulas.reduced_plane import body, potential
from solvers.verify.formulas.sphere_bodies import factor_312
from solvers.verify.registry import formula
from solvers.verify.variables import chaplygin_rho


def _bivector(x, dK):
    """J = X ^ d/dK3 in x = (s, K1, K2, K3), X = d/ds + dK . d/dK (antisymmetric 4 x 4)."""
    J = np.zeros((4, 4), dtype=np.result_type(x[0], x[1], x[2], dK[0], dK[1], float))
    J[0, 3] = 1.0
    J[1, 3] = dK[0]
    J[2, 3] = dK[1]
    return J - J.T


# --- body of revolution, round disk (any profile of the family) ----------------------------

@formula("sphere_revolution_bracket")
def sphere_revolution_bracket(P, x):
    """Project's bracket: {g3, K3} = 1, {K1, K3} = dK1/dg3, {K2, K3} = dK2/dg3 with the
    right members of (3.14) (corrected sign of the gyrostat term; at s = 0 it is (3.4))."""
    return _bivector(x, rd.eq3_10(body(P), x[0], x[1:3]))


@formula("sphere_revolution_hamiltonian")
def sphere_revolution_hamiltonian(P, x):
    """H = K3^2/2 + the K-part of the energy after (3.4) + U: (2.7) with K1 replaced by
    K1/(1 - k f1) ((3.3) rescales K1 by (1 - k f1))."""
    b = body(P)
    f1 = profile(b.prof, x[0])[0]
    xp = np.array([x[0], x[1] / (1 - b.k * f1), x[2], x[3]])
    return rd.energy(b, xp, lambda s: potential(P, s))


@formula("sphere_revolution_time_change")
def sphere_revolution_time_change(P, x):
    """d tau = N dt, N = k_p/(1 - k f2'), k_p = sqrt((1 - g3^2)/(I1 + m r^2)) the plane's
    multiplier of (2.6): d g3/dt (1 - k f2') = (gamma x omega)_3 = k_p K3 on a sphere."""
    b = body(P)
    f2p = profile(b.prof, x[0])[3]
    return rd.kappa(b, x[0]) / (1 - b.k * f2p) + 0.0 * x[1]


def sphere_revolution_reduced_density(P, x):
    """1/N: the invariant density of the reduced system in (g3, K1, K2, K3) (the reducing
    multiplier's reciprocal, as 1/k is on the plane)."""
    return 1.0 / sphere_revolution_time_change(P, x)


# --- Routh ball, from the paper's own linear systems (3.6) / (3.15) ------------------------

@formula("sphere_routh_bracket")
def sphere_routh_bracket(P, x):
    """Project's bracket for the ball with displaced centre: {g3, K3} = 1 and {K_i, K3} the
    right members of (3.15) (corrected: no factor R in the K1 gyrostat term; s = 0: (3.6)),
    {K1, K3} = -rho kR (I1 - I3)(1 - kR) K2 - (1 - kR)^2 s,
    {K2, K3} = rho k m R^3/(1 - kR) K1 - rho m R (1 - kR)(R g3 + a) s."""
    return _bivector(x, rd.eq3_11(body(P), x[0], x[1:3]))


# --- flat base, axisymmetric (I1 = I2, centre of mass on the axis) --------------------------

def _flat(P):
    I1, I3 = P.I[0], P.I[2]
    return I1, I3, P.m, P.z, 1.0 / P.k


@formula("flat_axisym_bracket")
def flat_axisym_bracket(P, x):
    """Project's bracket in (u, K1, K2, K3): {u, K3} = 1, {K_i, K3} = dK_i/du of (3.26)
    ((3.22) corrected at s = 0)."""
    return _bivector(x, rd.eq3_21(P.p, x[0], x[1:3]))


@formula("flat_axisym_hamiltonian")
def flat_axisym_hamiltonian(P, x):
    """H = K3^2/(2 u (I1 + m z^2 + m u)) + ((I1 + m z^2) K1^2 + (I1 u + I3 z^2) K2^2
    - 2 z sq K1 K2)/(2 I1^2 u), sq = sqrt(I3 (I1 + m z^2) + I1 m u) ((3.25) with its
    corrected K1 K2 term, its udot^2 term written with K3 = r1 M2 - r2 M1; no field on the
    flat base)."""
    I1, I3, m, z, _ = _flat(P)
    u, K1, K2, K3 = x
    sq = np.sqrt(I3 * (I1 + m * z * z) + I1 * m * u)
    T = ((I1 + m * z * z) * K1 * K1 + (I1 * u + I3 * z * z) * K2 * K2
         - 2 * z * sq * K1 * K2) / (2 * I1 * I1 * u)
    return 0.5 * K3 * K3 / (u * (I1 + m * z * z + m * u)) + T


@formula("flat_axisym_time_change")
def flat_axisym_time_change(P, x):
    """d tau = N dt, N = 2 R u: du/dt = 2R (r1 w2 - r2 w1) (3.17) = 2R K3/(I1 + m z^2 + m u)
    = N dH/dK3."""
    return 2 * (1.0 / P.k) * x[0] + 0.0 * x[1]


def flat_axisym_reduced_density(P, x):
    """1/N: invariant density of the reduced flat-base system in (u, K1, K2, K3)."""
    return 1.0 / flat_axisym_time_change(P, x)


# --- the Borisov-Fedorov ball ((3.10) at a = 2R) ---------------------------------------------
# Two constructions, derived in docs/hamiltonian-sphere.md:
#   * bf_candidate_bracket: (2.25) carried to (3.10)'s factor k. It generates the flow for
#     every k but is not Poisson at k = -1 (claim .../project/attempt/plane-bracket).
#   * bf_level0_bracket: the Lie-Poisson e(3) bracket pulled back through the linear map
#     L = K(gamma) M below. Poisson by construction (a pull-back), Casimirs gamma^2 and
#     F = (M, Abar gamma) of (3.11); after d tau = N dt it generates (3.10) at k = -1 ON THE
#     LEVEL F = 0 ONLY (claim .../project); off that level it does not (.../attempt/all-levels).

@formula("bf_plane_bracket_carried")
def bf_candidate_bracket(P, x):
    """(2.25) (with the sign that generates the flow) carried to (3.10)'s factor k:
    {M_i, M_j} = -eps_ijk rho^-1 (M_k - k g gamma_k), {M_i, gamma_j} = -k eps_ijk rho^-1
    gamma_k, {gamma_i, gamma_j} = 0, g = D (omega, gamma), rho of (2.24). By construction
    rho J grad H = the field of (3.10) for every k (H = (M, omega)/2); at k = 1 it is the
    plane's bracket, which is Poisson. At k = -1 (Borisov-Fedorov) it is NOT: the Jacobiator
    is of relative size 0.1-0.6, and no conformal factor f(M, gamma) repairs it (the
    Jacobiator is not of the form Y ^ J)."""

    k = factor_312(P)
    M, g = x[:3], x[3:6]
    irho = 1.0 / chaplygin_rho(P, g)
    top = -irho * eps_dot(M - k * g_eq2_25(P, M, g) * g)
    mg = -k * irho * eps_dot(g)
    return np.block([[top, mg], [mg, 0.0 * mg]])


def _bf_map_build():
    """(K, dK) as NumPy functions of (gamma, I1, I2, I3, D): L = K(gamma) M and
    dK[j] = dK/dgamma_j, built once with sympy (complex-safe: the checks differentiate the
    bracket again by complex step, so dK must be exact, not a finite difference).

    K = N (E - gamma gamma^T/|gamma|^2)(E - w gamma^T) + gamma (Abar gamma)^T with
      Abar = E - 2 J/tr J, J = I + D (3.11), w = J Abar gamma/(I gamma, Abar gamma),
      N = rho (I gamma, Abar gamma)/(JJ Abar gamma, Abar gamma), JJ = J - D gamma gamma^T
      (the operator of (3.10): M = JJ omega), rho of (2.24).
    Why this K: on F = 0, (M - (M, gamma) w) is, turned by gamma x, the momentum of the
    2-degree-of-freedom system on the sphere of gamma; N is the density of the invariant
    measure ((2.24) restricted to F = 0) in (gamma, momentum): Chaplygin's reducing
    multiplier, so L = N x momentum is the canonical e(3) variable at (L, gamma) = 0."""
    import sympy as sp  # lazy: sympy, not loaded by solvers.verify.run nor at server start

    g = sp.Matrix(sp.symbols("g1:4"))
    I1, I2, I3, D = sp.symbols("I1 I2 I3 D")
    Iv = sp.Matrix([I1, I2, I3])
    Jv = Iv + sp.Matrix([D, D, D])
    trJ = sum(Jv)
    ab = sp.Matrix([(1 - 2 * Jv[i] / trJ) * g[i] for i in range(3)])          # Abar gamma
    g2 = (g.T * g)[0]
    Ig_ab = sum(Iv[i] * g[i] * ab[i] for i in range(3))
    JJab = sp.Matrix([Jv[i] * ab[i] for i in range(3)]) - D * g * (g.T * ab)[0]
    rho = 1 / sp.sqrt(1 - D * sum(g[i] ** 2 / Jv[i] for i in range(3)))
    N = rho * Ig_ab / (JJab.T * ab)[0]
    w = sp.Matrix([Jv[i] * ab[i] for i in range(3)]) / Ig_ab
    E = sp.eye(3)
    K = N * (E - g * g.T / g2) * (E - w * g.T) + g * ab.T
    args = (*g, I1, I2, I3, D)
    Kf = sp.lambdify(args, K, modules="numpy", cse=True)
    dKf = sp.lambdify(args, [K.diff(g[j]) for j in range(3)], modules="numpy", cse=True)
    return Kf, dKf


_bf_map = functools.cache(_bf_map_build)


def _bf_args(P, g):
    return (g[0], g[1], g[2], P.I[0], P.I[1], P.I[2], P.D)


def bf_level0_map(P, x):
    """(L, gamma) = (K(gamma) M, gamma): the map whose e(3) pull-back is bf_level0_bracket.
    (L, gamma) = |gamma|^2 F, so on the sphere the e(3) Casimir (L, gamma) is (3.11)'s F."""
    K = np.asarray(_bf_map()[0](*_bf_args(P, x[3:6])))
    return np.concatenate([K @ x[:3], x[3:6]])


@formula("bf_level0_bracket")
def bf_level0_bracket(P, x):
    """The e(3) bracket {L_i, L_j} = eps_ijk L_k, {L_i, gamma_j} = eps_ijk gamma_k,
    {gamma_i, gamma_j} = 0 (the sign of (2.27); it generates the flow forward in tau),
    pulled back to (M, gamma) through L = K(gamma) M: with A = dx/dy = [[K^-1, -K^-1 C], [0, E]],
    C_ij = (dK/dgamma_j M)_i, the tensor is A Pi(y) A^T. Poisson because it is a pull-back."""

    M, g = x[:3], x[3:6]
    Kf, dKf = _bf_map()
    a = _bf_args(P, g)
    K = np.asarray(Kf(*a))
    C = np.stack([np.asarray(dk) @ M for dk in dKf(*a)], axis=1)
    Ki = np.linalg.inv(K)
    L = K @ M
    Z = np.zeros((3, 3), dtype=Ki.dtype)
    A = np.block([[Ki, -Ki @ C], [Z, np.eye(3)]])
    Pi = np.block([[eps_dot(L), eps_dot(g)], [eps_dot(g), 0.0 * Z]])
    return A @ Pi @ A.T


@formula("bf_level0_time_change")
def bf_level0_time_change(P, x):
    """d tau = N dt, N = rho (I gamma, Abar gamma)/(JJ Abar gamma, Abar gamma) (see _bf_map):
    the density of the measure (2.24) on the level F = 0, written in (gamma, momentum)."""
    g = x[3:6]
    J = P.I + P.D
    ab = (1.0 - 2.0 * J / np.sum(J)) * g
    JJab = J * ab - P.D * g * (g @ ab)
    return chaplygin_rho(P, g) * ((P.I * g) @ ab) / (JJab @ ab) + 0.0 * x[0]


@formula("bf_level0_hamiltonian")
def bf_level0_hamiltonian(P, x):
    """H = (M, omega)/2 with (3.10)'s M = (I + D) omega - D gamma (omega, gamma) (the energy
    after (3.10), no field)."""
    M, g = x[:3], x[3:6]
    JJ = np.diag(P.I + P.D) - P.D * np.outer(g, g)
    return 0.5 * (M @ np.linalg.solve(JJ, M))
