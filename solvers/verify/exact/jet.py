"""First-order jets over the rationals, and the two numbers outside Q that their own
operations create: exact values and exact partial derivatives.

A `Jet` holds a rational value v and its partials dv/dy_j with respect to the seeded state
coordinates (forward-mode dual numbers with a vector of infinitesimals). Every operation is
exact (python-flint `fmpq`); a square root is taken only of a perfect rational square
(`NotRational` otherwise), so the whole computation stays in Q.

Each jet also carries a degree bound (n, d) for the Schwartz-Zippel lemma: its value and
every partial can be written N_i(z) / Q(z) over one common denominator, with polynomials of
total degree deg N_i <= n and deg Q <= d in the sampled free coordinates z (parameters,
stereographic/Pythagorean coordinates of gamma, components of M). The rules below build
such a representation from those of the operands; a square root of a radicand that is a
square of a rational function of z (what the parametrisations of points.py make it) has
numerator degree at most half that of the radicand's numerator times denominator.

`log` keeps only the derivatives (d ln a = da / a, rational); its value is an unknown
constant, which may be added to but never multiplied: the checks only use d ln rho.

The jet's sqrt and arccos may leave Q, so the two numbers they return live here too:
`Angle`, theta = arccos(gamma3), whose cosine, sine and derivatives are rational at our
points (sin theta = sqrt(1 - gamma3^2) is rational by the Pythagorean choice of gamma,
points.sphere_point), for the reduced systems printed in theta ((2.16), (2.17), (2.33),
(3.5)); and `Radical`, a + c sqrt(r) in the field Q(sqrt r), r = R(point), for a radicand
that no parameter makes a square ((2.24), K3 of (2.5)). In Q(sqrt r) a square root created
from a rational jet R starts as a = 0, c = 1, C_j = R_j / (2 R); products obey
(a1 + c1 s)(a2 + c2 s) = (a1 a2 + r c1 c2) + (a1 c2 + c1 a2) s; x = 0 iff a = c = 0. Two
radicands combine when their ratio is a rational square, and pure roots multiply; anything
else (a sum over two independent roots, a root of a root) raises NotRational.
"""

from fractions import Fraction
from functools import total_ordering

import numpy as np
from flint import fmpq

from solvers.verify.exact.rational import (
    ONE,
    ZERO,
    NotRational,
    comb,
    drop_cancelled_root,
    is_square,
    is_zero_const,
    is_zero_value,
    lose_degree,
    q_of,
    sqrt_q,
)


