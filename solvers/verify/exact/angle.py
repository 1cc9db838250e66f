"""theta = arccos(gamma3) over the rationals: an angle whose value is transcendental but
whose cosine, sine and derivatives are rational at our points.

Reduced systems of the disk are printed in theta ((2.16), (2.17), (2.33), (3.5)). gamma3 is
rational, and so is sin theta = sqrt(1 - gamma3^2) by the Pythagorean choice of gamma
(points.sphere_point), so sin, cos and d theta = -d gamma3 / sin theta are exact; theta
itself is never used (a jet with an unknown value refuses to be multiplied).
"""

from solvers.verify.exact.jet import Jet, NotRational


class Angle(Jet):
    __slots__ = ("c", "s")

    @staticmethod
    def arccos_of(u: Jet):
        if not -1 < u.v < 1:
            raise NotRational("arccos outside (-1, 1)")
        s = (1 - u.value() * u.value()).sqrt()          # sin theta >= 0
        g = None if u.g is None else tuple(-x / _val(s) for x in u.g)
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
        return _with_partials(f, df, self)

    @property
    def real(self):
        return self.value()


def _val(x):
    if isinstance(x, Jet):
        return x.v
    raise NotRational("sin theta is not rational here")


def _with_partials(f, df, theta):
    """The jet f(theta) whose partials are df * d theta / d y_j; degree bound over the
    common denominator Q_f Q_df Q_theta."""
    if not isinstance(f, Jet) or not isinstance(df, Jet):
        raise NotRational("sin theta is not rational here")
    n = max(f.n + df.d + theta.d, df.n + theta.n + f.d)
    return Jet(f.v, tuple(df.v * x for x in theta.g), n, f.d + df.d + theta.d)
