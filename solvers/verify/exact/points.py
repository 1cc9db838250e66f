"""Random rational points: parameters, a rational gamma on the unit sphere, and square
roots made rational by solving one parameter.

Every free coordinate is drawn uniformly from a grid of N = 2^BITS distinct rationals
(`GridRng`); the Schwartz-Zippel bound of certify.py counts on that. Parameters come from
the project's own draw (solvers.verify.params.draw, the conditions of each claim) fed with
this grid generator, so relations such as I1 = I2, I3 = 2 I1 or I3 = I1 + I2 hold exactly
(grid values are dyadic, their sums and doubles are exact floats) and are read as exact
rationals.
"""

from fractions import Fraction

import numpy as np

from solvers.kernels import layout as L
from solvers.verify.exact.jet import Jet, NotRational, q_of
from solvers.verify.exact.model import ExactParams

BITS = 64
N_GRID = 2 ** BITS


class GridRng:
    """The subset of numpy's Generator that params.draw uses, returning grid values
    lo + (hi - lo) a / 2^BITS with a uniform in [0, 2^BITS) (exact dyadic floats when lo and
    hi are)."""

    def __init__(self, seed):
        self.rng = np.random.default_rng(seed)

    def integer(self):
        return int(self.rng.integers(0, N_GRID, dtype=np.uint64))

    def grid(self, lo, hi):
        """An exact rational uniform on the grid of [lo, hi)."""
        lo, hi = q_of(lo), q_of(hi)
        return lo + (hi - lo) * self.integer() / N_GRID

    def uniform(self, lo=0.0, hi=1.0, size=None):
        if size is None:
            return float(Fraction(lo) + Fraction(hi - lo) * self.integer() / N_GRID)
        return np.array([self.uniform(lo, hi) for _ in range(size)])

    def choice(self, seq):
        return seq[int(self.rng.integers(0, len(seq)))]


def free(x):
    """A drawn free coordinate: degree 1 in z."""
    return Jet(q_of(x), None, 1, 0)


def pythagorean(t):
    """(c, s) = ((1 - t^2), 2 t) / (1 + t^2): a rational point of the unit circle."""
    t = Jet.const(t)
    den = 1 + t * t
    return (1 - t * t) / den, 2 * t / den


def stereographic(u, v):
    """Inverse stereographic projection from the north pole: a rational point of |gamma| = 1
    for every rational (u, v)."""
    u, v = Jet.const(u), Jet.const(v)
    n = 1 + u * u + v * v
    return np.array([2 * u / n, 2 * v / n, (u * u + v * v - 1) / n], dtype=object)


def sphere_point(t, w, flip=False):
    """gamma = (sin th cos ph, sin th sin ph, cos th) with (cos th, sin th), (cos ph, sin ph)
    Pythagorean in t, w: on |gamma| = 1 AND with g1^2 + g2^2 = sin^2 th a square, which the
    disk's sqrt(g1^2 + g2^2) (eq2.71) needs."""
    ct, st = pythagorean(t)
    cp, sp = pythagorean(w)
    g1 = st * cp
    return np.array([-g1 if flip else g1, st * sp, ct], dtype=object)


def rational_gamma(rng: GridRng, pole_margin=0.05):
    """A rational gamma away from the poles (|g3| < 1 - pole_margin, as the float checks)."""
    while True:
        t = free(rng.grid(Fraction(1, 8), 7))      # theta = 2 atan t in (0.25, 2.88)
        w = free(rng.grid(-3, 3))                  # phi = 2 atan w in (-2.5, 2.5)
        g = sphere_point(t, w, flip=rng.choice([False, True]))
        if abs(g[2].to_float()) < 1 - pole_margin:
            return g


def ellipsoid_radicand(p, g, rng: GridRng):
    """Make sqrt(gamma.B gamma) (eq2.28) rational: draw q on a fine grid near its float value
    and solve B33 = (q^2 - sum_{(i,j) != (3,3)} B_ij g_i g_j) / g3^2; the change of B33 is
    relative 2^-20 at most, so B stays positive definite and the body as drawn."""
    B = [[p[L.B11], p[L.B12], p[L.B13]], [p[L.B12], p[L.B22], p[L.B23]],
         [p[L.B13], p[L.B23], p[L.B33]]]
    q0 = sum(B[i][j].to_float() * g[i].to_float() * g[j].to_float()
             for i in range(3) for j in range(3))
    if q0 <= 0 or g[2] == 0:
        raise NotRational("gamma.B gamma <= 0")
    qf = Fraction(q0 ** 0.5).limit_denominator(2 ** 20)
    q = free(q_of(qf) * (1 + rng.grid(0, Fraction(1, 2 ** 20))))
    rest = sum(B[i][j] * g[i] * g[j] for i in range(3) for j in range(3) if (i, j) != (2, 2))
    return (q * q - rest) / (g[2] * g[2])


