"""Section 1 (equations of motion, energy, geometric integral) and the integrals every
(M, gamma) model shares."""


from solvers.verify.registry import formula


def _omega(P, x):
    return P.omega(x[:3], x[3:6])


@formula("energy")
def energy(P, x):
    """eq1.7: H = (M, omega)/2 + U, U = m g (r, gamma) + eps/2 (I gamma, gamma)."""
    M, g = x[:3], x[3:6]
    return 0.5 * (M @ _omega(P, x)) + P.m * P.g * (P.r(g) @ g) + 0.5 * P.eps * (P.I * g @ g)


@formula("geometric")
def geometric(P, x):
    return x[3:6] @ x[3:6]


@formula("area")
def area(P, x):
    return x[:3] @ x[3:6]


@formula("M2")
def m2(P, x):
    return x[:3] @ x[:3]