class Jet:
    __slots__ = ("d", "g", "n", "unknown", "v")

    def __init__(self, v, g=None, n=0, d=0, unknown=False):
        self.v = v if isinstance(v, fmpq) or type(v).__name__ == "RF" else q_of(v)
        self.g = g              # tuple of fmpq (partials) or None (all zero)
        self.n, self.d = n, d
        self.unknown = unknown

    # --- construction -------------------------------------------------------------
    @staticmethod
    def const(x, n=0, d=0):
        if isinstance(x, Jet) or type(x).__name__ == "Radical":
            return x
        return Jet(q_of(x), None, n, d)

    @staticmethod
    def seed(value, j, nvars):
        """Coordinate y_j = value (a Jet with degree bound, no partials) with dy_j/dy_j = 1."""
        value = Jet.const(value)
        g = tuple(ONE if i == j else ZERO for i in range(nvars))
        return Jet(value.v, g, max(value.n, value.d), value.d)

    def value(self):
        """The value alone, as a jet without partials (same degree bound)."""
        self._known()
        return Jet(self.v, None, self.n, self.d)

    def partial(self, j):
        return Jet(self.g[j] if self.g else ZERO, None, self.n, self.d)

    def _known(self):
        if self.unknown:
            raise NotRational("the value of a logarithm is used")

    # --- arithmetic -------------------------------------------------------------------
    def __add__(self, o):
        o = lift(o)
        if o is NotImplemented:
            return o
        g = comb(self.g, ONE, o.g, ONE)
        return Jet(self.v + o.v, g, max(self.n + o.d, o.n + self.d), self.d + o.d,
                   self.unknown or o.unknown)

    __radd__ = __add__

    def __neg__(self):
        return Jet(-self.v, None if self.g is None else tuple(-x for x in self.g),
                   self.n, self.d, self.unknown)

    def __pos__(self):
        return self

    def __sub__(self, o):
        o = lift(o)
        return o if o is NotImplemented else self + (-o)

    def __rsub__(self, o):
        o = lift(o)
        return o if o is NotImplemented else o + (-self)

    def __mul__(self, o):
        o = lift(o)
        if o is NotImplemented:
            return o
        if is_zero_const(o) or is_zero_const(self):
            return Jet(ZERO)          # 0 * theta: a formula's broadcast, not a use of theta
        if (self.unknown and is_zero_value(o)) or (o.unknown and is_zero_value(self)):
            # a zero at the point that is not the zero constant, times an unknown value:
            # the product is zero here, but its degree as a function is not tracked
            lose_degree("a value zero at the point multiplied an unknown constant")
            return Jet(ZERO)
        self._known()
        o._known()
        g = comb(self.g, o.v, o.g, self.v)
        return Jet(self.v * o.v, g, self.n + o.n, self.d + o.d)

    __rmul__ = __mul__

    def __truediv__(self, o):
        o = lift(o)
        if o is NotImplemented:
            return o
        self._known()
        o._known()
        if o.v == 0:
            raise ZeroDivisionError("exact division by zero")
        v = self.v / o.v
        g = None
        if self.g is not None or o.g is not None:
            # (a/b)' = (a' - (a/b) b') / b
            ib = 1 / o.v
            g = comb(self.g, ib, o.g, -v * ib)
        # common denominator Q_a N_b^2 (see the module docstring)
        return Jet(v, g, self.n + o.d + o.n, self.d + 2 * o.n)

    def __rtruediv__(self, o):
        o = lift(o)
        return o if o is NotImplemented else o / self

    def __pow__(self, e):
        if isinstance(e, Jet):
            if e.g is not None:
                raise NotRational("a power with a variable exponent")
            e = e.v
        qe = q_of(e)
        if qe.q == 1:
            k = int(qe.p)
            if k == 0:
                return Jet(ONE)
            out = self
            for _ in range(abs(k) - 1):
                out = out * self
            return out if k > 0 else 1 / out
        if qe.q == 2:            # a half-integer power: through the exact square root
            return self.sqrt() ** int(qe.p)
        raise NotRational(f"power {e} of a jet")

    def __rpow__(self, b):
        raise NotRational("a power with a variable exponent")

    def sqrt(self):
        self._known()
        if self.v > 0 and not is_square(self.v):
            return Radical.of(self)
        s = sqrt_q(self.v)
        if s == 0:
            raise ZeroDivisionError("derivative of sqrt at 0")
        g = None if self.g is None else tuple(x / (2 * s) for x in self.g)
        h = (self.n + self.d + 1) // 2      # deg of the polynomial P with P^2 = N Q
        return Jet(s, g, self.n + self.d, self.d + h)

    def arccos(self):
        self._known()
        return Angle.arccos_of(self)

    def sin(self):
        raise NotRational("sin of a variable that is not an angle of ours")

    cos = tan = arctan = arcsin = exp = sinh = cosh = sin

    def log(self):
        self._known()
        if self.v <= 0:
            raise NotRational("log of a non-positive number")
        g = None if self.g is None else tuple(x / self.v for x in self.g)
        return Jet(ZERO, g, self.n, self.n, unknown=True)

    def __abs__(self):
        self._known()
        return -self if self.v < 0 else self

    # --- NumPy object-array protocol and comparisons ----------------------------------
    @property
    def real(self):
        # as Re of a complex-step number: the value without its infinitesimal part (the
        # formulas use np.real to hold a quantity constant, e.g. (2.21)'s lambda)
        return self.value()

    @property
    def imag(self):
        return Jet(ZERO)

    def conjugate(self):
        return self

    def _cmp_value(self, o):
        self._known()
        o = lift(o)
        o._known()
        return self.v, o.v

    def __lt__(self, o):
        a, b = self._cmp_value(o)
        return a < b

    def __le__(self, o):
        a, b = self._cmp_value(o)
        return a <= b

    def __gt__(self, o):
        a, b = self._cmp_value(o)
        return a > b

    def __ge__(self, o):
        a, b = self._cmp_value(o)
        return a >= b

    def __eq__(self, o):
        o = lift(o)
        if o is NotImplemented:
            return False
        return self.v == o.v

    def __ne__(self, o):
        return not self.__eq__(o)

    __hash__ = None

    def __float__(self):
        # float() of an exact value would silently leave Q (a formula reading a parameter
        # as float(p[...]) then computes with a rounded number): refuse, so such a formula
        # is reported as not exactly evaluable instead of giving a false exact verdict.
        raise NotRational("float() of an exact value")

    def to_float(self) -> float:
        self._known()
        return float(Fraction(int(self.v.p), int(self.v.q)))

    def structural_zero(self) -> bool:
        """The zero function, not only zero at the point: value and partials zero with
        numerator degree 0 (a constant), or an RF that is the zero function."""
        return not self.unknown and is_zero_value(self) and (
            self.n == 0 or type(self.v).__name__ == "RF")

    def __bool__(self):
        return self.v != 0

    def __repr__(self):
        return f"Jet({self.v}, {self.g}, deg<=({self.n},{self.d}))"


