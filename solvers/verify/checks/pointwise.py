"""Pointwise checks with exact derivatives at random phase points: integrals, measures,
identities, and printed systems against the full field."""

import numpy as np

from catalogue.schema import Gyrostat, Potential
from solvers.models.derivatives import field
from solvers.verify.checks.common import (
    N_POINTS,
    N_SETTINGS,
    TOL,
    directional,
    divergence_terms,
    full_field,
    gradient,
    implementation,
)
from solvers.verify.params import draw, merged_conditions, random_states
from solvers.verify.registry import COMPARISONS, CORRECTED, Outcome, check
from solvers.verify.variables import SAME_DIMENSION, log_det, to_vars


def sample_points(case, claim, seed):
    rng = np.random.default_rng(seed)
    for _ in range(N_SETTINGS):
        P = draw(case, claim, rng)
        for y in random_states(P, N_POINTS, rng):
            yield P, y


def _formula_vars(catalogue, fid):
    return catalogue.formula(fid).variables.value


def max_residual(points, residual):
    worst, where = 0.0, None
    for P, y in points:
        r = residual(P, y)
        if not np.isfinite(r):
            return float("inf"), (P, y)
        if r > worst:
            worst, where = r, (P, y)
    return worst, where


def verdict_of(residual, corrected_residual=None, negative=False, what=""):
    if negative:   # the claim says this should NOT hold
        if residual > TOL:
            return Outcome("evidence", residual, f"as the paper says, {what} does not hold "
                           f"here (residual {residual:.2e} > {TOL:g})")
        return Outcome("fails", residual, f"{what} holds after all (residual {residual:.2e})")
    if residual <= TOL:
        return Outcome("verified", residual, f"{what}: max normalised residual "
                       f"{residual:.2e} <= {TOL:g}")
    msg = f"{what} fails as printed: max normalised residual {residual:.2e} > {TOL:g}"
    out = Outcome("fails", residual, msg, corrected_residual=corrected_residual)
    if corrected_residual is not None:
        out.message += f"; the project's corrected form: {corrected_residual:.2e}"
    return out


# --- integrals ---------------------------------------------------------------------------

def integral_residual(catalogue, case, claim, fid, use_corrected=False, seed=0):
    F = implementation(fid, use_corrected)
    V = _formula_vars(catalogue, fid)

    def residual(P, y):
        G = lambda yy: F(P, to_vars(V, P, yy))  # noqa: E731
        v = full_field(P, y)
        gr = gradient(G, y)
        return abs(gr @ v) / max(np.linalg.norm(gr) * np.linalg.norm(v), 1e-300)

    return max_residual(sample_points(case, claim, seed), residual)[0]


def relaxed(case, claim):
    """The claim with its restrictions on the potential and the gyrostat lifted (None if it
    has none): where a claim needs U = 0 or S = 0, show what happens without."""

    cond = merged_conditions(case, claim)
    update = {}
    if cond.potential in (Potential.NONE,):
        update["potential"] = Potential.ANY
    if cond.S is Gyrostat.ZERO:
        update["S"] = Gyrostat.AXIAL if cond.I is not None and "I1=I2" in cond.I.value \
            else Gyrostat.ANY
    if not update:
        return None, {}
    new = claim.model_copy(update={"conditions": claim.conditions.model_copy(update=update)})
    return new, update


def _without_condition(out, case, claim, residual_fn):
    """Append to a verified outcome the residual with the claim's conditions lifted."""
    if out.verdict != "verified":
        return out
    loose, update = relaxed(case, claim)
    if loose is None:
        return out
    res = residual_fn(loose)
    what = ", ".join(f"{k} {v.value}" for k, v in update.items())
    out.evidence["residual without its condition (" + what + ")"] = res
    out.message += (f"; without its condition ({what}) it fails: {res:.2e}" if res > TOL
                    else f"; it also holds with {what} ({res:.2e})")
    return out


def _integral(catalogue, case, claim, negative):
    fid = claim.check_args.formula
    res = integral_residual(catalogue, case, claim, fid)
    corr = None
    if res > TOL and fid in CORRECTED and not negative:
        corr = integral_residual(catalogue, case, claim, fid, use_corrected=True)
    out = verdict_of(res, corr, negative, f"d/dt {fid} = grad F . v = 0")
    return _without_condition(out, case, claim,
                              lambda c: integral_residual(catalogue, case, c, fid))


