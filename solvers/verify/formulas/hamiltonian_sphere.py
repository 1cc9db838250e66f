"""The project's Hamiltonian forms of the reduced systems on a sphere (Table 2, "Hamiltonian
form" row, columns 6-9). The paper asserts them ("we do not present the corresponding
calculations because of their bulkiness", after eq3.3) but prints no bracket; every formula
here is the PROJECT's, derived in docs/hamiltonian-sphere.md, by analogy with the plane's
theorem on eq2-*3.

The construction. Reduced variables x = (s, K1, K2, K3): s = gamma3 (body of revolution, disk,
Routh ball; K1, K2 of eq3.2-1, K3 of eq2.4) or s = u = r1^2 + r2^2 (flat base; K1, K2 after
eq3.18, K3 = (r1 M2 - r2 M1)/sqrt(u (I1 + m z^2 + m u))). In them

  * the energy is H = K3^2/2 + T(s, K1, K2) + U(s)     (K3 carries the whole ds/dt share),
  * ds/dt = N(s) K3                                      (N is read off the full field),
  * dK/ds = A(s) K + b(s)                                (eq3.3 / eq3.10 corrected / eq3.7 /
                                                          eq3.11 corrected / eq3.21).

Take the bivector J = X ^ d/dK3 with X = d/ds + (A K + b) . d/dK, i.e.

  {s, K3} = 1,  {K1, K3} = (dK/ds)_1,  {K2, K3} = (dK/ds)_2,  all others 0

(on the plane this IS eq2-*3: its entries are the right members of eq2.5). It is Poisson for
any A, b: [X, d/dK3] = 0. After d tau = N dt the reduced field is {x, H}: the first three
components by construction, the K3 component because H is conserved. The Casimirs are the
two integrals linear in K (solutions of the linear system); rank 2.

N is the reducing multiplier: A(s) is trace-free in every case here (on a body of
revolution the K2 coefficient of eq3.3's K2 equation, g3 f2' + sqrt(1-g3^2)(f1
sqrt(1-g3^2))', vanishes identically by the meridian relation eq2.1/2), so the
tau-field J grad H is divergence-free and 1/N is an invariant density of the reduced system,
exactly as on the plane (N = k of eq2-*1, density 1/k).

k is CONVENTIONS.md's signed curvature; on the flat base R = 1/k (signed), as in reduced.py.
"""

import numpy as np

