"""Non-existence of a smooth invariant measure, proved in exact rational arithmetic:
the check `no_measure`.

The systems it applies to are the zero-potential, gyrostat-free cases whose measure the
paper doubts (the unbalanced ball on a plane, (2.28), and on a sphere, (3.12); the body
with a flat base, z != 0, (3.16)-(3.17)) or leaves open (the balanced ellipsoid with
I = mu E + lambda m B, lambda not 0 or 1, (2.39)-(2.40), and its general case, where "no
obstacles to an analytic measure are found yet"). Their field is homogeneous in M:

    dM/dt is quadratic in M, d(position)/dt is linear in M          (H)

(omega = I_Q^-1 M and dr/dt are linear in M; U = 0, S = 0). The proof has three steps.

1. Homogeneity reduces any density to one of the position (Kozlov's argument). Let rho > 0
   be a C^1 invariant density on a neighbourhood of the rest points (0, pos), pos near pos*.
   Phi_s(M, pos) = (s M, pos) conjugates v to s v by (H) (v(Phi_s x) = s DPhi_s v(x)), so
   rho_s(M, pos) = rho(s M, pos) is an invariant density of v for every s > 0 (the pulled
   back measure s^3 rho_s dx is invariant for s v). As s -> 0, rho_s -> rho0(pos) =
   rho(0, pos) in C^1 on compact sets, so rho0 (positive) is an invariant density too.
2. A density of the position alone needs an algebraic condition. div v is linear in M,
   div v = c(pos) . omega (no constant term: checked exactly below), and the Liouville
   equation v . grad ln rho0 + div v = 0 must hold for every omega:
       (M, gamma), sphere of curvature k: gamma' = (E - k J)^-1 (gamma x omega), so
           c = gamma x h with h = (E - k J^T)^-1 grad ln rho0, hence c . gamma = 0;
       flat base (M, r1, r2): r' = (omega2, -omega1) / k, hence c3 = 0
   (negative.py's conditions (1), whose first half is enough here).
3. One exact point where it fails. At a rational position pos* (a Pythagorean gamma, so
   |gamma| = 1 exactly) and rational parameters, c(pos*) is computed exactly with the jets
   of solvers/verify/exact (first derivatives of the exact field, no approximation); the
   obstruction Q = c . gamma (or c3) is a nonzero rational. Then no C^1 positive invariant
   density exists on any neighbourhood of the rest point (0, pos*), so none on the phase
   space, and no Hamiltonian form after a smooth positive change of time whose Poisson
   structure has constant rank near (0, pos*) (it would carry one: Weinstein's splitting
   gives such a bracket a local invariant volume).

Parameters covered: at the fixed pos*, Q is a rational function of the parameters (the
field is rational in them there; for the ellipsoid an algebraic one, through
sqrt(gamma.B gamma)), nonzero at the example, hence not the zero function: the proof covers
every parameter value off the zero set of Q, a proper algebraic subset (closed, of measure
zero), in particular an open neighbourhood of the example. The drawn parameter sets of the
claim are proved the same way, each read as exact rationals (for the ellipsoid with B33
moved by < 1% so that sqrt(gamma.B gamma) is rational at pos*: `at_point`).

Why not an equilibrium with tr(dv/dx) != 0 (the usual criterion): with U = 0 the
equilibria are the rest points (M = 0, where the linearisation vanishes) and steady
rotations (M, pos) with dpos/dt = 0; at every steady rotation we located div v = 0 to
round-off (a finding: tests/test_nonexistence.py pins it), so they decide nothing. The
rest points are where the decision is made, after the blow-up M -> s M of step 1.
Control: the same computation with the change that restores a known measure (a = 0: the
Chaplygin ball, (2.24), and the balanced ball on a sphere; z = 0: (3.18)) gives Q = 0
exactly at every point.
"""

from fractions import Fraction

import numpy as np
from flint import fmpq
from scipy.optimize import fsolve

from solvers.kernels import layout as L
from solvers.models.cases import build, registry
from solvers.models.derivatives import field as ffield
from solvers.verify.checks import negative
from solvers.verify.checks.common import N_SETTINGS, divergence_terms
from solvers.verify.checks.negative import case_params
from solvers.verify.exact.jet import Jet
from solvers.verify.exact.model import ExactParams, field
from solvers.verify.registry import Outcome, check