@check("integral")
def check_integral(catalogue, case, claim):
    return _integral(catalogue, case, claim, negative=False)


@check("integral_fails")
def check_integral_fails(catalogue, case, claim):
    return _integral(catalogue, case, claim, negative=True)


# --- measures ------------------------------------------------------------------------------

ALTERNATE_VARIABLES = {"(M, gamma)": "(omega, gamma)", "(omega, gamma)": "(M, gamma)",
                       "(M, r1, r2)": "(omega, r1, r2)", "(omega, r1, r2)": "(M, r1, r2)"}


def measure_residual(catalogue, case, claim, fid, use_corrected=False, seed=1, variables=None):
    """Liouville: d/dt ln rho + div v = 0, normalised by |d/dt ln rho| + sum |dv_i/dy_i|.
    A density in other coordinates of the same dimension is pulled back to the full state
    by its Jacobian; in reduced variables the claim's `system` gives the field."""
    rho = implementation(fid, use_corrected)
    V = variables or _formula_vars(catalogue, fid)
    if V in SAME_DIMENSION:
        def residual(P, y):
            v = full_field(P, y)
            lnrho = lambda yy: np.log(rho(P, to_vars(V, P, yy))) + log_det(V, P, yy)  # noqa: E731
            dln = float(directional(lnrho, y, v))
            div, scale = divergence_terms(lambda yy: complex_field(P, yy), y)
            return abs(dln + div) / max(abs(dln) + scale, 1e-300)
    else:
        sys_id = claim.check_args.system
        if sys_id is None:
            raise LookupError(f"{claim.id}: a density in {V} needs check_args.system")
        f = implementation(sys_id, use_corrected and sys_id in CORRECTED)

        def residual(P, y):
            x = np.asarray(to_vars(V, P, y), dtype=float)
            v = np.asarray(f(P, x), dtype=float)
            lnrho = lambda xx: np.log(rho(P, xx))  # noqa: E731
            dln = float(directional(lnrho, x, v))
            div, scale = divergence_terms(lambda xx: f(P, xx), x)
            return abs(dln + div) / max(abs(dln) + scale, 1e-300)

    return max_residual(sample_points(case, claim, seed), residual)[0]


def complex_field(P, y):
    v, _ = field(P.model.model, P.p, y)
    return v


def _measure(catalogue, case, claim, negative):
    """The density in the variables the catalogue gives it; where that fails, the other
    natural reading ((M, gamma) <-> (omega, gamma)) is tried too, for densities whose
    variables the paper does not state."""
    fid = claim.check_args.formula
    V = _formula_vars(catalogue, fid)
    res = measure_residual(catalogue, case, claim, fid)
    alt = ALTERNATE_VARIABLES.get(V)
    alt_res = None
    if res > TOL and alt is not None:
        alt_res = measure_residual(catalogue, case, claim, fid, variables=alt)
    corr = None
    if res > TOL and fid in CORRECTED and not negative:
        corr = measure_residual(catalogue, case, claim, fid, use_corrected=True)
    if alt_res is not None and alt_res <= TOL and not negative:
        out = Outcome("verified", alt_res, f"div({fid} v) = 0 holds read as a density in "
                      f"{alt} (residual {alt_res:.2e}); in {V} it fails ({res:.2e})")
    else:
        out = verdict_of(res, corr, negative, f"div({fid} v) = 0 in {V}")
        if alt_res is not None:
            out.message += f"; read in {alt} it fails too ({alt_res:.2e})"
    out.evidence = {"residual_" + V: res, **({"residual_" + alt: alt_res} if alt_res else {})}
    if not negative and res <= TOL:
        _without_condition(out, case, claim,
                           lambda c: measure_residual(catalogue, case, c, fid))
    return out


@check("measure")
def check_measure(catalogue, case, claim):
    return _measure(catalogue, case, claim, negative=False)


@check("measure_fails")
def check_measure_fails(catalogue, case, claim):
    return _measure(catalogue, case, claim, negative=True)


# --- identities and printed systems --------------------------------------------------------

def relative_difference(a, b):
    a, b = np.atleast_1d(np.asarray(a, dtype=complex)), np.atleast_1d(np.asarray(b, dtype=complex))
    return float(np.max(np.abs(a - b)) / max(np.max(np.abs(a)), np.max(np.abs(b)), 1e-300))


