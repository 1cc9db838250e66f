"""Random rational points: parameters, a rational gamma on the unit sphere, and square
roots made rational by solving one parameter.

Every free coordinate is drawn uniformly from a grid of N = N_GRID = 2^BITS distinct exact
rationals lo + (hi - lo) a / 2^BITS, a uniform in [0, 2^BITS) (`GridRng`); the
Schwartz-Zippel bound of certify.py counts on that. Parameters come from the project's own
draw (solvers.verify.params.draw, the conditions of each claim) fed with this generator:
`GridRng.uniform` returns an exact grid rational (`Drawn`, a jet of degree 1), every product
and sum the draw makes of them is exact, and the parameter vector is filled from the drawn
values by the project's own bodies.fill_inertia / fill_body, exactly (`exact_slots`). So
relations such as I1 = I2, I3 = 2 I1, I3 = I0 u or I = mu E + lambda m B (2.40) hold
exactly, and the parameters are polynomials (of tracked degree) in grid draws.

One value is a scale, not a coordinate: params.draw scales the curvature by
1 / max(R, sqrt(max(b1, b3)), 1), and a square root of a drawn value is not rational; it is
read as the float it is (`Drawn.sqrt`), so k = +-size u with size a fixed rational given the
earlier draws, uniform over N distinct values: a coordinate in its own right (the
Schwartz-Zippel lemma allows a coordinate's set to depend on the coordinates drawn before).

The points are seeded by the claim id (certify.run_points): every certificate is
reproducible, but the points are not random against someone who picks a formula after
seeing them.
"""

from contextlib import contextmanager
from fractions import Fraction

import numpy as np

import solvers.verify.params as params_mod
from solvers.errors import InputError
from solvers.kernels import layout as L
from solvers.models.bodies import check_state, fill_body, fill_inertia, tangent_fit
from solvers.models.cases import PARAM_SLOTS, get_case
from solvers.verify.exact.jet import Jet
from solvers.verify.exact.model import ExactParams, support
from solvers.verify.exact.rational import NotRational, q_of
from solvers.verify.exact.symbolic import S, mark, release, symbol

BITS = 64
N_GRID = 2 ** BITS


def _drawn_op(name):
    op = getattr(Jet, name)

    def f(self, *a):
        # on plain jets: a Drawn operand would make Python try the subclass's reflected
        # method first, and that one would call back here
        r = op(self.jet(), *(x.jet() if isinstance(x, Drawn) else x for x in a))
        if type(r) is Jet:
            r.__class__ = Drawn
        return r
    f.__name__ = name
    return f


class Drawn(Jet):
    """A parameter while params.draw and bodies.fill_* compute with it: an exact jet that
    the draw may also read as a float (its validity checks, the model build). Never seen by
    a formula: `exact_slots` turns every value into a plain Jet, whose float() raises."""
    __slots__ = ()

    def __float__(self):
        return self.to_float()

    def sqrt(self):
        # params.draw's curvature scale (see the module docstring): a rational read of the
        # float root; the coordinate is then k itself
        return float(np.sqrt(self.to_float()))

    def jet(self) -> Jet:
        return Jet(self.v, self.g, self.n, self.d, self.unknown)


for _name in ("__add__", "__radd__", "__sub__", "__rsub__", "__mul__", "__rmul__",
              "__truediv__", "__rtruediv__", "__neg__", "__pow__", "__abs__"):
    setattr(Drawn, _name, _drawn_op(_name))


class GridRng:
    """The subset of numpy's Generator that params.draw uses. `uniform` and `grid` return
    exact grid values lo + (hi - lo) a / 2^BITS, a uniform in [0, 2^BITS); every draw is
    logged (lo, hi, a, value) so that a test can check it lies on its grid."""

    def __init__(self, seed):
        self.rng = np.random.default_rng(seed)
        self.log = []
        self.prm = None               # the exact parameters the last draw built
        self.allow_any_inertia = False

    def integer(self):
        return int(self.rng.integers(0, N_GRID, dtype=np.uint64))

    def grid(self, lo, hi):
        """An exact rational uniform on the grid of [lo, hi)."""
        lo, hi = q_of(lo), q_of(hi)
        a = self.integer()
        v = lo + (hi - lo) * a / N_GRID
        self.log.append((lo, hi, a, v))
        return v

    def uniform(self, lo=0.0, hi=1.0, size=None):
        if size is None:
            x = free(self.grid(lo, hi))
            x.__class__ = Drawn
            return x
        return np.array([self.uniform(lo, hi) for _ in range(size)], dtype=object)

    def choice(self, seq):
        return seq[int(self.rng.integers(0, len(seq)))]

    def exact_of(self, x: float):
        """The exact drawn value +-u whose float is x (a parameter set outside build, as
        negative.case_params sets k)."""
        for d in reversed(self.drawn):
            for sign in (1, -1):
                if sign * d.to_float() == x:
                    return d.jet() if sign > 0 else -d.jet()
        raise NotRational(f"parameter {x!r} is not a drawn grid value")

    @contextmanager
    def drawing(self):
        """Within: params.build records the exact parameters it is given."""
        real = params_mod.build
        self.drawn = []
        uniform = self.uniform

        def logged_uniform(lo=0.0, hi=1.0, size=None):
            out = uniform(lo, hi, size)
            self.drawn.extend(np.atleast_1d(out))
            return out

        def capture(case_id, prm=None, *, allow_any_inertia=False):
            self.prm = dict(prm or {})
            self.allow_any_inertia = allow_any_inertia
            return real(case_id, prm, allow_any_inertia=allow_any_inertia)

        params_mod.build = capture
        self.uniform = logged_uniform
        try:
            yield self
        finally:
            params_mod.build = real
            self.uniform = uniform


