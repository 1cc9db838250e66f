"""Per-check exact residuals, mirroring solvers/verify/checks/pointwise.py one by one.

Each `residual_*` returns, for a claim, a function (P, y) -> list of Jets (the residual's
components) evaluated exactly at a rational point; certify.run_points turns it into the
record's `exact` field.
"""

import numpy as np

from solvers.verify.checks.common import implementation
from solvers.verify.checks.negative import CANDIDATES
from solvers.verify.checks.pointwise import ALTERNATE_VARIABLES, PARAMETRISED
from solvers.verify.exact.certify import Unsupported, directional, plain, residual_vector, seeded
from solvers.verify.exact.jet import Jet
from solvers.verify.exact.model import field
from solvers.verify.registry import COMPARISONS
from solvers.verify.variables import SAME_DIMENSION, log_det, to_vars


def _vars(catalogue, fid):
    return catalogue.formula(fid).variables.value


def integral(catalogue, claim, use_corrected):
    """d/dt F = grad F . v (pointwise.integral_residual)."""
    fid = claim.check_args.formula
    F = implementation(fid, use_corrected)
    V = _vars(catalogue, fid)

    def res(P, y):
        v = field(P, plain(y))
        ys = seeded(y)
        return residual_vector(directional(F(P, to_vars(V, P, ys)), v))
    return res


def measure(catalogue, claim, use_corrected, variables=None):
    """d/dt ln rho + div v (pointwise.measure_residual), densities in coordinates of the
    same dimension pulled back by log det D phi."""
    fid = claim.check_args.formula
    rho = implementation(fid, use_corrected)
    V = variables or _vars(catalogue, fid)
    if V not in SAME_DIMENSION:
        raise Unsupported(f"density in reduced variables {V}: the map to them has square "
                          "roots of (1 - gamma3^2)(I1 + m r^2) that no parameter makes square")

    def res(P, y):
        ys = seeded(y)
        v = field(P, ys)
        lnrho = np.log(rho(P, to_vars(V, P, ys))) + log_det(V, P, ys)
        dln = directional(lnrho, v)[0]
        div = sum((v[j].partial(j) for j in range(len(y))), Jet(0))
        return [dln + div]
    return res


def identity(catalogue, claim, use_corrected):
    fid, other = claim.check_args.formula, claim.check_args.against
    V = _vars(catalogue, fid)
    pair = COMPARISONS.get((fid, other))

    def diff(a, b):
        a = np.atleast_1d(np.asarray(a, dtype=object)).ravel()
        b = np.atleast_1d(np.asarray(b, dtype=object)).ravel()
        return residual_vector(a - b)

    def res(P, y):
        x = to_vars(V, P, plain(y))
        if pair is not None:
            return diff(*pair(P, x, corrected=use_corrected))
        f = implementation(fid, use_corrected)
        if other is None:
            return diff(*f(P, x))
        g = implementation(other)
        return diff(f(P, x), g(P, to_vars(_vars(catalogue, other), P, plain(y))))
    return res


def reduced(catalogue, claim, use_corrected):
    """A printed system against the full field pushed forward (pointwise.reduced_residual)."""
    fid = claim.check_args.formula
    f = implementation(fid, use_corrected)
    V = _vars(catalogue, fid)

    def res(P, y):
        v = field(P, plain(y))
        X = to_vars(V, P, seeded(y))
        xdot = directional(X, v)
        x = np.array([Jet.const(c).value() for c in np.atleast_1d(X)], dtype=object)
        printed = np.atleast_1d(np.asarray(f(P, x), dtype=object))
        want = xdot[1:] / xdot[0] if V in PARAMETRISED else xdot
        return residual_vector(printed - want)
    return res


def transform(catalogue, claim, use_corrected):
    """A map onto the Chaplygin ball (pointwise.transform_residuals): the transformed flow
    must conserve |M~|^2 and (M~, gamma~)."""
    T = implementation(claim.check_args.transform)

    def res(P, y):
        v = field(P, plain(y))
        x = T(P, seeded(y))
        return [directional(x[:3] @ x[:3], v)[0], directional(x[:3] @ x[3:6], v)[0]]
    return res


ALTERNATE = ALTERNATE_VARIABLES


def found_density(catalogue, claim, use_corrected, case_id):
    """The density the project found where the paper doubts one (negative_measure with a
    candidate, checks/negative.CANDIDATES: on a sphere, (mu + m r^2)^-1/2 det(E - k J) for
    the body with spherical inertia, (2.31)'s generalisation): its Liouville residual
    d/dt ln rho + div v in (M, gamma), exactly."""
    name, rho = CANDIDATES[case_id][-1]

    def res(P, y):
        ys = seeded(y)
        v = field(P, ys)
        dln = directional(np.log(rho(P, ys)), v)[0]
        div = sum((v[j].partial(j) for j in range(len(y))), Jet(0))
        return [dln + div]
    res.density = name
    return res


def rate_identity(catalogue, claim, use_corrected):
    """An identity whose printed form needs d s/dt of its first variable (the energies after
    (3.4) and (3.25), checks/ode.rate_identity_residual): x = (to_vars(V), ds/dt)."""
    fid, other = claim.check_args.formula, claim.check_args.against
    f = implementation(fid, use_corrected)
    g = implementation(other)
    V, W = _vars(catalogue, fid), _vars(catalogue, other)

    def res(P, y):
        v = field(P, plain(y))
        X = np.atleast_1d(to_vars(V, P, seeded(y)))
        sd = directional(X[0], v)[0]
        x = np.array([*(Jet.const(c).value() for c in X), sd], dtype=object)
        lhs = np.atleast_1d(np.asarray(f(P, x), dtype=object)).ravel()
        rhs = np.atleast_1d(np.asarray(g(P, to_vars(W, P, plain(y))), dtype=object)).ravel()
        return residual_vector(lhs - rhs)
    return res