def exact_params(Pf, gamma, rng: GridRng) -> ExactParams:
    """The float draw Pf as exact rationals (its dyadic floats read exactly), with the
    ellipsoid part solved so that sqrt(gamma.B gamma) is rational at `gamma`."""
    pf = Pf.p
    p = np.array([free(x) if x != 0 else Jet(0) for x in pf], dtype=object)
    case = Pf.model.case
    if case.fixed_k == "2/R":
        p[L.CURV] = 2 / (p[L.BALL_C] if p[L.BALL_C] != 0 else p[L.DISK_D])
    if gamma is not None and any(pf[i] != 0 for i in (L.B11, L.B22, L.B33)):
        p[L.B33] = ellipsoid_radicand(p, gamma, rng)
    extra = {k: free(v) for k, v in Pf.model.params.items() if k in ("mu", "lambda")}
    # relations that build() imposes in floats, imposed again exactly (bodies.fill_inertia)
    if case.symmetry == "spherical" and "mu" in extra:
        p[L.I1] = p[L.I2] = p[L.I3] = extra["mu"]
    elif case.body == "ellipsoid" and "mu" in extra and "lambda" in extra:
        for i, b in ((L.I1, L.B11), (L.I2, L.B22), (L.I3, L.B33)):
            p[i] = extra["mu"] + extra["lambda"] * p[L.MASS] * p[b]     # eq2.29
    if gamma is not None and case.symmetry == "axial":
        axial_radicand(p, pf, gamma, rng)
    return ExactParams(Pf.model, p, extra)


def axial_radicand(p, pf, gamma, rng: GridRng):
    """Make sqrt(I1 + m r^2) rational (K3 of eq2.4 divides by sqrt((1 - g3^2)(I1 + m r^2)),
    and 1 - g3^2 = sin^2 th is already a square): draw q near its float value and solve
    I1 = I2 = q^2 - m r^2 (a relative change ~2^-20; I3 = I1 or I3 = 2 I1 kept where drawn so),
    so that the reduced variables need one irrational root (rho0's) only."""
    from solvers.verify.exact.model import support
    r, _ = support(p, np.asarray(gamma, dtype=object))
    mr2 = p[L.MASS] * (r @ r)
    q0 = (pf[L.I1] + mr2.to_float()) ** 0.5
    q = free(q_of(Fraction(q0).limit_denominator(2 ** 20))
             * (1 + rng.grid(0, Fraction(1, 2 ** 20))))
    I1 = q * q - mr2
    if I1.v <= 0:
        return
    if pf[L.I3] == pf[L.I1]:             # spherical inertia (I1 = I2 = I3) kept
        p[L.I3] = I1
    elif pf[L.I3] == 2 * pf[L.I1]:
        p[L.I3] = 2 * I1
    p[L.I1] = p[L.I2] = I1


def rational_state(Pf, rng: GridRng):
    """(exact params, exact state values) of one random point; float-validated like
    solvers.verify.params.random_states (pole margin, fit, disk not flat)."""
    from solvers.errors import InputError
    from solvers.models.bodies import check_state, tangent_fit
    for _ in range(200):
        M = [free(rng.grid(-2, 2)) for _ in range(3)]
        if Pf.model.model == L.MODEL_FULL:
            g = rational_gamma(rng)
            P = exact_params(Pf, g, rng)
            y = [*M, *g]
        elif Pf.model.model == L.MODEL_FLAT:
            P = exact_params(Pf, None, rng)
            y = [*M, free(rng.grid(-1, 1)), free(rng.grid(-1, 1))]
        else:
            raise NotRational(f"no rational states for model {Pf.model.model}")
        pf = np.array([x.to_float() for x in P.p])
        yf = np.array([x.to_float() for x in y])
        if Pf.model.model == L.MODEL_FULL and P.model.case.fixed_k is None and pf[L.CURV] != 0 \
                and tangent_fit(pf, yf[3:6]) <= 0.05:
            continue
        try:
            check_state(Pf.model.model, pf, yf, shell=Pf.model.case.fixed_k is not None)
        except InputError:
            continue
        return P, y
    raise NotRational("no valid rational point found")