def free(x):
    """A drawn free coordinate: degree 1 in z (in symbolic mode, a new symbol z_i)."""
    q = q_of(x)
    return Jet(symbol(q) if S.active else q, None, 1, 0)


def exact_slots(case_id, prm_in, allow_any_inertia):
    """The parameter vector of cases.build, filled exactly from the drawn values by the
    project's own bodies.fill_inertia / fill_body (object arrays of `Drawn`), then handed
    over as plain jets."""
    case = get_case(case_id)

    def drawn(v):
        if isinstance(v, Drawn):
            return v
        x = Jet(q_of(v))
        x.__class__ = Drawn
        return x

    prm = {}
    for name in case.param_names:
        v = prm_in.get(name, case.optional.get(name))
        prm[name] = None if v is None else drawn(v)
    p = np.array([drawn(0) for _ in range(L.N_PARAMS)], dtype=object)
    fill_inertia(case.body, case.symmetry, prm, p, allow_any_inertia)
    fill_body(case.body, prm, p)
    for name, slot in PARAM_SLOTS.items():
        if prm.get(name) is not None:
            p[slot] = prm[name]
    if case.fixed_k == "2/R":
        p[L.CURV] = 2 / prm["R"]
    out = np.array([drawn(x).jet() for x in p], dtype=object)
    return out, {k: v.jet() for k, v in prm.items() if v is not None}


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
    disk's sqrt(g1^2 + g2^2) (2.15) needs."""
    ct, st = pythagorean(t)
    cp, sp = pythagorean(w)
    g1 = st * cp
    return np.array([-g1 if flip else g1, st * sp, ct], dtype=object)


def rational_gamma(rng: GridRng, pole_margin=0.05, square_sin=True):
    """A rational gamma away from the poles (|g3| < 1 - pole_margin, as the float checks).
    square_sin: Pythagorean angles (sphere_point), so that sin theta = sqrt(g1^2 + g2^2) is
    rational (the disk's support (2.15), theta of the axial reductions, K3 of (2.5)); else
    the inverse stereographic projection, whose components have half the degree (the
    symbolic proofs of the other bodies stay smaller)."""
    while True:
        n0 = mark()
        if square_sin:
            t = free(rng.grid(Fraction(1, 8), 7))      # theta = 2 atan t in (0.25, 2.88)
            w = free(rng.grid(-3, 3))                  # phi = 2 atan w in (-2.5, 2.5)
            g = sphere_point(t, w, flip=rng.choice([False, True]))
        else:
            g = stereographic(free(rng.grid(-3, 3)), free(rng.grid(-3, 3)))
        if abs(g[2].to_float()) < 1 - pole_margin:
            return g
        release(n0)