def lift(o):
    if isinstance(o, Jet):
        return o
    if isinstance(o, (np.ndarray, list, tuple)) or type(o).__name__ in ("Radical", "T2"):
        return NotImplemented      # let NumPy broadcast / the radical combine
    try:
        return Jet(q_of(o))
    except (TypeError, ValueError):
        return NotImplemented


def q_str(x) -> str:
    """A rational as "p/q" (or "p")."""
    x = x.v if isinstance(x, Jet) else q_of(x)
    return f"{x.p}" if x.q == 1 else f"{x.p}/{x.q}"


class Angle(Jet):
    __slots__ = ("c", "s")

    @staticmethod
    def arccos_of(u: Jet):
        if not -1 < u.v < 1:
            raise NotRational("arccos outside (-1, 1)")
        s = (1 - u.value() * u.value()).sqrt()          # sin theta >= 0
        g = None if u.g is None else tuple(-x / _angle_val(s) for x in u.g)
        # d theta / d y_j = -u_j / sin theta: over the denominators of u (Q_u) and of
        # sin theta = P_s / Q_s it is -N_j Q_s / (Q_u P_s), degrees (n_u + d_s, d_u + n_s)
        # (the 1/sin theta counts too)
        n, d = (u.n + s.d, u.d + s.n) if isinstance(s, Jet) else (u.n, u.d)
        a = Angle(0, g, n, d, unknown=True)
        a.c, a.s = u.value(), s
        return a

    def value(self):
        a = Angle(0, None, self.n, self.d, unknown=True)
        a.c, a.s = self.c, self.s
        return a

    def cos(self):
        return self._of(self.c, -self.s)        # d cos theta = -sin theta d theta

    def sin(self):
        return self._of(self.s, self.c)

    def _of(self, f, df):
        if self.g is None:
            return f
        return _angle_with_partials(f, df, self)

    @property
    def real(self):
        return self.value()


def _angle_val(x):
    if isinstance(x, Jet):
        return x.v
    raise NotRational("sin theta is not rational here")


def _angle_with_partials(f, df, theta):
    """The jet f(theta) whose partials are df * d theta / d y_j; degree bound over the
    common denominator Q_f Q_df Q_theta."""
    if not isinstance(f, Jet) or not isinstance(df, Jet):
        raise NotRational("sin theta is not rational here")
    n = max(f.n + df.d + theta.d, df.n + theta.n + f.d)
    return Jet(f.v, tuple(df.v * x for x in theta.g), n, f.d + df.d + theta.d)


