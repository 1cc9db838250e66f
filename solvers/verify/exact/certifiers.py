"""Which checks have an exact certifier, and why the others stay numeric."""

from solvers.verify.checks.negative import CANDIDATES, case_params
from solvers.verify.checks.ode import RATE_FORMULAS, is_jet_claim
from solvers.verify.exact import checks as X
from solvers.verify.exact import proofs
from solvers.verify.exact import structure as S
from solvers.verify.exact.certify import Unsupported, run_points
from solvers.verify.exact.flow_series import second_order  # (2.17), (2.33), (3.5)
from solvers.verify.exact.rational import NotRational
from solvers.verify.params import draw

# check name -> (residual builder, negative?)  negative: the claim says it does NOT hold
CERTIFIERS = {
    "integral": (X.integral, False),
    "integral_fails": (X.integral, True),
    "measure": (X.measure, False),
    "measure_fails": (X.measure, True),
    "identity": (X.identity, False),
    "reduced_agrees": (X.reduced, False),
    "jacobi": (S.jacobi, False),
    "jacobi_fails": (S.jacobi, True),
    "hamiltonian_field": (S.hamiltonian, False),
}

# Why the other checks stay numeric: where no exact test applies, the reason is stated.
NUMERIC = {
    "solves_ode": "a printed solution with trigonometric/hyperbolic or hypergeometric "
                  "functions of the state (eq-**, eq3.21): not algebraic",
    "negative_integral": "negative evidence from trajectories (returns of an integral "
                         "candidate), not a pointwise identity",
    "negative_measure": "negative evidence: a search for a density along trajectories",
    "permanent_rotations": "a statement about trajectories (stationary motions), checked "
                           "by integration",
    "linear_integrals": "recurrence of K1, K2 along long trajectories: trajectory evidence",
    "casimir": "no exact certifier yet",
    "hamiltonian_field_on_level": "no exact certifier yet (its points lie on a level set of "
                                  "an integral, and its bracket is a pull-back computed "
                                  "with a matrix inverse)",
    "hamiltonian_attempt": "a failed construction, not a claim that holds: its residuals are "
                           "evidence, no certificate is due",
    "bracket_rank": "a rank, not an identity",
    "functionally_dependent": "a rank statement about gradients",
    "symmetry": "no exact certifier yet",
    "open_problem": "nothing to compute",
    "formula_not_printed": "nothing to compute",
    "not_checkable": "nothing to compute",
}

_REASONS: dict[str, str] = {}


def _candidates():
    return CANDIDATES


def _found_density(catalogue, case, claim, key):
    """Item 6: the object that refutes the paper's doubt, certified exactly. `holds` is
    about the found density (it IS invariant), `refutes` says what that means for the
    negative claim."""
    res = X.found_density(catalogue, claim, False, case.id)
    try:
        out = run_points(key, lambda rng: case_params(case, claim, rng), res,
                         proof=_stored_proof(catalogue, case, claim, False))
    except (Unsupported, NotRational) as e:
        _REASONS[key] = f"not algebraic at our rational points: {e}"
        return None
    out["negative"] = True
    out["object"] = f"invariant density {res.density} in (M, gamma)"
    if out["holds"]:
        out["refutes"] = ("the paper's 'probably this generalization does not exist': the "
                          "density above satisfies the Liouville equation exactly")
    return out


def _rate_formulas():
    return RATE_FORMULAS


def _second_order(catalogue, claim):
    return is_jet_claim(catalogue, claim)


def why_not(claim_id: str) -> str | None:
    """Why the last exact_for(...) of this claim returned None."""
    return _REASONS.get(claim_id)


def _builder(catalogue, case, claim):
    """(residual builder, negative?) of a claim, or (None, reason)."""
    name = claim.check.value
    args = claim.check_args
    if name == "reduced_agrees" and args.transform is not None \
            and args.against == "chaplygin_system":     # as checks/pointwise.check_reduced
        return X.transform, False
    if name == "reduced_agrees" and _second_order(catalogue, claim):
        return second_order, False
    if name == "identity" and args.formula in _rate_formulas():
        return X.rate_identity, False
    if name in CERTIFIERS:
        return CERTIFIERS[name]
    return None, NUMERIC.get(name, f"no exact certifier for check {name}")


def residual_job(catalogue, case, claim, corrected=False):
    """(seed key, parameter draw, residual) of the record, as exact_for runs it; None where
    no exact test applies. prove_all.generate proves these."""
    key = claim.id + ("/corrected" if corrected else "")
    if claim.check.value == "negative_measure" and case.id in _candidates():
        res = X.found_density(catalogue, claim, False, case.id)
        return key, (lambda rng: case_params(case, claim, rng)), res
    build, _ = _builder(catalogue, case, claim)
    if build is None:
        return None
    try:
        res = build(catalogue, claim, corrected)
    except (Unsupported, NotRational, TypeError, ValueError, AttributeError, LookupError):
        return None
    return key, (lambda rng: draw(case, claim, rng)), res


def _stored_proof(catalogue, case, claim, corrected):
    return proofs.lookup(claim.id + ("/corrected" if corrected else ""),
                         proofs.fingerprint(catalogue, case, claim, corrected))


def exact_for(catalogue, case, claim, corrected=False):
    """The `exact` field of the record of `claim` (of its project correction if
    `corrected`): None where no exact test applies (reason: why_not(claim.id)). A record
    with a current stored symbolic proof (proofs.py) carries it."""
    key = claim.id + ("/corrected" if corrected else "")
    name = claim.check.value
    args = claim.check_args
    if name == "negative_measure" and case.id in _candidates():
        return _found_density(catalogue, case, claim, key)
    build, negative = _builder(catalogue, case, claim)
    if build is None:
        _REASONS[key] = negative
        return None
    proof = _stored_proof(catalogue, case, claim, corrected)
    try:
        res = build(catalogue, claim, corrected)
        out = run_points(key, lambda rng: draw(case, claim, rng), res, proof=proof)
        if not out["holds"] and name == "measure" and not corrected:
            alt = X.ALTERNATE.get(catalogue.formula(args.formula).variables.value)
            if alt is not None:      # as the complex-step check: the other natural reading
                alt_out = run_points(key, lambda rng: draw(case, claim, rng),
                                     X.measure(catalogue, claim, corrected, variables=alt))
                if alt_out["holds"]:
                    alt_out["method"] += f"; density read in {alt}"
                    out = alt_out
    except (Unsupported, NotRational) as e:
        _REASONS[key] = f"not algebraic at our rational points: {e}"
        return None
    except (TypeError, ValueError, AttributeError, LookupError, ArithmeticError) as e:
        # the formula's code is not exact-evaluable (numba kernels, float(), complex step)
        _REASONS[key] = f"not exactly evaluable: {type(e).__name__}: {e}"
        return None
    out["negative"] = negative
    return out