def ellipsoid_radicand(p, g, rng: GridRng):
    """Make sqrt(gamma.B gamma) (2.39) rational: draw q on a fine grid near its float value
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
    """The draw Pf as exact rationals (rng.prm: the exact values the draw gave build()),
    with the ellipsoid part solved so that sqrt(gamma.B gamma) is rational at `gamma`."""
    if rng.prm is None:
        raise NotRational("the parameters were not drawn by this generator")
    pf = Pf.p
    case = Pf.model.case
    p, prm = exact_slots(case.id, rng.prm, rng.allow_any_inertia)
    if pf[L.CURV] != 0 and p[L.CURV] == 0:          # negative.case_params: k set after build
        p[L.CURV] = rng.exact_of(float(pf[L.CURV]))
    for i, (x, f) in enumerate(zip(p, pf, strict=True)):   # the same model as the float one
        if abs(x.to_float() - f) > 1e-12 * max(1.0, abs(f)):
            raise NotRational(f"exact parameter slot {i} = {x.to_float()!r} != {f!r}")
    if S.active:
        _generic_slots(p, prm)
    if gamma is not None and any(pf[i] != 0 for i in (L.B11, L.B22, L.B33)):
        p[L.B33] = ellipsoid_radicand(p, gamma, rng)
    extra = {k: v for k, v in prm.items() if k in ("mu", "lambda")}
    # relations build() imposes, imposed again after B33 was solved (bodies.fill_inertia)
    if case.symmetry == "spherical" and "mu" in extra:
        p[L.I1] = p[L.I2] = p[L.I3] = extra["mu"]
    elif case.body == "ellipsoid" and "mu" in extra and "lambda" in extra:
        for i, b in ((L.I1, L.B11), (L.I2, L.B22), (L.I3, L.B33)):
            p[i] = extra["mu"] + extra["lambda"] * p[L.MASS] * p[b]     # (2.40)
    if gamma is not None and case.symmetry == "axial":
        axial_radicand(p, gamma, rng)
    return ExactParams(Pf.model, p, extra)


def _vars(x):
    v = x.v
    if type(v).__name__ != "RF":
        return frozenset()
    out = set()
    for poly in (v.num, v.den):
        out |= {j for j, e in enumerate(poly.degrees()) if e}
    return frozenset(out)


def _generic_slots(p, prm):
    """Symbolic mode: a parameter slot whose value shares no drawn coordinate with any other
    slot or named parameter (a = a0 u1 + 0.1 u2, m = m0 u, ...) becomes one symbol of its
    own. The proof is then of the identity for that parameter arbitrary, which implies the
    drawn case, with fewer variables to expand. Slots tied by a relation (I2 = I1, I3 = 2 I1,
    I = mu + lambda m B, k = 2/R) share coordinates and are kept as they are."""
    used = [_vars(x) for x in p]
    others = [_vars(x) for x in prm.values()]
    for i, vi in enumerate(used):
        if not vi:
            continue
        same = [j for j, vj in enumerate(used) if j != i and vj & vi]
        if same or sum(1 for vo in others if vo & vi and p[i].v != _val(vo, prm, vi)) > 0:
            continue
        p[i] = Jet(symbol(p[i].v.val), None, 1, 0)


def _val(vo, prm, vi):
    # the named parameter using vi's coordinates (a slot's own name: the same value)
    for x in prm.values():
        if _vars(x) == vo:
            return x.v
    return None


def axial_radicand(p, gamma, rng: GridRng):
    """Make sqrt(I1 + m r^2) rational (K3 of (2.5) divides by sqrt((1 - g3^2)(I1 + m r^2)),
    and 1 - g3^2 = sin^2 th is already a square): draw q near its float value and solve
    I1 = I2 = q^2 - m r^2 (a relative change ~2^-20; I3 = I1 or I3 = 2 I1 kept where drawn so),
    so that the reduced variables need one irrational root (rho0's) only."""
    r, _ = support(p, np.asarray(gamma, dtype=object))
    mr2 = p[L.MASS] * (r @ r)
    q0 = (p[L.I1].to_float() + mr2.to_float()) ** 0.5
    q = free(q_of(Fraction(q0).limit_denominator(2 ** 20))
             * (1 + rng.grid(0, Fraction(1, 2 ** 20))))
    I1 = q * q - mr2
    if I1.v <= 0:
        return
    if p[L.I3] == p[L.I1]:             # spherical inertia (I1 = I2 = I3) kept
        p[L.I3] = I1
    elif p[L.I3] == 2 * p[L.I1]:
        p[L.I3] = 2 * I1
    p[L.I1] = p[L.I2] = I1


def rational_state(Pf, rng: GridRng):
    """(exact params, exact state values) of one random point; float-validated like
    solvers.verify.params.random_states (pole margin, fit, disk not flat)."""
    square_sin = Pf.model.case.symmetry == "axial" or Pf.p[L.DISK_D] != 0
    for _ in range(200):
        n0 = mark()
        M = [free(rng.grid(-2, 2)) for _ in range(3)]
        if Pf.model.model == L.MODEL_FULL:
            g = rational_gamma(rng, square_sin=square_sin)
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
            release(n0)
            continue
        try:
            check_state(Pf.model.model, pf, yf, shell=Pf.model.case.fixed_k is not None)
        except InputError:
            release(n0)
            continue
        return P, y
    raise NotRational("no valid rational point found")