def identity_residual(catalogue, case, claim, use_corrected=False, seed=2):
    fid, other = claim.check_args.formula, claim.check_args.against
    V = _formula_vars(catalogue, fid)
    pair = COMPARISONS.get((fid, other))
    if pair is not None:       # registered comparison (registry.compares)
        def residual(P, y):
            return relative_difference(*pair(P, to_vars(V, P, y), corrected=use_corrected))
        return max_residual(sample_points(case, claim, seed), residual)[0]
    f = implementation(fid, use_corrected)
    if other is None:          # the formula returns (lhs, rhs): its own two printed forms
        def residual(P, y):
            lhs, rhs = f(P, to_vars(V, P, y))
            return relative_difference(lhs, rhs)
    else:
        g = implementation(other)
        W = _formula_vars(catalogue, other)

        def residual(P, y):
            return relative_difference(f(P, to_vars(V, P, y)), g(P, to_vars(W, P, y)))
    return max_residual(sample_points(case, claim, seed), residual)[0]


@check("identity")
def check_identity(catalogue, case, claim):
    res = identity_residual(catalogue, case, claim)
    corr = None
    if res > TOL and claim.check_args.formula in CORRECTED:
        corr = identity_residual(catalogue, case, claim, use_corrected=True)
    return verdict_of(res, corr, what=f"{claim.check_args.formula} == "
                    f"{claim.check_args.against or 'its second form'}")


PARAMETRISED = {"(gamma3, K1, K2)", "(theta, K1, K2)", "(u, K1, K2)"}


def reduced_residual(catalogue, case, claim, use_corrected=False, seed=3):
    """A printed system in variables V against the full field pushed forward by the map
    full -> V: dx/dt = D phi . v (exact, complex step). For systems written with the first
    variable s as independent variable (dK/dgamma3, dK/dtheta, dK/du) compare with
    (dK/dt) / (ds/dt)."""
    fid = claim.check_args.formula
    f = implementation(fid, use_corrected)
    V = _formula_vars(catalogue, fid)

    def residual(P, y):
        v = full_field(P, y)
        xdot = directional(lambda yy: to_vars(V, P, yy), y, v)
        x = np.asarray(to_vars(V, P, y), dtype=float)
        printed = np.asarray(f(P, x), dtype=float)
        want = xdot[1:] / xdot[0] if V in PARAMETRISED else xdot
        return relative_difference(printed, want)

    return max_residual(sample_points(case, claim, seed), residual)[0]


def transform_residuals(catalogue, case, claim, seed=4):
    """A claimed map x~ = T(x) onto the Chaplygin ball on a plane ((2.23), U = 0): every
    such ball conserves |M|^2 and (M, gamma), whatever its inertia and time scale, so the
    transformed flow must conserve |M~|^2 and (M~, gamma~). Returns the two max rates."""
    T = implementation(claim.check_args.transform)

    def rate(k):
        def residual(P, y):
            v = full_field(P, y)
            def G(yy):
                x = T(P, yy)
                return x[:3] @ x[:3] if k == 0 else x[:3] @ x[3:6]
            gr = gradient(G, y)
            return abs(gr @ v) / max(np.linalg.norm(gr) * np.linalg.norm(v), 1e-300)
        return max_residual(sample_points(case, claim, seed), residual)[0]

    return rate(0), rate(1)


@check("reduced_agrees")
def check_reduced(catalogue, case, claim):
    if claim.check_args.transform is not None and claim.check_args.against == "chaplygin_system":
        m2, area = transform_residuals(catalogue, case, claim)
        ev = {"rate |M~|^2": m2, "rate (M~, gamma)": area}
        if max(m2, area) > TOL:
            return Outcome("fails", max(m2, area),
                           f"the transformed flow does not conserve |M~|^2 (rate {m2:.2e}) "
                           f"/ (M~, gamma) (rate {area:.2e}); every Chaplygin ball on a plane "
                           "conserves both, so the printed map cannot produce one", ev)
        return Outcome("unchecked", max(m2, area), "necessary conditions hold (|M~|^2 and "
                       "(M~, gamma) conserved); the target's inertia and time scale are not "
                       "printed, so the full equivalence is not tested", ev)
    res = reduced_residual(catalogue, case, claim)
    corr = None
    if res > TOL and claim.check_args.formula in CORRECTED:
        corr = reduced_residual(catalogue, case, claim, use_corrected=True)
    return verdict_of(res, corr, what=f"{claim.check_args.formula} agrees with the full field")
