"""Section 2, Chaplygin ball on the plane: (2.23)-(2.27), Kozlov's Brun integral, Markeev's
gyrostat (2.38) (D = m a^2 with a the ball's radius: our P.R)."""

import numpy as np

from solvers.verify.formulas.general import dU, kinetic
from solvers.verify.registry import compares, corrected, formula
from solvers.verify.variables import chaplygin_rho

EPS = np.zeros((3, 3, 3))
for _i, _j, _k in ((0, 1, 2), (1, 2, 0), (2, 0, 1)):
    EPS[_i, _j, _k], EPS[_j, _i, _k] = 1.0, -1.0


def eps_dot(v):
    """The matrix (eps_ijk v_k)_ij."""
    return np.einsum("ijk,k->ij", EPS, v)


def _A(P):
    return 1.0 / (P.I + P.D)


def chaplygin_omega(P, M, g):
    """omega from (2.23)'s M = I omega + D gamma x (omega x gamma) (a linear solve)."""
    Q = np.diag(P.I) + P.D * ((g @ g) * np.eye(3) - np.outer(g, g))
    return np.linalg.solve(Q, M)


@formula("chaplygin_system")
def chaplygin_system(P, x):
    """(2.23): dM/dt = M x omega + gamma x dU/dgamma, dgamma/dt = gamma x omega,
    M = I omega + D gamma x (omega x gamma)."""
    M, g = x[:3], x[3:6]
    w = chaplygin_omega(P, M, g)
    return np.concatenate([np.cross(M, w) + np.cross(g, dU(P, g)), np.cross(g, w)])


@formula("chaplygin_density")
def chaplygin_density(P, x):
    """(2.24): rho = (1 - D (gamma, A gamma))^-1/2, A = (I + D E)^-1, D = m a^2."""
    return chaplygin_rho(P, x[3:6])


@formula("kozlov_brun_F3")
def kozlov_brun_f3(P, x):
    """After (2.24): F3 = M^2 - k/det A (gamma, A gamma); the paper's k is the Brun constant
    (our eps, U = eps/2 (I gamma, gamma))."""
    M, g = x[:3], x[3:6]
    A = _A(P)
    return M @ M - P.eps / np.prod(A) * (g @ (A * g))


@formula("brun_potential")
def brun_potential(P, x):
    """U = k/2 (I gamma, gamma), k the Brun constant (our eps)."""
    g = x[3:6]
    return 0.5 * P.eps * (P.I * g @ g)


@formula("chaplygin_time_change")
def chaplygin_time_change(P, x):
    """d tau = rho dt: returns the multiplier N = rho of d tau = N dt (rho of (2.24))."""
    return chaplygin_rho(P, x[3:6])


def g_eq2_25(P, M, gam):
    """g = D (gamma, A M) / (1 - D (gamma, A gamma)) of (2.25) (= D (omega, gamma))."""
    A = _A(P)
    return P.D * (gam @ (A * M)) / (1.0 - P.D * (gam @ (A * gam)))


@formula("chaplygin_bracket")
def chaplygin_bracket(P, x):
    """(2.25) as a 6 x 6 Poisson tensor in (M, gamma):
    {M_i, M_j} = eps_ijk rho^-1 (M_k - g gamma_k), {M_i, gamma_j} = eps_ijk rho^-1 gamma_k,
    {gamma_i, gamma_j} = 0."""
    M, g = x[:3], x[3:6]
    irho = 1.0 / chaplygin_rho(P, g)
    top = irho * eps_dot(M - g_eq2_25(P, M, g) * g)
    mg = irho * eps_dot(g)
    zero = 0.0 * mg
    return np.block([[top, mg], [mg, zero]])


# The Chaplygin-ball paragraph states no orientation of its bracket; the paper writes
# dx/dtau = {x, H} only for the body of revolution (the theorem on (2.8)). Under that
# orientation the printed sign gives the time-reversed field; under dx/dtau = {H, x} (the
# catalogue's holds_under) the printed bracket itself holds.
SIGN_NOTE = ("the opposite overall sign, {M_i, M_j} = −ε_ijk ... (equivalently the printed "
             "bracket read with dx/dτ = {H, x}): read with dx/dτ = {x, H}, the "
             "orientation the paper writes for the body of revolution (theorem on eq2-*3), "
             "the printed sign gives the time-reversed field, -v/rho")