# Rational positions: Pythagorean unit normals gamma* (|gamma*| = 1 exactly, away from the
# poles and from the principal planes) and points (r1, r2) of the flat base.
GAMMAS = ((Fraction(3, 13), Fraction(4, 13), Fraction(12, 13)),
          (Fraction(-2, 3), Fraction(1, 3), Fraction(2, 3)),
          (Fraction(6, 7), Fraction(-2, 7), Fraction(-3, 7)))
FLAT_POINTS = ((Fraction(1, 5), Fraction(-1, 3)),
               (Fraction(-2, 7), Fraction(1, 4)),
               (Fraction(1, 2), Fraction(1, 6)))
M_PROBE = (Fraction(7, 10), Fraction(-13, 10), Fraction(2, 5))   # for the premise checks

# The change of parameters that restores a known measure: negative.CONTROLS's for the cases
# both checks share, and the ellipsoid's lambda = 1.
CONTROLS = {**{cid: negative.CONTROLS[cid] for cid in
               ("plane/unbalanced-ball", "sphere/unbalanced-ball", "sphere/flat-base")},
            "plane/ellipsoid": ({"lambda": 1.0}, "lambda = 1: density eq2.30")}
# The ellipsoid's claims hold for lambda not 0 or 1 (2.40): the example (lambda = 1, where
# (2.41) is a measure) is moved to lambda = 1/2 for them.
EXAMPLE_CHANGE = {"plane/ellipsoid": {"lambda": 0.5}}
# Claims that conjecture a measure may exist: a proof of non-existence refutes them.
REFUTES = {"plane/ellipsoid/negative/general-measure"}


def q(x) -> fmpq:
    """A parameter or coordinate as the exact rational it is (a float's binary value)."""
    fr = Fraction(x) if not isinstance(x, Fraction) else x
    return fmpq(fr.numerator, fr.denominator)


def exact_params(model) -> ExactParams:
    """The built model's parameters, every float read as its exact binary rational (a drawn
    parameter set is proved at exactly the values the float check uses)."""
    p = np.array([Jet(q(x)) for x in model.p], dtype=object)
    extra = {k: Jet(q(v)) for k, v in model.params.items() if k in ("mu", "lambda")}
    return ExactParams(model, p, extra)


def example_model(case_id: str, change: dict | None = None):
    """The case's example parameters (registry) with `change`, as a built model and as
    ExactParams holding the printed decimals exactly (0.1 is 1/10, not its binary float)."""
    spec = registry()[case_id]
    prm = dict(spec.example, **(change or {}))
    model = build(case_id, prm)
    # the shortest decimal that round-trips: the example's printed values (0.1 is 1/10)
    p = [Jet(q(Fraction(repr(float(x))))) for x in model.p]
    extra = {k: Jet(q(Fraction(repr(float(v))))) for k, v in prm.items()
             if k in ("mu", "lambda")}
    return model, ExactParams(model, np.array(p, dtype=object), extra)


def at_point(P, pos):
    """P itself, or for an ellipsoid (2.39) P with B33 changed so that sqrt(gamma.B gamma)
    is rational at gamma = pos (the nearest q with denominator <= 64 to its float value,
    B33 = (q^2 - B11 g1^2 - B22 g2^2) / g3^2) and I = mu E + lambda m B re-imposed exactly
    (2.40) where the model has it; returns (P', B33 as a Fraction or None)."""
    if all(P.p[i].v == 0 for i in (L.B11, L.B22, L.B33)):
        return P, None
    g = [q(x) for x in pos]
    b1, b2, b3 = (P.p[i].v for i in (L.B11, L.B22, L.B33))
    q0 = float(b1 * g[0] ** 2 + b2 * g[1] ** 2 + b3 * g[2] ** 2) ** 0.5
    qq = q(Fraction(q0).limit_denominator(64))
    B33 = (qq * qq - b1 * g[0] ** 2 - b2 * g[1] ** 2) / g[2] ** 2
    p = P.p.copy()
    p[L.B33] = Jet(B33)
    mu, lam = P.extra.get("mu"), P.extra.get("lambda")
    if mu is not None and lam is not None:
        for i, b in ((L.I1, L.B11), (L.I2, L.B22), (L.I3, L.B33)):
            p[i] = Jet(mu.v + lam.v * P.p[L.MASS].v * p[b].v)
    return ExactParams(P.model, p, P.extra), Fraction(int(B33.p), int(B33.q))


