"""Exact certifiers of the pointwise checks (solvers/verify/checks/pointwise.py).

Each certifier evaluates the same residual as its complex-step check, but exactly.

1. A proof where the algebra allows it (`prove`, symbolic.py): the residual computed as a
   rational function of the free coordinates; if its numerator is the zero polynomial the
   identity holds, with certainty.
2. Otherwise, at k = {K} random rational points (points.py) the residual, derivatives
   included (forward-mode jets over Q, jet.py), is zero or not. A nonzero value is a proof
   that the formula fails, with the point as witness; zero at all k points certifies it up
   to the Schwartz-Zippel bound

       P(a nonzero residual vanishes at all k points) <= (deg / N)^k,

   deg an upper bound of the total degree of the residual's numerator in the drawn free
   coordinates (tracked through the arithmetic, jet.py) and N = 2^{BITS} exact grid
   rationals per coordinate (points.GridRng; parameters included). A record whose degree is
   not known (a value zero at the point used as the zero function, jet.lose_degree) states
   no probability and is not counted as certified.

The points are seeded by the claim id: every certificate is reproducible, but the points
are not random against someone who chooses a formula after seeing them.
"""

import zlib

import numpy as np

from solvers.kernels import layout as L
from solvers.verify.exact.exact_mode import exact_linalg
from solvers.verify.exact.jet import Jet, Radical, q_str
from solvers.verify.exact.points import BITS, N_GRID, GridRng, rational_state
from solvers.verify.exact.rational import Lost, NotRational, Strict
from solvers.verify.exact.symbolic import RF, S, TooBig, mark, release, symbolic

K_POINTS = 3          # points per certificate: the bound below is stated for this k
PROOF_SECONDS = 4.0   # symbolic budget per record (symbolic.py; then the k-point certificate)
SEEDED = ("The points are seeded by the claim id: reproducible, but not random against "
          "someone who picks a formula after seeing them.")
PROOF_METHOD = ("symbolic: the same computation with every free coordinate (grid draws of "
                "the parameters, gamma's Pythagorean angle parameters, M, ...) a symbol; "
                "values and derivatives are rational functions N/D, N and D in Z[z] "
                "(python-flint fmpz_mpoly, reduced by their gcd), radicals in Q(z)(sqrt R)")