@corrected("chaplygin_bracket", SIGN_NOTE)
def chaplygin_bracket_corrected(P, x):
    return -chaplygin_bracket(P, x)


@formula("chaplygin_hamiltonian_M")
def chaplygin_hamiltonian_m(P, x):
    """(2.26): H = (M, A M)/2 + g (A M, gamma)/2 + U(gamma)."""
    M, g = x[:3], x[3:6]
    A = _A(P)
    AM = A * M
    return 0.5 * (M @ AM) + 0.5 * g_eq2_25(P, M, g) * (AM @ g) + _potential(P, g)


def _potential(P, g):
    return P.m * P.g * (P.r(g) @ g) + 0.5 * P.eps * (P.I * g @ g)


@formula("chaplygin_bracket_K")
def chaplygin_bracket_k(P, x):
    """(2.27) in (K, gamma), K = rho M: {K_i, K_j} = eps_ijk (K_k - D rho^2 (K, gamma) a_k
    gamma_k), {K_i, gamma_j} = eps_ijk gamma_k, {gamma_i, gamma_j} = 0; a_k (not defined in
    the text) read as the diagonal of A = (I + D E)^-1."""
    K, g = x[:3], x[3:6]
    rho = chaplygin_rho(P, g)
    top = eps_dot(K - P.D * rho**2 * (K @ g) * _A(P) * g)
    kg = eps_dot(g)
    return np.block([[top, kg], [kg, 0.0 * kg]])


@corrected("chaplygin_bracket_K", SIGN_NOTE)
def chaplygin_bracket_k_corrected(P, x):
    return -chaplygin_bracket_k(P, x)


def _e3_bracket(x):
    """The Lie-Poisson tensor of e(3): {K_i, K_j} = eps_ijk K_k, {K_i, gamma_j} = eps_ijk
    gamma_k, {gamma_i, gamma_j} = 0."""
    K, g = x[:3], x[3:6]
    kg = eps_dot(g)
    return np.block([[eps_dot(K), kg], [kg, 0.0 * kg]])


@compares("chaplygin_bracket_K")
def chaplygin_bracket_k_zero_level(P, x, corrected=False):
    """'at the zero level (K, gamma) = 0 bracket (2.27) passes to e(3)': the random point is
    moved onto the level (K -> K - (K, gamma) gamma / gamma^2) and both tensors compared."""
    K, g = x[:3], x[3:6]
    y = np.concatenate([K - (K @ g) / (g @ g) * g, g])
    return chaplygin_bracket_k(P, y), _e3_bracket(y)


@formula("chaplygin_hamiltonian_K")
def chaplygin_hamiltonian_k(P, x):
    """(2.27): H = rho^-2 (K, A K)/2 + D (A K, gamma)^2/2 + U(gamma)."""
    K, g = x[:3], x[3:6]
    A = _A(P)
    rho = chaplygin_rho(P, g)
    return 0.5 * (K @ (A * K)) / rho**2 + 0.5 * P.D * ((A * K) @ g) ** 2 + _potential(P, g)


# --- Markeev's gyrostat, (2.38) ---------------------------------------------------------------

@formula("markeev_system")
def markeev_system(P, x):
    """(2.38): dM/dt = (M + S) x omega, dgamma/dt = gamma x omega (the printed dot on gamma
    is missing), omega of the Chaplygin ball (U = 0)."""
    M, g = x[:3], x[3:6]
    w = chaplygin_omega(P, M, g)
    return np.concatenate([np.cross(M + P.S, w), np.cross(g, w)])


@formula("markeev_energy")
def markeev_energy(P, x):
    """(2.38): H = (M, omega)/2."""
    return kinetic(P, x)


@formula("markeev_F2")
def markeev_f2(P, x):
    """(2.38): F2 = (M + S, M + S)."""
    MS = x[:3] + P.S
    return MS @ MS


@formula("markeev_F3")
def markeev_f3(P, x):
    """(2.38): F3 = (M + S, gamma)."""
    return (x[:3] + P.S) @ x[3:6]
