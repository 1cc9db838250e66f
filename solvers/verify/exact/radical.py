"""Square roots that are not rational: x = C sqrt(R), C and R rational jets.

A density such as (1 - D (gamma, A gamma))^-1/2 (eq2.17) or an integral divided by one is
rational times the square root of a rational radicand R that no parameter can make a square
at every point. Its logarithmic derivative is rational, and so is everything the checks
form from it, up to the common factor sqrt(R):

    x = c sqrt(R),  dx/dy_j = C_j sqrt(R),   C = (c, C_j) a rational jet,

so d ln x = C_j / c is rational, and a residual c_res sqrt(R) vanishes iff its rational
coefficient c_res does (R > 0). Products and quotients combine radicands (sqrt R1 sqrt R2 =
sqrt(R1 R2) for positive reals); a sum needs the same radicand; anything else (a sum of
different radicals, a radical under another root) leaves this field and raises NotRational.
"""

from solvers.verify.exact.jet import Jet, NotRational, _lift


class Radical:
    __slots__ = ("R", "c")

    def __init__(self, c: Jet, R: Jet):
        self.c, self.R = c, R            # R: value and degree only; its partials live in c

    @staticmethod
    def of(R: Jet):
        """sqrt(R) for a rational jet R > 0: c = 1, C_j = R_j / (2 R)."""
        if R.v <= 0:
            raise NotRational(f"square root of a non-positive rational {R.v}")
        g = None if R.g is None else tuple(x / (2 * R.v) for x in R.g)
        return Radical(Jet(1, g, R.n + R.d, R.n + R.d), R.value())

    # --- arithmetic ---------------------------------------------------------------------
    def __mul__(self, o):
        if isinstance(o, Radical):
            if o.R.v == self.R.v:          # sqrt R sqrt R = R: rational
                return (self.c * o.c) * self.R
            return Radical(self.c * o.c, self.R * o.R)
        o = _lift(o)
        if o is NotImplemented:
            return o
        return Radical(self.c * o, self.R)

    __rmul__ = __mul__

    def __truediv__(self, o):
        if isinstance(o, Radical):
            if o.R.v == self.R.v:
                return self.c / o.c
            return Radical(self.c / o.c, self.R / o.R)
        o = _lift(o)
        if o is NotImplemented:
            return o
        return Radical(self.c / o, self.R)

    def __rtruediv__(self, o):
        o = _lift(o)
        if o is NotImplemented:
            return o
        # o / (c sqrt R) = (o / (c R)) sqrt R
        return Radical(o / (self.c * self.R), self.R)

    def __add__(self, o):
        if isinstance(o, Radical) and o.R.v == self.R.v:
            return Radical(self.c + o.c, self.R)
        o2 = o if isinstance(o, Radical) else _lift(o)
        if o2 is NotImplemented:
            return o2
        if not isinstance(o2, Radical) and o2.v == 0 and o2.g is None:
            return self
        if self.c.v == 0 and self.c.g is None:
            return o2
        raise NotRational("a sum of a rational and an irrational square root")

    __radd__ = __add__

    def __neg__(self):
        return Radical(-self.c, self.R)

    def __pos__(self):
        return self

    def __sub__(self, o):
        return self + (-o)

    def __rsub__(self, o):
        return (-self) + o

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
        c = self.c
        if c.v <= 0:
            raise NotRational("log of a non-positive number")
        g = None if c.g is None else tuple(x / c.v for x in c.g)
        return Jet(0, g, c.n, c.n, unknown=True)

    def __abs__(self):
        return -self if self.c.v < 0 else self

    @property
    def real(self):
        return self

    def partial(self, j):
        return Radical(self.c.partial(j), self.R)

    def value(self):
        return Radical(self.c.value(), self.R)

    def coefficient(self) -> Jet:
        """The rational coefficient c: the radical is zero iff it is."""
        return self.c

    def __lt__(self, o):
        return self.c.v < 0 if _lift(o).v == 0 else _cmp_fail()

    def __gt__(self, o):
        return self.c.v > 0 if _lift(o).v == 0 else _cmp_fail()

    def __ne__(self, o):
        return self.c.v != 0 if _lift(o).v == 0 else _cmp_fail()

    def __eq__(self, o):
        return not self.__ne__(o)

    __hash__ = None

    def __float__(self):
        raise NotRational("float() of an exact value")


def _cmp_fail():
    raise NotRational("comparison of an irrational square root")