def _flat(P) -> bool:
    return P.model.model == L.MODEL_FLAT


def _seeded(y):
    n = len(y)
    return np.array([Jet.seed(Jet(q(x)), j, n) for j, x in enumerate(y)], dtype=object)


def exact_field(P, y):
    return [x.v for x in field(P, np.array([Jet(q(x)) for x in y], dtype=object))]


def exact_divergence(P, y) -> fmpq:
    """div v at the rational point y: the trace of the exact Jacobian (jets)."""
    v = field(P, _seeded(y))
    return sum((v[j].partial(j).v for j in range(len(y))), fmpq(0))


def premises(P, pos) -> dict:
    """Exact checks of what steps 1-2 use, at (M_PROBE, pos): the field is homogeneous in M
    (v(2M) = (4 v_M, 2 v_pos)), div v(0, pos) = 0 and div v is linear in M."""
    M = list(M_PROBE)
    v1 = exact_field(P, M + list(pos))
    v2 = exact_field(P, [2 * x for x in M] + list(pos))
    hom = all(v2[i] == 4 * v1[i] for i in range(3)) and \
        all(v2[i] == 2 * v1[i] for i in range(3, len(v1)))
    d0 = exact_divergence(P, [0, 0, 0, *pos])
    basis = [exact_divergence(P, list(e) + list(pos)) for e in np.eye(3, dtype=int).tolist()]
    dM = exact_divergence(P, M + list(pos))
    lin = dM == sum((b * q(m) for b, m in zip(basis, M, strict=True)), fmpq(0))
    return {"homogeneous": hom, "div at M = 0": d0, "div linear in M": lin,
            "div coefficients": basis}


def obstruction(P, pos):
    """(Q, c): c(pos) with div v = c . omega, exact, and Q = c . gamma (full model) or c3
    (flat base); Q != 0 excludes every density of the position near pos."""
    d = premises(P, pos)["div coefficients"]
    if _flat(P):
        r = np.array([Jet(q(pos[0])), Jet(q(pos[1])), P.z], dtype=object)
    else:
        r = P.r(np.array([Jet(q(x)) for x in pos], dtype=object))
    IQ = P.contact_inertia(r)
    c = [sum((IQ[i, j].v * d[j] for j in range(3)), fmpq(0)) for i in range(3)]
    Q = c[2] if _flat(P) else sum((c[i] * q(pos[i]) for i in range(3)), fmpq(0))
    return Q, c


def prove(P, points):
    """The first point of `points` where the premises hold exactly and Q != 0:
    (pos, Q, premises) or None (an ellipsoid is taken at_point)."""
    for pos in points:
        Pp, b33 = at_point(P, pos)
        pre = premises(Pp, pos)
        if not (pre["homogeneous"] and pre["div at M = 0"] == 0 and pre["div linear in M"]):
            continue
        Q, _ = obstruction(Pp, pos)
        if Q != 0:
            if b33 is not None:
                pre["B33 (solved for a rational sqrt(gamma.B gamma))"] = str(b33)
            return pos, Q, pre
    return None


def _points_for(P):
    return FLAT_POINTS if _flat(P) else GAMMAS


def _fmt(pos):
    return "(" + ", ".join(str(x) for x in pos) + ")"


def _params_text(model):
    keep = [k for k, v in model.params.items() if v != 0.0 or k in ("a1", "a2", "a3", "z")]
    return ", ".join(f"{k} = {model.params[k]:g}" for k in keep)


