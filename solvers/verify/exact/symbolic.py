"""Rational functions over Q with a point value: the element type of the symbolic proofs.

An `RF` is N(z)/D(z), N, D in Z[z] (python-flint fmpz_mpoly, reduced by their gcd, D with a
positive leading coefficient: a canonical form, so equality is identity of rational
functions), together with its exact value at the drawn point. Jets (jet.py) hold RFs in place
of fmpq while `symbolic()` is active, so the project's own formulas, field and checks run
unchanged and produce each residual as a rational function of the free coordinates z (the
grid draws of the parameters, the angle parameters of gamma, M, ...): a residual whose
numerator is the zero polynomial is PROVED to vanish identically, with no probability.

Decisions the arithmetic takes (a pivot, "is this zero", "is this a square") are made on
the functions, not on the point: zero means the zero function, a square root is taken of a
rational function that is a square (its sign fixed by the value at the point: the branch
the model is on). Order comparisons (<, >, abs) use the value at the point: a proof then
holds on the open region of parameter space where those signs hold, which contains the
point; an identity of rational functions on an open set holds wherever both sides are
defined.

Cost is bounded: an RF with more than MAX_TERMS terms, or work past the deadline set by
`symbolic(seconds)`, raises TooBig and the record falls back to the probabilistic
certificate (certify.py).
"""

import time
from contextlib import contextmanager
from typing import ClassVar

from flint import fmpq, fmpz, fmpz_mpoly_ctx

N_SYMBOLS = 64          # free coordinates a record may draw (parameters, gamma, M, ...)
MAX_TERMS = 150_000     # an RF larger than this is not expanded further (TooBig)
CTX = fmpz_mpoly_ctx.get(("z", N_SYMBOLS), "degrevlex")
_ONE = CTX.from_dict({(0,) * N_SYMBOLS: 1})


class TooBig(ArithmeticError):
    """The symbolic expansion exceeded its budget (terms or time)."""


class _State:
    active = False
    deadline = None
    values: ClassVar[list] = []      # the point: value of symbol i


S = _State()


@contextmanager
def symbolic(seconds=4.0):
    """Within: free coordinates are symbols (points.free), jets hold RFs."""
    S.active, S.values, S.deadline = True, [], time.monotonic() + seconds
    try:
        yield
    finally:
        S.active, S.values, S.deadline = False, [], None


def mark() -> int:
    """The number of symbols drawn so far (a rejected draw gives its symbols back)."""
    return len(S.values)


def release(n: int):
    del S.values[n:]


def _const(q) -> "RF":
    q = q if isinstance(q, fmpq) else fmpq(q)
    return RF(CTX.from_dict({(0,) * N_SYMBOLS: int(q.p)}),
              CTX.from_dict({(0,) * N_SYMBOLS: int(q.q)}), q, reduced=True)


def symbol(value) -> "RF":
    """A new free coordinate with the given exact value at the point."""
    i = len(S.values)
    if i >= N_SYMBOLS:
        raise TooBig(f"more than {N_SYMBOLS} free coordinates")
    S.values.append(value)
    e = [0] * N_SYMBOLS
    e[i] = 1
    return RF(CTX.from_dict({tuple(e): 1}), _ONE, value, reduced=True)


def _lc_sign(p) -> int:
    c = p.leading_coefficient()
    return 1 if c > 0 else -1


def _check(p):
    if len(p) > MAX_TERMS:
        raise TooBig(f"an intermediate rational function has {len(p)} terms")
    if S.deadline is not None and time.monotonic() > S.deadline:
        raise TooBig("symbolic time budget spent")


def _eval(p) -> fmpq:
    vals = S.values
    out = fmpq(0)
    for mon, c in zip(p.monoms(), p.coeffs(), strict=True):
        t = fmpq(int(c))
        for i, e in enumerate(mon):
            if e:
                t *= vals[i] ** e
        out += t
    return out