from solvers.models import reduced as rd
from solvers.models.revolution import profile
from solvers.verify.formulas.reduced_plane import body, potential
from solvers.verify.registry import formula


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
    right members of eq3.10 (corrected sign of the gyrostat term; at s = 0 it is eq3.3)."""
    return _bivector(x, rd.eq3_10(body(P), x[0], x[1:3]))


@formula("sphere_revolution_hamiltonian")
def sphere_revolution_hamiltonian(P, x):
    """H = K3^2/2 + the K-part of the energy after eq3.3 + U: eq2-*2 with K1 replaced by
    K1/(1 - k f1) (eq3.2-1 rescales K1 by (1 - k f1))."""
    b = body(P)
    f1 = profile(b.prof, x[0])[0]
    xp = np.array([x[0], x[1] / (1 - b.k * f1), x[2], x[3]])
    return rd.energy(b, xp, lambda s: potential(P, s))


@formula("sphere_revolution_time_change")
def sphere_revolution_time_change(P, x):
    """d tau = N dt, N = k_p/(1 - k f2'), k_p = sqrt((1 - g3^2)/(I1 + m r^2)) the plane's
    multiplier of eq2-*1: d g3/dt (1 - k f2') = (gamma x omega)_3 = k_p K3 on a sphere."""
    b = body(P)
    f2p = profile(b.prof, x[0])[3]
    return rd.kappa(b, x[0]) / (1 - b.k * f2p) + 0.0 * x[1]


def sphere_revolution_reduced_density(P, x):
    """1/N: the invariant density of the reduced system in (g3, K1, K2, K3) (the reducing
    multiplier's reciprocal, as 1/k is on the plane)."""
    return 1.0 / sphere_revolution_time_change(P, x)


# --- Routh ball, from the paper's own linear systems eq3.7 / eq3.11 ------------------------

@formula("sphere_routh_bracket")
def sphere_routh_bracket(P, x):
    """Project's bracket for the ball with displaced centre: {g3, K3} = 1 and {K_i, K3} the
    right members of eq3.11 (corrected: no factor R in the K1 gyrostat term; s = 0: eq3.7),
    {K1, K3} = -rho kR (I1 - I3)(1 - kR) K2 - (1 - kR)^2 s,
    {K2, K3} = rho k m R^3/(1 - kR) K1 - rho m R (1 - kR)(R g3 + a) s."""
    return _bivector(x, rd.eq3_11(body(P), x[0], x[1:3]))


# --- flat base, axisymmetric (I1 = I2, centre of mass on the axis) --------------------------

def _flat(P):
    I1, I3 = P.I[0], P.I[2]
    return I1, I3, P.m, P.z, 1.0 / P.k


@formula("flat_axisym_bracket")
def flat_axisym_bracket(P, x):
    """Project's bracket in (u, K1, K2, K3): {u, K3} = 1, {K_i, K3} = dK_i/du of eq3.21
    (eq3.19 corrected at s = 0)."""
    return _bivector(x, rd.eq3_21(P.p, x[0], x[1:3]))


@formula("flat_axisym_hamiltonian")
def flat_axisym_hamiltonian(P, x):
    """H = K3^2/(2 u (I1 + m z^2 + m u)) + ((I1 + m z^2) K1^2 + (I1 u + I3 z^2) K2^2
    - 2 z sq K1 K2)/(2 I1^2 u), sq = sqrt(I3 (I1 + m z^2) + I1 m u) (eq-***3 with its
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
    """d tau = N dt, N = 2 R u: du/dt = 2R (r1 w2 - r2 w1) (eq3.15) = 2R K3/(I1 + m z^2 + m u)
    = N dH/dK3."""
    return 2 * (1.0 / P.k) * x[0] + 0.0 * x[1]


def flat_axisym_reduced_density(P, x):
    """1/N: invariant density of the reduced flat-base system in (u, K1, K2, K3)."""
    return 1.0 / flat_axisym_time_change(P, x)


# --- the Borisov-Fedorov ball (eq3.12 at a = 2R): what the project tried -------------------
# Not a registered formula and not a claim: the cell "the system is Hamiltonian after the
# change of time (A. V. Borisov, I. S. Mamaev, 2000)" stays unchecked (the bracket is in
# another paper). This candidate is recorded so the failure is reproducible
# (tests/test_hamiltonian_sphere.py::test_bf_candidate_generates_the_flow_but_is_not_poisson).

def bf_candidate_bracket(P, x):
    """eq2b-*1 (with the sign that generates the flow) carried to eq3.12's factor k:
    {M_i, M_j} = -eps_ijk rho^-1 (M_k - k g gamma_k), {M_i, gamma_j} = -k eps_ijk rho^-1
    gamma_k, {gamma_i, gamma_j} = 0, g = D (omega, gamma), rho of eq2.17. By construction
    rho J grad H = the field of eq3.12 for every k (H = (M, omega)/2); at k = 1 it is the
    plane's bracket, which is Poisson. At k = -1 (Borisov-Fedorov) it is NOT: the Jacobiator
    is of relative size 0.1-0.6, and no conformal factor f(M, gamma) repairs it (the
    Jacobiator is not of the form Y ^ J)."""
    from solvers.verify.formulas.chaplygin import _g, eps_dot
    from solvers.verify.formulas.sphere_bodies import factor_312
    from solvers.verify.variables import chaplygin_rho

    k = factor_312(P)
    M, g = x[:3], x[3:6]
    irho = 1.0 / chaplygin_rho(P, g)
    top = -irho * eps_dot(M - k * _g(P, M, g) * g)
    mg = -k * irho * eps_dot(g)
    return np.block([[top, mg], [mg, 0.0 * mg]])