@check("no_measure")
def check_no_measure(catalogue, case, claim, *, settings=N_SETTINGS):

    if case.id not in CONTROLS:
        return Outcome("unchecked", None, f"no_measure: no homogeneous model for {case.id}")
    model, P = example_model(case.id, EXAMPLE_CHANGE.get(case.id))
    if any(P.p[i].v != 0 for i in (L.S1, L.S2, L.S3, L.GRAV, L.BRUN)):
        return Outcome("unchecked", None, "no_measure needs U = 0 and S = 0 (homogeneity)")
    ev: dict = {"criterion": "Kozlov homogeneity: a C^1 density rho(M, pos) gives the "
                "invariant density rho(0, pos); that one needs c . gamma = 0 (c3 = 0 on "
                "the flat base) where div v = c . omega"}
    found = prove(P, _points_for(P))
    if found is None:
        return Outcome("evidence", None, "no rational point with a nonzero obstruction "
                       "among those tried: not proved", evidence=ev)
    pos, Q, pre = found
    what = "c3" if _flat(P) else "c . gamma"
    ev["example parameters"] = _params_text(model)
    b33 = pre.get("B33 (solved for a rational sqrt(gamma.B gamma))")
    if b33 is not None:
        ev["example parameters"] += (f", b3 replaced by {b33} so that sqrt(gamma.B gamma) is "
                                     "rational")
    ev["rational point"] = _fmt(pos)
    ev[f"obstruction {what} (exact)"] = str(Q)
    ev[f"obstruction {what}"] = float(Q.p) / float(Q.q)
    ev["premises (exact)"] = {"v(2M) = (4 v_M, 2 v_pos)": pre["homogeneous"],
                              "div v(0, pos)": str(pre["div at M = 0"]),
                              "div v linear in M": pre["div linear in M"]}
    # the claim's own parameter draws, each proved the same way
    rng = np.random.default_rng(21)
    drawn = []
    for _ in range(settings):
        Pf = case_params(case, claim, rng)
        hit = prove(exact_params(Pf.model), _points_for(P))
        drawn.append(None if hit is None else float(hit[1].p) / float(hit[1].q))
    ev[f"drawn parameter sets: obstruction {what}"] = drawn
    change, ctext = CONTROLS[case.id]
    _, Pc = example_model(case.id, change)
    ctrl = [obstruction(at_point(Pc, pos_)[0], pos_)[0] for pos_ in _points_for(P)]
    ev["control"] = ctext
    ev[f"control: {what} at the same points (exact)"] = [str(x) for x in ctrl]
    if any(x != 0 for x in ctrl):
        return Outcome("unchecked", None, "the control has a nonzero obstruction: the test "
                       "does not separate the cases", evidence=ev)
    n_drawn = sum(x is not None for x in drawn)
    msg = (f"proved: no smooth invariant measure (rest point M = 0 at {_fmt(pos)}: exact "
           f"obstruction {what} = {float(Q.p) / float(Q.q):.6g} != 0, so no C^1 positive "
           f"density near it, by homogeneity in M); parameters: the example "
           f"({ev['example parameters']}) and every value off the zero set of this "
           f"{'algebraic' if b33 is not None else 'rational'} function of the parameters "
           f"(closed, of measure zero: an open dense set containing the example), "
           f"{n_drawn} of {settings} drawn sets proved the same way; control "
           f"({ctext}): 0 exactly")
    if claim.id.endswith("hamiltonian"):
        msg += ("; hence no Hamiltonian form after a smooth positive change of time with a "
                "Poisson structure of constant rank near the rest points")
    if n_drawn < settings:
        return Outcome("evidence", 0.0, msg, evidence=ev)
    if claim.id in REFUTES:      # the paper thinks a measure may exist: the proof refutes it
        return Outcome("fails", abs(float(Q.p) / float(Q.q)),
                       "refuted: " + msg.removeprefix("proved: "), evidence=ev)
    return Outcome("verified", 0.0, msg, evidence=ev)


# --- the equilibrium criterion, for the record (the zero-potential finding) -----------------

def steady_rotations(P, n_starts=200, seed=0, tol=1e-10):
    """Equilibria (M != 0) of the float field of Params P found by Newton (scipy fsolve) from
    random starts, with div v at each by complex step: [(y, div v)]. An equilibrium with
    div v != 0 would exclude a smooth measure; with U = 0 every one found has div v = 0 to
    round-off (module docstring), with gravity (g != 0) some do not."""

    def v(y):
        return ffield(P.model.model, P.p, y)[0]

    rng = np.random.default_rng(seed)
    out: list = []
    for _ in range(n_starts):
        y0 = rng.normal(size=6)
        y0[3:] /= np.linalg.norm(y0[3:])
        y, _, ier, _ = fsolve(lambda x: np.r_[v(x)[:5], x[3:] @ x[3:] - 1.0], y0,
                              xtol=1e-14, full_output=True)
        if ier != 1 and np.linalg.norm(v(y)) > tol:
            continue
        if np.linalg.norm(v(y)) > tol or np.linalg.norm(y[:3]) < 1e-6:
            continue
        if any(np.allclose(y, z, atol=1e-7) for z, _ in out):
            continue
        out.append((y, float(divergence_terms(v, y)[0])))
    return out
