"""Second-order equations along the flow, exactly: truncated Taylor series in time.

(2.17), (2.33) and (3.5) are second-order equations for w = omega3 in theta = arccos(gamma3)
(or x = (1 - gamma3)/2). Along the flow y(t) = y + t v + t^2 (Dv v)/2 + O(t^3), so every
quantity f(y(t)) = f0 + f1 t + f2 t^2 + O(t^3) with f1 = df/dt, f2 = (d2f/dt2)/2. `T2` is
that truncated series with rational-jet coefficients (degrees tracked as in jet.py); the
field's Dv v comes from one first-order jet in the direction v. Then
    dw/ds = w' / s',   d2w/ds2 = (w'' s' - w' s'') / s'^3     (' = d/dt).
"""

import numpy as np

from solvers.verify.checks.common import implementation
from solvers.verify.exact.jet import Angle, Jet, lift
from solvers.verify.exact.model import field
from solvers.verify.exact.rational import NotRational


class T2:
    __slots__ = ("c",)

    def __init__(self, c0, c1, c2):
        self.c = (c0, c1, c2)

    @staticmethod
    def _of(o):
        if isinstance(o, T2):
            return o
        o = o if type(o).__name__ == "Radical" else lift(o)
        if o is NotImplemented:
            return None
        return T2(o, Jet(0), Jet(0))

    def __add__(self, o):
        o = T2._of(o)
        if o is None:
            return NotImplemented
        return T2(*(a + b for a, b in zip(self.c, o.c, strict=True)))

    __radd__ = __add__

    def __neg__(self):
        return T2(*(-a for a in self.c))

    def __sub__(self, o):
        return self + (-o)

    def __rsub__(self, o):
        return (-self) + o

    def __mul__(self, o):
        o = T2._of(o)
        if o is None:
            return NotImplemented
        a, b = self.c, o.c
        return T2(a[0] * b[0], a[0] * b[1] + a[1] * b[0], a[0] * b[2] + a[1] * b[1] + a[2] * b[0])

    __rmul__ = __mul__

    def __truediv__(self, o):
        o = T2._of(o)
        if o is None:
            return NotImplemented
        b = o.c
        q0 = self.c[0] / b[0]
        q1 = (self.c[1] - q0 * b[1]) / b[0]
        q2 = (self.c[2] - q0 * b[2] - q1 * b[1]) / b[0]
        return T2(q0, q1, q2)

    def __rtruediv__(self, o):
        return T2._of(o) / self

    def __pow__(self, e):
        k = int(e)
        if k != e:
            if 2 * e == int(2 * e):
                return self.sqrt() ** int(2 * e)
            raise NotRational(f"power {e} of a series")
        out = T2(Jet(1), Jet(0), Jet(0))
        for _ in range(abs(k)):
            out = out * self
        return out if k >= 0 else 1 / out

    def sqrt(self):
        s0 = self.c[0].sqrt()
        s1 = self.c[1] / (2 * s0)
        s2 = (self.c[2] - s1 * s1) / (2 * s0)
        return T2(s0, s1, s2)

    def __ne__(self, o):
        return self.c[0] != (o.c[0] if isinstance(o, T2) else o)

    def __eq__(self, o):
        return not self.__ne__(o)

    __hash__ = None

    def __lt__(self, o):
        return self.c[0] < (o.c[0] if isinstance(o, T2) else o)

    def __gt__(self, o):
        return self.c[0] > (o.c[0] if isinstance(o, T2) else o)

    def __float__(self):
        raise NotRational("float() of an exact value")


def _directed(y, vj):
    n = max(y.n + vj.d, vj.n + y.d)
    return Jet(y.v, (vj.v,), n, y.d + vj.d)


def flow_series(P, y, field):
    """y(t) to second order as T2s: y + t v + t^2 (Dv v)/2, all exact."""
    n = len(y)
    v = field(P, np.array([Jet.const(c).value() for c in y], dtype=object))
    # y_j seeded in the direction v: value y_j, partial v_j, over the common denominator of
    # both (the partial's degree is v_j's, not y_j's)
    yd = np.array([_directed(Jet.const(y[j]), v[j]) for j in range(n)], dtype=object)
    vd = field(P, yd)
    return np.array([T2(Jet.const(y[j]).value(), v[j].value(), vd[j].partial(0) / 2)
                     for j in range(n)], dtype=object)


def second_order(catalogue, claim, use_corrected):
    """The terms of the printed second-order equation at (s, w, dw/ds, d2w/ds2) of the
    full flow; their sum is the residual (checks/ode.jet_residual)."""
    fid = claim.check_args.formula
    f = implementation(fid, use_corrected)
    V = catalogue.formula(fid).variables.value

    def res(P, y):
        Y = flow_series(P, y, field)
        w = P.omega(Y[:3], Y[3:6])[2]
        u = Y[5]
        if V == "(theta, omega3)":
            S = (1 - u * u).sqrt()
            u0, u1, u2 = u.c
            s1 = -u1 / S.c[0]
            s2 = -(2 * u2 * S.c[0] - u1 * S.c[1]) / (2 * S.c[0] * S.c[0])
            s = Angle.arccos_of(u0).value()
        elif V == "(x, omega3)":
            s1, s2 = -u.c[1] / 2, -u.c[2] / 2
            s = (1 - u.c[0]) / 2
        else:
            raise NotRational(f"second-order equation in {V}")
        sd, sdd = s1, 2 * s2
        wd, wdd = w.c[1], 2 * w.c[2]
        w1 = wd / sd
        w2 = (wdd * sd - wd * sdd) / (sd * sd * sd)
        terms = np.atleast_1d(np.asarray(f(P, np.array([s, w.c[0], w1, w2], dtype=object)),
                                         dtype=object))
        return [sum(terms[1:], terms[0])]
    return res