__doc__ = __doc__.replace("{K}", str(K_POINTS)).replace("{BITS}", str(BITS))
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
    e.g. K = rho M of (2.27)) is seeded in its rational part."""
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
        n0 = mark()
        try:
            with rng.drawing():
                Pf = Pf_draw(rng)
            return rational_state(Pf, rng)
        except (RuntimeError, NotRational):
            release(n0)          # the rejected draw's symbols are not coordinates
            continue
    raise Unsupported("no valid rational point in 50 draws")


def _parts(r):
    return r.parts() if isinstance(r, Radical) else (Jet.const(r),)


def _evaluate(residual_fn, P, y):
    """The residual at one point, strictly first (radical.Strict: no sqrt(r) coefficient
    dropped unless it is the zero function); if that leaves Q(sqrt r), again with drops
    allowed. Returns (residual list, reasons the degree bound was lost)."""
    for strict in (True, False):
        Lost.reasons = []
        Strict.on = strict
        try:
            with exact_linalg():
                return residual_fn(P, y), list(Lost.reasons)
        except NotRational:
            if not strict:
                raise
        except ZeroDivisionError as e:
            raise Unsupported(f"singular at a rational point: {e}") from e
        finally:
            Strict.on = False
    raise AssertionError("unreachable")


def prove(seed_key, Pf_draw, residual_fn, seconds=PROOF_SECONDS):
    """The symbolic proof (symbolic.py): the same draw with every free coordinate a symbol,
    the same residual as rational functions. Returns (status, info): status "proved" (every
    part of the residual is the zero function), "nonzero" (a part is a nonzero rational
    function: info = (its numerator's total degree, the tracked bound)), or "no" (info: why
    no proof was attempted to the end)."""
    rng = GridRng(zlib.crc32(seed_key.encode()))
    try:
        with symbolic(seconds) as _:
            P, y = _draw_point(Pf_draw, rng)
            with exact_linalg():
                res = residual_fn(P, y)
            parts = [c for r in res for c in _parts(r)]
            for c in parts:
                c._known()
            nvars = len(_symbols())
            if all(_rf(c.v).is_zero() for c in parts):
                return "proved", nvars
            true = max(_rf(c.v).degree() for c in parts)
            return "nonzero", (true, max(c.n for c in parts))
    except TooBig as e:
        return "no", f"too large to expand within the budget ({e})"
    except Unsupported as e:
        return "no", str(e)
    except NotRational as e:
        return "no", f"not a rational function after the substitutions: {e}"
    except ZeroDivisionError as e:
        return "no", f"a denominator is the zero function: {e}"
    except (TypeError, ValueError, AttributeError, LookupError, ArithmeticError) as e:
        return "no", f"not symbolically evaluable: {type(e).__name__}: {e}"


def _symbols():
    return S.values


def _rf(v):
    return v if isinstance(v, RF) else RF.of(v)


def bound_text(deg, k=K_POINTS):
    p = (deg / N_GRID) ** k
    return (f"Schwartz-Zippel: residual numerator of total degree <= {deg} in the free "
            f"coordinates, each uniform over N = 2^{BITS} exact grid rationals; "
            f"P(a nonzero residual vanishes at all k = {k} points) <= "
            f"({deg}/2^{BITS})^{k} = {p:.1e}. {SEEDED}")


def proof_dict(nvars):
    return {"holds": True, "kind": "proof", "points": 1, "method": PROOF_METHOD,
            "bound": (f"proved: the residual's numerator, expanded over Q in {nvars} free "
                      "coordinates, is the zero polynomial (certain, no probability; on the "
                      "region of parameter space where the signs taken at the drawn point "
                      "hold)"),
            "witness": None}


def run_points(seed_key, Pf_draw, residual_fn, k=K_POINTS, proof=None, try_proof=False):
    """The `exact` dict of one record: its symbolic proof (`proof`: the stored one,
    proofs.py; or computed now if try_proof), else residual_fn(P, y) -> list of Jets at k
    points with the Schwartz-Zippel bound."""
    if proof is not None and proof["proved"]:
        return proof_dict(proof["variables"])
    why_no_proof = proof["reason"] if proof is not None else \
        "no current stored symbolic proof (solvers/verify/exact/proofs.json)"
    if try_proof:
        status, info = prove(seed_key, Pf_draw, residual_fn)
        if status == "proved":
            return proof_dict(info)
        why_no_proof = (f"the residual is a nonzero rational function (numerator of degree "
                        f"{info[0]})" if status == "nonzero" else info)
    rng = GridRng(zlib.crc32(seed_key.encode()))
    deg, lost = 0, []
    for _ in range(k):
        P, y = _draw_point(Pf_draw, rng)
        res, why = _evaluate(residual_fn, P, y)
        lost += why
        for r in res:
            parts = _parts(r)
            for c in parts:
                c._known()
                deg = max(deg, c.n)
            if any(c.v != 0 for c in parts):
                text = q_str(r.a) + " + " + q_str(r.c) + f" * sqrt({q_str(r.r)})" \
                    if isinstance(r, Radical) else q_str(r)
                return {"holds": False, "kind": "witness", "points": 1, "method": METHOD,
                        "bound": "exact: a nonzero residual disproves the identity",
                        "witness": {"point": point_json(P, y), "residual": text},
                        "no_proof": why_no_proof}
    if deg == 0 or lost:
        why = lost[0] if lost else ("the tracked bound is 0 although the residual is a "
                                    "function of the drawn point")
        return {"holds": True, "kind": "zeros", "points": k, "method": METHOD,
                "bounded": False,
                "bound": (f"exact zeros at {k} points; the degree of the residual is not "
                          f"known ({why}), so no Schwartz-Zippel probability is stated and "
                          "the record does not count as certified"),
                "witness": None, "no_proof": why_no_proof}
    return {"holds": True, "kind": "certificate", "points": k, "method": METHOD,
            "bound": bound_text(deg, k), "degree": deg, "witness": None,
            "no_proof": why_no_proof}