@total_ordering
class Radical:
    __slots__ = ("a", "c", "r")

    def __init__(self, a: Jet, c: Jet, r: Jet):
        self.a, self.c, self.r = a, c, r      # r: value and degree only

    @staticmethod
    def of(R: Jet):
        """sqrt(R) for a rational jet R > 0 that is not a square."""
        if R.v <= 0:
            raise NotRational(f"square root of a non-positive rational {R.v}")
        g = None if R.g is None else tuple(x / (2 * R.v) for x in R.g)
        return Radical(Jet(0), Jet(1, g, R.n + R.d, R.n + R.d), R.value())

    @property
    def pure(self):
        return is_zero_value(self.a)

    def _with(self, o):
        """o (a Jet or a Radical) over this radicand, or None if it cannot be."""
        if isinstance(o, Radical):
            if o.r.v == self.r.v:
                return o
            ratio = o.r / self.r
            if not is_square(ratio.v):
                return None
            s = ratio.sqrt()                   # sqrt(r_o) = s sqrt(r_self)
            return Radical(o.a, o.c * s, self.r)
        o = lift(o)
        if o is NotImplemented:
            return None
        return Radical(o, Jet(0), self.r)

    # --- arithmetic ---------------------------------------------------------------------
    def __add__(self, o):
        w = self._with(o)
        if w is None:
            if isinstance(o, (Jet, Radical, int, float)):
                raise NotRational("a sum over two independent square roots")
            return NotImplemented
        return drop_cancelled_root(Radical(self.a + w.a, self.c + w.c, self.r))

    __radd__ = __add__

    def __neg__(self):
        return Radical(-self.a, -self.c, self.r)

    def __pos__(self):
        return self

    def __sub__(self, o):
        return self + (-o)

    def __rsub__(self, o):
        return (-self) + o

    def __mul__(self, o):
        w = self._with(o)
        if w is None:
            if isinstance(o, Radical) and self.pure and o.pure:
                return Radical(Jet(0), self.c * o.c, self.r * o.r)
            if isinstance(o, (Jet, Radical)):
                raise NotRational("a product over two independent square roots")
            return NotImplemented
        a = self.a * w.a + self.r * (self.c * w.c)
        c = self.a * w.c + self.c * w.a
        return drop_cancelled_root(Radical(a, c, self.r))

    __rmul__ = __mul__

    def inverse(self):
        n = self.a * self.a - self.r * (self.c * self.c)      # nonzero: sqrt r irrational
        return drop_cancelled_root(Radical(self.a / n, -self.c / n, self.r))

    def __truediv__(self, o):
        if isinstance(o, Radical):
            if self._with(o) is None and self.pure and o.pure:
                # c1 sqrt r1 / (c2 sqrt r2) = (c1 / (c2 r2)) sqrt(r1 r2)
                return Radical(Jet(0), self.c / (o.c * o.r), self.r * o.r)
            return self * o.inverse()
        o = lift(o)
        if o is NotImplemented:
            return o
        return Radical(self.a / o, self.c / o, self.r)

    def __rtruediv__(self, o):
        return self.inverse() * o

    def __pow__(self, e):
        k = int(e)
        if k != e:
            raise NotRational(f"power {e} of an irrational square root")
        if k == 0:
            return Jet(1)
        out = self
        for _ in range(abs(k) - 1):
            out = out * self
        return out if k > 0 else 1 / out

    def sqrt(self):
        raise NotRational("square root of an irrational square root")

    def log(self):
        """d ln x = dx / x; rational for a pure root c sqrt(r): C_j / c."""
        if not self.pure:
            raise NotRational("log of a + c sqrt(r) with a != 0")
        c = self.c
        g = None if c.g is None else tuple(x / c.v for x in c.g)
        return Jet(0, g, c.n, c.n, unknown=True)

    def sign(self) -> int:
        a, c, r = self.a.v, self.c.v, self.r.v
        sa, sc = (a > 0) - (a < 0), (c > 0) - (c < 0)
        if sa == sc or sc == 0:
            return sa
        if sa == 0:
            return sc
        return sa if a * a > r * c * c else sc

    def __abs__(self):
        return -self if self.sign() < 0 else self

    @property
    def real(self):
        # as Re of a complex-step number: the value without its infinitesimal part (the
        # formulas use np.real to hold a quantity constant, e.g. (2.21)'s lambda)
        return self.value()

    def partial(self, j):
        return Radical(self.a.partial(j), self.c.partial(j), self.r)

    def value(self):
        return Radical(self.a.value(), self.c.value(), self.r)

    def parts(self):
        """(a, c): the number is zero iff both are."""
        return self.a, self.c

    def _cmp(self, o):
        return (self - o).sign()

    def __lt__(self, o):
        return self._cmp(o) < 0

    def __eq__(self, o):
        return self._cmp(o) == 0

    __hash__ = None

    def __float__(self):
        raise NotRational("float() of an exact value")

    def __repr__(self):
        return f"Radical({self.a.v} + {self.c.v} sqrt({self.r.v}))"