class RF:
    __slots__ = ("den", "num", "val")

    def __init__(self, num, den, val, reduced=False):
        if not reduced:
            if num.is_zero():
                den = _ONE
            else:
                g = num.gcd(den)
                if not g.is_one():
                    num, den = num / g, den / g
                if _lc_sign(den) < 0:
                    num, den = -num, -den
            _check(num)
            _check(den)
        self.num, self.den, self.val = num, den, val

    # --- coercion ----------------------------------------------------------------------
    @staticmethod
    def of(o):
        if isinstance(o, RF):
            return o
        if isinstance(o, (fmpq, fmpz, int)):
            return _const(o)
        return None

    # --- arithmetic --------------------------------------------------------------------
    def __add__(self, o):
        o = RF.of(o)
        if o is None:
            return NotImplemented
        if o.num.is_zero():
            return self
        if self.num.is_zero():
            return o
        # Henrici: with g = gcd(b, d), a/b + c/d = t / (b' d' g), t = a d' + c b', and only
        # gcd(t, g) can cancel (both operands reduced); g is small where the full gcd of t
        # with the product of the denominators is not
        b, d = self.den, o.den
        if b == d:
            g, b1, d1 = b, _ONE, _ONE
        else:
            g = b.gcd(d)
            b1, d1 = (b, d) if g.is_one() else (b / g, d / g)
        t = self.num * d1 + o.num * b1
        if t.is_zero():
            return _const(0)
        if not g.is_one():
            h = t.gcd(g)
            if not h.is_one():
                t, g = t / h, g / h
        den = b1 * d1 * g
        if _lc_sign(den) < 0:
            t, den = -t, -den
        _check(t)
        return RF(t, den, self.val + o.val, reduced=True)

    __radd__ = __add__

    def __neg__(self):
        return RF(-self.num, self.den, -self.val, reduced=True)

    def __sub__(self, o):
        o = RF.of(o)
        return NotImplemented if o is None else self + (-o)

    def __rsub__(self, o):
        o = RF.of(o)
        return NotImplemented if o is None else o + (-self)

    def __mul__(self, o):
        o = RF.of(o)
        if o is None:
            return NotImplemented
        if self.num.is_zero() or o.num.is_zero():
            return _const(0)
        # cross-cancel first: (a/b)(c/d) with gcd(a, d), gcd(c, b) removed keeps sizes small
        g1, g2 = self.num.gcd(o.den), o.num.gcd(self.den)
        a, d = (self.num / g1, o.den / g1) if not g1.is_one() else (self.num, o.den)
        c, b = (o.num / g2, self.den / g2) if not g2.is_one() else (o.num, self.den)
        num, den = a * c, b * d
        if _lc_sign(den) < 0:
            num, den = -num, -den
        _check(num)
        _check(den)
        return RF(num, den, self.val * o.val, reduced=True)

    __rmul__ = __mul__

    def inverse(self):
        if self.num.is_zero():
            raise ZeroDivisionError("division by the zero function")
        num, den = self.den, self.num
        if _lc_sign(den) < 0:
            num, den = -num, -den
        return RF(num, den, 1 / self.val, reduced=True)

    def __truediv__(self, o):
        o = RF.of(o)
        if o is None:
            return NotImplemented
        return self * o.inverse()

    def __rtruediv__(self, o):
        o = RF.of(o)
        return NotImplemented if o is None else o * self.inverse()

    def __pow__(self, e):
        k = int(e)
        out = _const(1)
        for _ in range(abs(k)):
            out = out * self
        return out if k >= 0 else out.inverse()

    # --- squares -----------------------------------------------------------------------
    def sqrt_or_none(self):
        """The square root of a square rational function, positive at the point; None if
        it is not a square (N D is not the square of a polynomial)."""
        if self.num.is_zero():
            return _const(0)
        if self.val <= 0:
            return None
        try:
            s = (self.num * self.den).sqrt()
        except Exception:     # flint: not a perfect square
            return None
        root = RF(s, self.den, fmpq(0))
        v = _eval(root.num) / _eval(root.den)
        if v < 0:          # the branch positive at the point
            return RF(-root.num, root.den, -v, reduced=True)
        root.val = v
        return root

    # --- comparisons: identity for ==, the point for orders -----------------------------
    def __eq__(self, o):
        o = RF.of(o)
        if o is None:
            return NotImplemented
        return self.num == o.num and self.den == o.den

    def __ne__(self, o):
        r = self.__eq__(o)
        return r if r is NotImplemented else not r

    __hash__ = None

    def _v(self, o):
        return o.val if isinstance(o, RF) else o

    def __lt__(self, o):
        return self.val < self._v(o)

    def __le__(self, o):
        return self.val <= self._v(o)

    def __gt__(self, o):
        return self.val > self._v(o)

    def __ge__(self, o):
        return self.val >= self._v(o)

    def is_zero(self):
        return self.num.is_zero()

    def degree(self) -> int:
        """Total degree of the numerator (-1 for the zero function)."""
        return -1 if self.num.is_zero() else int(self.num.total_degree())

    @property
    def p(self):          # numerator / denominator of the VALUE (q_str, to_float)
        return self.val.p

    @property
    def q(self):
        return self.val.q

    def __repr__(self):
        return f"RF({self.num} / {self.den} = {self.val})"
