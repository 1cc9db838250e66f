"""Square roots that are not rational: numbers a + c sqrt(r) of the field Q(sqrt r).

A density such as (1 - D (gamma, A gamma))^-1/2 (2.24), an integral divided by one, or
the reduced variable K3 of (2.5) holds the square root of a radicand R that no parameter can
make a square at every point. We compute in Q(sqrt r), r = R(point), with jets over Q for
both parts:

    x = a + c sqrt(r),   dx/dy_j = A_j + C_j sqrt(r),

where a square root created from a rational jet R (value R, partials R_j) starts as
a = 0, c = 1, C_j = R_j / (2 R) (d sqrt R = R_j / (2 sqrt R)); after that r is a constant of
the arithmetic, and products obey (a1 + c1 s)(a2 + c2 s) = (a1 a2 + r c1 c2) + (a1 c2 +
c1 a2) s with the jets' own product rule. Since sqrt(r) is irrational, x = 0 iff a = c = 0:
a residual vanishes exactly iff both rational parts do. Two different radicands combine when
their ratio is a rational square, and pure roots multiply (sqrt R1 sqrt R2 = sqrt(R1 R2),
positive reals); anything else (a sum over two independent roots, a root of a root) leaves
the field and raises NotRational.
"""

from solvers.verify.exact.jet import Jet, NotRational, _is_square, _lift, lose_degree


def _zero(j: Jet) -> bool:
    return j.v == 0 and (j.g is None or all(x == 0 for x in j.g))


class Strict:
    """In strict mode a sqrt(r) coefficient that vanishes at the point without being the
    zero function is kept (the number stays in Q(sqrt r), both parts with their degree
    bounds); certify.run_points evaluates strictly first and only falls back to dropping it
    (and to stating no probability) when the strict computation leaves the field."""
    on = False


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
        return _zero(self.a)

    def _with(self, o):
        """o (a Jet or a Radical) over this radicand, or None if it cannot be."""
        if isinstance(o, Radical):
            if o.r.v == self.r.v:
                return o
            ratio = o.r / self.r
            if not _is_square(ratio.v):
                return None
            s = ratio.sqrt()                   # sqrt(r_o) = s sqrt(r_self)
            return Radical(o.a, o.c * s, self.r)
        o = _lift(o)
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
        return _norm(Radical(self.a + w.a, self.c + w.c, self.r))

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
        return _norm(Radical(a, c, self.r))

    __rmul__ = __mul__

    def inverse(self):
        n = self.a * self.a - self.r * (self.c * self.c)      # nonzero: sqrt r irrational
        return _norm(Radical(self.a / n, -self.c / n, self.r))

    def __truediv__(self, o):
        if isinstance(o, Radical):
            if self._with(o) is None and self.pure and o.pure:
                # c1 sqrt r1 / (c2 sqrt r2) = (c1 / (c2 r2)) sqrt(r1 r2)
                return Radical(Jet(0), self.c / (o.c * o.r), self.r * o.r)
            return self * o.inverse()
        o = _lift(o)
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

    def __le__(self, o):
        return self._cmp(o) <= 0

    def __gt__(self, o):
        return self._cmp(o) > 0

    def __ge__(self, o):
        return self._cmp(o) >= 0

    def __ne__(self, o):
        return self._cmp(o) != 0

    def __eq__(self, o):
        return self._cmp(o) == 0

    __hash__ = None

    def __float__(self):
        raise NotRational("float() of an exact value")

    def __repr__(self):
        return f"Radical({self.a.v} + {self.c.v} sqrt({self.r.v}))"


def _norm(x: Radical):
    """Back to a rational jet when the root has cancelled.

    Only the zero function may be dropped without losing the degree bound: a coefficient c
    that is zero at the point (value and partials) but not identically is what a checked
    identity c1 - c2 looks like, and dropping it would state the degree of the rational part
    alone, far below the true degree. Such a drop is recorded, so
    the record states no probability (or the strict mode keeps the radical)."""
    if not _zero(x.c):
        return x
    if x.c.structural_zero():
        return x.a
    if Strict.on:
        return x
    lose_degree("a sqrt(r) coefficient vanished at the point without being the zero function")
    return x.a
