"""Exact certifiers of the pointwise checks (solvers/verify/checks/pointwise.py).

Each certifier evaluates the same residual as its complex-step check, but exactly: at k
random rational points (points.py) the residual, derivatives included (forward-mode jets
over Q, jet.py), is zero or not. A nonzero value is a proof that the formula fails, with the
point as witness; zero at all k points certifies it up to the Schwartz-Zippel bound

    P(a nonzero residual vanishes at all k points) <= (deg / N)^k,

deg an upper bound of the total degree of the residual's numerator in the drawn free
coordinates (tracked through the arithmetic, jet.py) and N = 2^40 grid values per coordinate.
"""

import zlib

import numpy as np

from solvers.kernels import layout as L
from solvers.verify.exact.jet import Jet, NotRational, q_str
from solvers.verify.exact.linalg import exact_linalg
from solvers.verify.exact.points import BITS, GridRng, rational_state
from solvers.verify.exact.radical import Radical

K_POINTS = 3          # points per certificate: the bound below is stated for this k
METHOD = ("exact rational arithmetic (python-flint fmpq) with forward-mode derivatives "
          "(first-order jets over Q) at random rational points; gamma rational on |gamma| = 1 "
          "(Pythagorean angles), the ellipsoid's and the disk's square roots made rational "
          "(B33 solved, g1^2+g2^2 a square), other roots computed in Q(sqrt r)")

SLOT_NAMES = {L.I1: "I1", L.I2: "I2", L.I3: "I3", L.MASS: "m", L.CURV: "k", L.S1: "S1",
              L.S2: "S2", L.S3: "S3", L.GRAV: "g", L.BRUN: "eps", L.B11: "B11", L.B22: "B22",
              L.B33: "B33", L.B12: "B12", L.B13: "B13", L.B23: "B23", L.BALL_C: "c",
              L.DISK_D: "d", L.A1: "a1", L.A2: "a2", L.A3: "a3", L.FLAT_Z: "z"}


class Unsupported(Exception):
    """No exact test applies (the reason is the message)."""


def seeded(y):
    """The point y with d y_i / d y_j = delta_ij; a coordinate in Q(sqrt r) (a + c sqrt r,
    e.g. K = rho M of eq2b-*3) is seeded in its rational part."""
    n = len(y)
    out = []
    for j, v in enumerate(y):
        if isinstance(v, Radical):
            out.append(Radical(Jet.seed(v.a.value(), j, n), v.c.value(), v.r))
        else:
            out.append(Jet.seed(v, j, n))
    return np.array(out, dtype=object)


def plain(y):
    return np.array([Jet.const(v).value() for v in y], dtype=object)


def directional(X, v):
    """d/dt of the jets X along the exact field values v: sum_j dX/dy_j v_j."""
    X = np.atleast_1d(np.asarray(X, dtype=object))
    return np.array([sum((Jet.const(x).partial(j) * v[j].value() for j in range(len(v))),
                         Jet(0)) for x in X], dtype=object)


def point_json(P, y):
    out = {lab: q_str(v) for lab, v in zip(P.model.state_labels, y, strict=False)}
    for i, x in enumerate(P.p):
        if x != 0 and i in SLOT_NAMES:
            out[SLOT_NAMES[i]] = q_str(x)
    for k, v in P.extra.items():
        out[k] = q_str(v)
    return out


def residual_vector(res):
    res = np.atleast_1d(np.asarray(res, dtype=object)).ravel()
    return [Jet.const(r) for r in res]


def _draw_point(Pf_draw, rng, tries=50):
    """Parameters and a state; a draw the model rejects (triangle inequality, fit) is
    redrawn, as solvers.verify.params does."""
    for _ in range(tries):
        try:
            return rational_state(Pf_draw(rng), rng)
        except (RuntimeError, NotRational):
            continue
    raise Unsupported("no valid rational point in 50 draws")


def run_points(seed_key, Pf_draw, residual_fn, k=K_POINTS):
    """Evaluate residual_fn(P, y) -> list of Jets at k points. Returns the `exact` dict."""
    rng = GridRng(zlib.crc32(seed_key.encode()))
    deg = 0
    for _ in range(k):
        P, y = _draw_point(Pf_draw, rng)
        try:
            with exact_linalg():
                res = residual_fn(P, y)
        except ZeroDivisionError as e:
            raise Unsupported(f"singular at a rational point: {e}") from e
        for r in res:
            parts = r.parts() if isinstance(r, Radical) else (r,)
            for c in parts:
                c._known()
                deg = max(deg, c.n)
            if any(c.v != 0 for c in parts):
                text = q_str(r.a) + " + " + q_str(r.c) + f" * sqrt({q_str(r.r)})" \
                    if isinstance(r, Radical) else q_str(r)
                return {"holds": False, "points": 1, "method": METHOD,
                        "bound": "exact: a nonzero residual disproves the identity",
                        "witness": {"point": point_json(P, y), "residual": text}}
    if deg == 0:
        # every residual is a function of the seeded state, so a tracked bound of 0 means
        # the degree was lost on the way (a rational constant re-entered as a fresh jet);
        # the exact zeros stand, but no probability is claimed for them
        return {"holds": True, "points": k, "method": METHOD, "bounded": False,
                "bound": (f"exact zeros at {k} points; the degree of the residual was not "
                          "tracked through this computation, so no Schwartz-Zippel "
                          "probability is stated and the record does not count as certified"),
                "witness": None}
    N = 2 ** BITS
    p = (deg / N) ** k
    return {"holds": True, "points": k, "method": METHOD,
            "bound": (f"Schwartz-Zippel: residual numerator of total degree <= {deg} in the "
                      f"free coordinates, each uniform over N = 2^{BITS} grid values; "
                      f"P(a nonzero residual vanishes at all {k} points) <= "
                      f"({deg}/2^{BITS})^{k} = {p:.1e}"),
            "witness": None}
