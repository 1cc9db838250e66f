"""What the exact numbers of jet.py share and need no jet for: a Python/NumPy number as an
fmpq, square roots in Q, sums of partials, the zero tests, the record of degree bounds that
stopped describing the computed function, and the strict mode of the radicals.
"""

from fractions import Fraction
from numbers import Rational
from typing import ClassVar

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


def is_square(v: fmpq) -> bool:
    if type(v).__name__ == "RF":        # symbolic.py: a square as a function
        return v.sqrt_or_none() is not None
    return v >= 0 and fmpz(v.p).sqrtrem()[1] == 0 and fmpz(v.q).sqrtrem()[1] == 0


def sqrt_q(v: fmpq) -> fmpq:
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


class Lost:
    """Reasons the degree bound stopped describing the computed function (a zero at the
    point used as if it were the zero function). certify.run_points reads and resets it:
    such a record states no probability."""
    reasons: ClassVar[list[str]] = []


def lose_degree(why: str):
    Lost.reasons.append(why)


def is_zero_const(x):
    """The constant 0 (degree 0, no partials): 0 * anything is 0 as a function too."""
    return not x.unknown and x.g is None and x.v == 0 and (
        x.n == 0 or type(x.v).__name__ == "RF")


def is_zero_value(x):
    return x.v == 0 and (x.g is None or all(y == 0 for y in x.g))


def comb(ga, ca, gb, cb):
    """ca * ga + cb * gb for partial tuples (None: zero)."""
    if ga is None and gb is None:
        return None
    if ga is None:
        return tuple(cb * x for x in gb)
    if gb is None:
        return tuple(ca * x for x in ga)
    return tuple(ca * x + cb * y for x, y in zip(ga, gb, strict=True))


class Strict:
    """In strict mode a sqrt(r) coefficient that vanishes at the point without being the
    zero function is kept (the number stays in Q(sqrt r), both parts with their degree
    bounds); certify.run_points evaluates strictly first and only falls back to dropping it
    (and to stating no probability) when the strict computation leaves the field."""
    on = False


def drop_cancelled_root(x):
    """Back to a rational jet when the root has cancelled.

    Only the zero function may be dropped without losing the degree bound: a coefficient c
    that is zero at the point (value and partials) but not identically is what a checked
    identity c1 - c2 looks like, and dropping it would state the degree of the rational part
    alone, far below the true degree. Such a drop is recorded, so
    the record states no probability (or the strict mode keeps the radical)."""
    if not is_zero_value(x.c):
        return x
    if x.c.structural_zero():
        return x.a
    if Strict.on:
        return x
    lose_degree("a sqrt(r) coefficient vanished at the point without being the zero function")
    return x.a
