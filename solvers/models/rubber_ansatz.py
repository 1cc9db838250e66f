"""Search for first integrals of a rubber case among polynomials in (omega, gamma).

Ansatz: F = sum of c_j * phi_j with phi_j = omega^alpha * gamma^beta, |alpha| <= d_omega,
|beta| <= d_gamma (all mixed degrees, so that a potential term in gamma alone is included).
Only bodies with a polynomial r(gamma) (balls: Chaplygin, unbalanced, Routh) have their
energy inside such an ansatz; for the others a count of zero says little.

F is an integral on N = {(omega, gamma) = 0, |gamma| = 1} iff dF/dt = sum c_j dphi_j/dt
vanishes on N. The derivatives dphi_j/dt (complex step along the field) at n random points
of N give a matrix; its numerical null space (singular values below 1e-9 of the largest)
holds the candidate integrals. Combinations that are constant on N (multiples of
(omega, gamma) and of |gamma|^2 - 1, the energy times |gamma|^2, ...) are removed by asking
that their values at the same points vary; the count returned is the number of independent
non-constant integrals of the ansatz, counted modulo constants on N.

This is a numerical search (double precision, random points), not an exact proof: a count
says what the ansatz holds up to round-off; exact proofs of what it finds live in
rubber_exact.py.
"""

from __future__ import annotations

import itertools

import numpy as np

from solvers.models import rubber_lagrange as rl
from solvers.models.rubber_bodies import RubberBody, body

H = 1e-30


def _monomials(d_omega: int, d_gamma: int):
    out = []
    for da in range(d_omega + 1):
        for a, d in itertools.product(itertools.combinations_with_replacement(range(3), da),
                                      range(d_gamma + 1)):
            for c in itertools.combinations_with_replacement(range(3), d):
                if a or c:                  # the constant 1 is no integral worth counting
                    out.append((a, c))
    return out


def _eval(monos, w, g):
    return np.array([np.prod([w[i] for i in a]) * np.prod([g[k] for k in c]) for a, c in monos])


def ball_Q(b: RubberBody, g):
    """Q = (gamma, J^-1 gamma), J = I + m R^2: the ball's measure is a power of Q."""
    return np.sum(g * g / (np.array(b.I) + b.m * b.c ** 2))


def count_integrals(b: RubberBody, d_omega: int, d_gamma: int, n_points: int | None = None,
                    seed: int = 0, q_power: float = 0.0) -> tuple[int, int]:
    """(independent non-constant integrals on N, size of the ansatz). With q_power = s != 0
    the ansatz is F = P * Q^s, P polynomial as above (balls only): dF/dt = 0 iff
    Q dP/dt + s P dQ/dt = 0, again linear in P's coefficients."""
    monos = _monomials(d_omega, d_gamma)
    n_points = n_points or 3 * len(monos) + 20
    rng = np.random.default_rng(seed)
    rates, values = [], []
    for _ in range(n_points):
        g = rng.normal(size=3)
        if b.d:
            g[2] *= 0.3
        y = rl.state_on_manifold(b, rng.normal(size=3), g)
        v = rl.field(b, y)
        yc = y + 1j * H * v
        phi = _eval(monos, rl.omega(b, y), y[3:])
        phi_dot = _eval(monos, rl.omega(b, yc), yc[3:]).imag / H
        if q_power:
            Q, Q_dot = ball_Q(b, y[3:]), ball_Q(b, yc[3:]).imag / H
            rates.append(Q * phi_dot + q_power * phi * Q_dot)
            values.append(phi * Q ** q_power)
        else:
            rates.append(phi_dot)
            values.append(phi)
    A = np.array(rates)
    A /= np.linalg.norm(A, axis=0, keepdims=True) + 1e-300
    V = np.array(values)
    _, S, Vt = np.linalg.svd(A)
    rank = int(np.sum(S > 1e-9 * S[0]))
    null = Vt[rank:]
    if null.shape[0] == 0:
        return 0, len(monos)
    scale = np.linalg.norm(np.array(rates), axis=0) + 1e-300
    F = V @ (null / scale).T
    F -= F.mean(axis=0)
    sv = np.linalg.svd(F, compute_uv=False)
    ref = np.linalg.norm(V @ (np.abs(null) / scale).T)
    return int(np.sum(sv > 1e-7 * ref)), len(monos)


SEARCHES = [
    (case, 2, d_gamma)
    for case in ("rubber-plane/chaplygin-ball", "rubber-plane/unbalanced-ball",
                 "rubber-plane/routh-ball", "rubber-sphere/ball-over", "rubber-sphere/ball-inside",
                 "rubber-sphere/shell-over-half-ball", "rubber-sphere/unbalanced-ball")
    for d_gamma in (2, 4)
]
# P / Q with P of omega-degree 2 exactly (the ball's energy is one: H = H Q / Q)
SEARCHES_OVER_Q = [("rubber-sphere/ball-over", k) for k in (0.0, -0.5, 0.4, 2.0, 3.0)]


def main():
    """The searches the rubber tables cite, one line each."""
    for case, d_omega, d_gamma in SEARCHES:
        n, size = count_integrals(body(case), d_omega, d_gamma)
        print(f"{case:40s} omega-degree <= {d_omega}, gamma-degree <= {d_gamma}: "
              f"{n} integral(s) among {size} monomials")
    for case, k in SEARCHES_OVER_Q:
        n, size = count_integrals(body(case, k=k), 2, 2, q_power=-1.0)
        print(f"{case:40s} kR = {k:+.1f}, P/Q, omega-degree <= 2, gamma-degree <= 2: "
              f"{n} integral(s) among {size} monomials")


if __name__ == "__main__":
    main()
