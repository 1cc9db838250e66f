"""First-order jets over the rationals: exact values and exact partial derivatives.

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
"""

from fractions import Fraction
from numbers import Rational
from typing import ClassVar

import numpy as np
from flint import fmpq, fmpz

Q = fmpq
ZERO = fmpq(0)
ONE = fmpq(1)


class NotRational(ArithmeticError):
    """The computation left the rationals (square root of a non-square, a transcendental
    function, an unknown constant used multiplicatively)."""


def q_of(x) -> fmpq:
    """A Python/NumPy number as an exact rational. A float is read as the simplest fraction
    with denominator <= 10^6 that rounds to it (1/3 written as 1.0/3 in a formula is meant
    as 1/3), else as the exact binary fraction it is."""
    if isinstance(x, fmpq) or type(x).__name__ == "RF":
        return x
    if isinstance(x, (int, fmpz)):
        return fmpq(x)
    if isinstance(x, Rational):
        return fmpq(int(x.numerator), int(x.denominator))
    if hasattr(x, "imag") and not isinstance(x, float) and x.imag != 0:
        raise NotRational("complex number in an exact computation")
    f = float(x.real if hasattr(x, "real") else x)
    fr = Fraction(f).limit_denominator(10 ** 6)
    if float(fr) != f:
        fr = Fraction(f)
    return fmpq(fr.numerator, fr.denominator)


def _is_square(v: fmpq) -> bool:
    if type(v).__name__ == "RF":        # symbolic.py: a square as a function
        return v.sqrt_or_none() is not None
    return v >= 0 and fmpz(v.p).sqrtrem()[1] == 0 and fmpz(v.q).sqrtrem()[1] == 0


def _sqrt_q(v: fmpq) -> fmpq:
    if type(v).__name__ == "RF":
        s = v.sqrt_or_none()
        if s is None:
            raise NotRational("square root of a rational function that is not a square")
        return s
    if v < 0:
        raise NotRational(f"square root of a negative rational {v}")
    try:
        return v.sqrt()
    except Exception as e:   # flint DomainError: not a square
        raise NotRational(f"square root of {v}, not a rational square") from e


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
        o = _lift(o)
        if o is NotImplemented:
            return o
        g = _comb(self.g, ONE, o.g, ONE)
        return Jet(self.v + o.v, g, max(self.n + o.d, o.n + self.d), self.d + o.d,
                   self.unknown or o.unknown)

    __radd__ = __add__

    def __neg__(self):
        return Jet(-self.v, None if self.g is None else tuple(-x for x in self.g),
                   self.n, self.d, self.unknown)

    def __pos__(self):
        return self

    def __sub__(self, o):
        o = _lift(o)
        return o if o is NotImplemented else self + (-o)

    def __rsub__(self, o):
        o = _lift(o)
        return o if o is NotImplemented else o + (-self)

    def __mul__(self, o):
        o = _lift(o)
        if o is NotImplemented:
            return o
        if _is_zero_const(o) or _is_zero_const(self):
            return Jet(ZERO)          # 0 * theta: a formula's broadcast, not a use of theta
        if (self.unknown and _is_zero_value(o)) or (o.unknown and _is_zero_value(self)):
            # a zero at the point that is not the zero constant, times an unknown value:
            # the product is zero here, but its degree as a function is not tracked
            lose_degree("a value zero at the point multiplied an unknown constant")
            return Jet(ZERO)
        self._known()
        o._known()
        g = _comb(self.g, o.v, o.g, self.v)
        return Jet(self.v * o.v, g, self.n + o.n, self.d + o.d)

    __rmul__ = __mul__

    def __truediv__(self, o):
        o = _lift(o)
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
            g = _comb(self.g, ib, o.g, -v * ib)
        # common denominator Q_a N_b^2 (see the module docstring)
        return Jet(v, g, self.n + o.d + o.n, self.d + 2 * o.n)

    def __rtruediv__(self, o):
        o = _lift(o)
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
        if self.v > 0 and not _is_square(self.v):
            from solvers.verify.exact.radical import Radical
            return Radical.of(self)
        s = _sqrt_q(self.v)
        if s == 0:
            raise ZeroDivisionError("derivative of sqrt at 0")
        g = None if self.g is None else tuple(x / (2 * s) for x in self.g)
        h = (self.n + self.d + 1) // 2      # deg of the polynomial P with P^2 = N Q
        return Jet(s, g, self.n + self.d, self.d + h)

    def arccos(self):
        from solvers.verify.exact.angle import Angle
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
        o = _lift(o)
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
        o = _lift(o)
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
        return not self.unknown and _is_zero_value(self) and (
            self.n == 0 or type(self.v).__name__ == "RF")

    def __bool__(self):
        return self.v != 0

    def __repr__(self):
        return f"Jet({self.v}, {self.g}, deg<=({self.n},{self.d}))"


def _lift(o):
    if isinstance(o, Jet):
        return o
    if isinstance(o, (np.ndarray, list, tuple)) or type(o).__name__ in ("Radical", "T2"):
        return NotImplemented      # let NumPy broadcast / the radical combine
    try:
        return Jet(q_of(o))
    except (TypeError, ValueError):
        return NotImplemented


def _is_zero_const(x):
    """The constant 0 (degree 0, no partials): 0 * anything is 0 as a function too."""
    return not x.unknown and x.g is None and x.v == 0 and (
        x.n == 0 or type(x.v).__name__ == "RF")


def _is_zero_value(x):
    return x.v == 0 and (x.g is None or all(y == 0 for y in x.g))


class _Lost:
    """Reasons the degree bound stopped describing the computed function (a zero at the
    point used as if it were the zero function). certify.run_points reads and resets it:
    such a record states no probability."""
    reasons: ClassVar[list[str]] = []


def lose_degree(why: str):
    _Lost.reasons.append(why)


def _comb(ga, ca, gb, cb):
    """ca * ga + cb * gb for partial tuples (None: zero)."""
    if ga is None and gb is None:
        return None
    if ga is None:
        return tuple(cb * x for x in gb)
    if gb is None:
        return tuple(ca * x for x in ga)
    return tuple(ca * x + cb * y for x, y in zip(ga, gb, strict=True))


def q_str(x) -> str:
    """A rational as "p/q" (or "p")."""
    x = x.v if isinstance(x, Jet) else q_of(x)
    return f"{x.p}" if x.q == 1 else f"{x.p}/{x.q}"
