"""Checks of Poisson and symmetry structure, pointwise with exact derivatives (complex step)
at the random phase points of pointwise.py, mapped to each formula's own variables:

  jacobi, jacobi_fails   J_il d_l J_jk + cyclic = 0 for the printed tensor J(x)
  casimir                J grad C = 0 for the listed functions C
  bracket_rank           rank J(x) equals the printed number (n - number of Casimirs)
  hamiltonian_field      after d tau = N dt: (1/N) dx/dt = J grad H, dx/dt the full field
                         pushed forward by the variable map (or by check_args.transform)
  hamiltonian_field_on_level  the same at points of the zero level of check_args.against
  hamiltonian_attempt    a construction tried for an unprinted Hamiltonian form: Jacobi and
                         flow over the whole phase space; unchecked (inconclusive) unless both hold
  symmetry               [v, X] = DX v - Dv X = 0 for the printed field X (2.4)
  functionally_dependent the gradients (in the full state) of the formulas are dependent

(permanent_rotations, the family of vertical permanent rotations, is in rotations.py.)

Contracts with the formula modules:
  bracket   f(P, x) -> antisymmetric n x n matrix, complex-safe (it is differentiated);
            a tensor with a free function (2.10) takes `lam=` (the VALUE lambda(x), which
            the checks compute from the same, possibly complex, x so that its derivatives
            enter the Jacobi identity); with check_args.against a formula of role
            definition (2.11), the checked tensor is lambda^-1 J_lambda, lambda = against.
  time-change f(P, x) -> N of d tau = N dt.
  condition (parameters) f(P) -> a scalar that vanishes, or a pair (lhs, rhs).
Residuals are normalised by the size of the terms that cancel, so round-off gives ~1e-15.
"""

import inspect

import numpy as np

from catalogue.numbering import printed
from solvers.verify.checks.common import (
    TOL,
    H,
    directional,
    full_field,
    gradient,
    implementation,
)
from solvers.verify.checks.pointwise import complex_field, max_residual, sample_points, verdict_of
from solvers.verify.registry import CORRECTED, Outcome, check
from solvers.verify.variables import to_vars


def state_vars(catalogue, fid):
    return catalogue.formula(fid).variables.value


def _has_corrected(*fids):
    return any(f is not None and f in CORRECTED for f in fids)


def _impl(fid, use_corrected):
    return implementation(fid, use_corrected and fid in CORRECTED)


# --- the tensor of a claim --------------------------------------------------------------------

def bracket_fn(catalogue, claim, use_corrected=False, free=None):
    """x -> J(x) for the claim's bracket. `free`: how to fill a free function lambda of the
    tensor when the claim does not fix it (None: the formula's default; "arbitrary": a
    non-constant affine function of x, the same at every point)."""
    fid = claim.check_args.bracket
    J = _impl(fid, use_corrected)
    takes_lam = "lam" in inspect.signature(J).parameters
    against = claim.check_args.against
    if takes_lam and against is not None and \
            catalogue.formula(against).role.value == "definition":
        lam = implementation(against)       # (2.11): the conformal factor lambda(x)

        def conformal(P, x):
            lv = lam(P, x)
            return J(P, x, lam=lv) / lv
        return conformal
    if takes_lam and free == "arbitrary":
        c = np.array([0.6, 0.3, -0.2, 0.25, 0.15, -0.1])

        def with_lam(P, x):
            return J(P, x, lam=c[0] + c[1:len(x) + 1] @ x)
        return with_lam
    return J


def _derivatives(f, x, n_out=None):
    """d f / d x_l for every l (complex step), stacked on the first axis."""
    out = []
    for j in range(len(x)):
        xc = x.astype(np.complex128)
        xc[j] += 1j * H
        out.append(np.asarray(f(xc)).imag / H)
    return np.stack(out)


def jacobi_residual_at(J, x):
    """max |J_il d_l J_jk + J_jl d_l J_ki + J_kl d_l J_ij| over (i, j, k), divided by the
    largest sum of the moduli of the products J_il d_l J_jk (all l, all three terms)."""
    J0 = np.asarray(J(x)).real
    dJ = _derivatives(J, x)                        # dJ[l] = d J / d x_l
    A = np.einsum("il,ljk->ijk", J0, dJ)
    T = A + np.einsum("jki->ijk", A) + np.einsum("kij->ijk", A)
    S = np.einsum("il,ljk->ijk", abs(J0), abs(dJ))
    S = S + np.einsum("jki->ijk", S) + np.einsum("kij->ijk", S)
    antisym = np.max(abs(J0 + J0.T)) / max(np.max(abs(J0)), 1e-300)
    return max(np.max(abs(T)) / max(np.max(S), 1e-300), antisym)


def _point_residual(catalogue, case, claim, at, seed):
    """max over the claim's random points of at(P, x), x in the bracket's variables."""
    V = state_vars(catalogue, claim.check_args.bracket)

    def residual(P, y):
        return at(P, np.asarray(to_vars(V, P, y)).real)
    return max_residual(sample_points(case, claim, seed), residual)[0]


def _pushforward_residual(catalogue, claim, P, y, use_corrected):
    """check_args.transform of a jacobi claim, when it names another bracket: the claim's
    tensor must be the push-forward D phi J_t D phi^T of that one (same dimension)."""
    Jt = _impl(claim.check_args.transform, use_corrected)
    Vt = state_vars(catalogue, claim.check_args.transform)
    Vb = state_vars(catalogue, claim.check_args.bracket)
    J = bracket_fn(catalogue, claim, use_corrected)
    xt = np.asarray(to_vars(Vt, P, y)).real
    xb = np.asarray(to_vars(Vb, P, y)).real
    Db = _derivatives(lambda yy: to_vars(Vb, P, yy), y).T     # d xb / d y
    Dt = _derivatives(lambda yy: to_vars(Vt, P, yy), y).T     # d xt / d y
    D = Db @ np.linalg.inv(Dt)                                # d xb / d xt
    push = D @ np.asarray(Jt(P, xt)).real @ D.T
    mine = np.asarray(J(P, xb)).real
    return np.max(abs(push - mine)) / max(np.max(abs(push)), np.max(abs(mine)), 1e-300)


def jacobi_residual(catalogue, case, claim, use_corrected=False, free=None, seed=11):
    J = bracket_fn(catalogue, claim, use_corrected, free)
    res = _point_residual(catalogue, case, claim,
                          lambda P, x: jacobi_residual_at(lambda xx: J(P, xx), x), seed)
    t = claim.check_args.transform
    if t is not None and catalogue.formula(t).role.value == "bracket":
        push = max_residual(sample_points(case, claim, seed),
                             lambda P, y: _pushforward_residual(catalogue, claim, P, y,
                                                                use_corrected))[0]
        res = max(res, push)
    return res


@check("jacobi")
def check_jacobi(catalogue, case, claim):
    res = jacobi_residual(catalogue, case, claim)
    corr = None
    if res > TOL and _has_corrected(claim.check_args.bracket):
        corr = jacobi_residual(catalogue, case, claim, use_corrected=True)
    what = f"Jacobi identity of {claim.check_args.bracket}"
    if claim.check_args.transform:
        what += f" (and push-forward of {claim.check_args.transform})"
    return verdict_of(res, corr, what=what)


@check("jacobi_fails")
def check_jacobi_fails(catalogue, case, claim):
    res = jacobi_residual(catalogue, case, claim)
    return verdict_of(res, negative=True, what=f"the Jacobi identity of {claim.check_args.bracket}"
                    " (free function at the formula's default)")


# --- Casimirs and rank ------------------------------------------------------------------------

@check("casimir")
def check_casimir(catalogue, case, claim):
    Vb = state_vars(catalogue, claim.check_args.bracket)
    J = bracket_fn(catalogue, claim)
    for c in claim.check_args.casimirs:
        if state_vars(catalogue, c) != Vb:
            raise LookupError(f"Casimir {c} is not written in the bracket's variables {Vb}")
    Cs = [implementation(c) for c in claim.check_args.casimirs]

    def at(P, x):
        J0 = np.asarray(J(P, x)).real
        worst = 0.0
        for C in Cs:
            g = gradient(lambda xx, C=C: C(P, xx), x)
            r = J0 @ g
            scale = abs(J0) @ abs(g)
            worst = max(worst, np.max(abs(r)) / max(np.max(scale), 1e-300))
        return worst

    res = _point_residual(catalogue, case, claim, at, seed=12)
    return verdict_of(res, what=f"J grad C = 0 for C in {', '.join(claim.check_args.casimirs)}")


@check("bracket_rank")
def check_bracket_rank(catalogue, case, claim):
    """rank r: s_{r+1}/s_1 = 0 (to TOL) and s_r/s_1 > TOL at every point (singular values of
    J(x) in decreasing order)."""
    rank = claim.check_args.rank
    J = bracket_fn(catalogue, claim)
    kept = [np.inf]

    def at(P, x):
        s = np.linalg.svd(np.asarray(J(P, x)).real, compute_uv=False)
        if rank > 0:
            kept[0] = min(kept[0], s[rank - 1] / s[0])
        return s[rank] / s[0] if rank < len(s) else 0.0

    res = _point_residual(catalogue, case, claim, at, seed=13)
    fid = claim.check_args.bracket
    if res <= TOL and kept[0] <= TOL:
        return Outcome("fails", kept[0], f"rank of {fid} is below {rank}: s_{rank}/s_1 = "
                       f"{kept[0]:.2e}")
    out = verdict_of(res, what=f"rank {rank} of {fid} (s_{rank + 1}/s_1 = 0)")
    if res <= TOL:
        out.message += f"; the kept s_{rank}/s_1 >= {kept[0]:.2e}"
    return out


# --- Hamiltonian form after a change of time ----------------------------------------------------

def hamiltonian_parts(catalogue, claim, use_corrected=False):
    """(J, H, N or None, to_b) of a Hamiltonian-form claim: the bracket, the Hamiltonian, the
    time multiplier and the map of the state to the bracket's variables (through
    check_args.transform when given); shared by this check and its exact twin."""
    a = claim.check_args
    Vb = state_vars(catalogue, a.bracket)
    if state_vars(catalogue, a.hamiltonian) != Vb:
        raise LookupError(f"{a.hamiltonian} is not written in the variables of {a.bracket}")
    J = bracket_fn(catalogue, claim, use_corrected, free="arbitrary")
    Hf = _impl(a.hamiltonian, use_corrected)
    Nf = _impl(a.multiplier, use_corrected) if a.multiplier else None
    if a.transform is not None:
        T = _impl(a.transform, use_corrected)
        Vt = state_vars(catalogue, a.transform)
        to_b = lambda P, yy: T(P, to_vars(Vt, P, yy))  # noqa: E731
    else:
        to_b = lambda P, yy: to_vars(Vb, P, yy)  # noqa: E731
    return J, Hf, Nf, to_b


def hamiltonian_residual(catalogue, case, claim, use_corrected=False, seed=14, level=None):
    """max ||(1/N) dx/dt - J grad H|| / max(||(1/N) dx/dt||, ||J grad H||), dx/dt the model's
    field pushed forward to the bracket's variables (through check_args.transform when given).
    level: a formula F of the full state, linear in M; the points are then moved onto F = 0
    (M -> M - F grad_M F/|grad_M F|^2, exact for F linear in M)."""
    a = claim.check_args
    J, Hf, Nf, to_b = hamiltonian_parts(catalogue, claim, use_corrected)
    on_level = _zero_level(catalogue, level) if level is not None else (lambda P, y: y)

    def residual(P, y):
        y = on_level(P, y)
        v = full_field(P, y)
        x = np.asarray(to_b(P, y)).real
        xdot = directional(lambda yy: to_b(P, yy), y, v)
        N = 1.0 if Nf is None else float(np.real(Nf(P, to_vars(state_vars(catalogue, a.multiplier),
                                                                   P, y))))
        lhs = xdot / N
        rhs = np.asarray(J(P, x)).real @ gradient(lambda xx: Hf(P, xx), x)
        return np.linalg.norm(lhs - rhs) / max(np.linalg.norm(lhs), np.linalg.norm(rhs), 1e-300)

    return max_residual(sample_points(case, claim, seed), residual)[0]


def _zero_level(catalogue, fid):
    """y -> the point of the zero level of formula fid (linear in M) with the same gamma."""
    F, V = implementation(fid), state_vars(catalogue, fid)

    def project(P, y):
        f = lambda yy: F(P, to_vars(V, P, yy))  # noqa: E731
        grad = gradient(f, y)
        out = np.array(y, dtype=float)
        out[:3] -= f(y).real * grad[:3] / (grad[:3] @ grad[:3])
        return out
    return project


@check("hamiltonian_field_on_level")
def check_hamiltonian_field_on_level(catalogue, case, claim):
    """hamiltonian_field at points of the zero level of check_args.against only (a bracket
    that is shown to generate the flow on one level of an integral, not everywhere)."""
    a = claim.check_args
    res = hamiltonian_residual(catalogue, case, claim, level=a.against)
    out = verdict_of(res, what=f"d x/d tau = J grad H with J = {a.bracket}, H = {a.hamiltonian}, "
                   f"d tau = N dt (N = {a.multiplier}), on the level {a.against} = 0")
    out.evidence = {"level of": printed(catalogue.formula(a.against).label) or a.against,
                    "flow residual on the level": res}
    return out


@check("hamiltonian_attempt")
def check_hamiltonian_attempt(catalogue, case, claim):
    """A construction the project tried for an asserted Hamiltonian form, over the whole phase
    space: verified if its tensor satisfies the Jacobi identity AND generates the flow after
    d tau = N dt; otherwise unchecked (inconclusive): a failed attempt neither confirms nor
    refutes that some bracket exists. Both residuals are kept as evidence."""
    a = claim.check_args
    jac = jacobi_residual(catalogue, case, claim)
    flow = hamiltonian_residual(catalogue, case, claim)
    ev = {"Jacobi identity residual": jac, "flow residual": flow, "tolerance": TOL}
    if a.against is not None:     # where the construction does hold: the zero level of F
        ev["flow residual on the level"] = hamiltonian_residual(catalogue, case, claim,
                                                                level=a.against)
        ev["level of"] = printed(catalogue.formula(a.against).label) or a.against
    what = f"{a.bracket} with H = {a.hamiltonian}, d tau = N dt (N = {a.multiplier})"
    if jac <= TOL and flow <= TOL:
        return Outcome("verified", max(jac, flow), f"{what}: Jacobi identity {jac:.2e} and "
                       f"flow {flow:.2e} <= {TOL:g}", evidence=ev)
    return Outcome("unchecked", max(jac, flow), f"the attempt {what} is not a Hamiltonian "
                   f"form: Jacobi identity residual {jac:.2e}, flow residual {flow:.2e} "
                   f"(tolerance {TOL:g}); this neither confirms nor refutes that a bracket "
                   "exists", evidence=ev)


@check("hamiltonian_field")
def check_hamiltonian_field(catalogue, case, claim):
    a = claim.check_args
    res = hamiltonian_residual(catalogue, case, claim)
    corr = None
    if res > TOL and _has_corrected(a.bracket, a.hamiltonian, a.multiplier, a.transform):
        corr = hamiltonian_residual(catalogue, case, claim, use_corrected=True)
    what = f"d x/d tau = J grad H with J = {a.bracket}, H = {a.hamiltonian}"
    if a.multiplier:
        what += f", d tau = N dt (N = {a.multiplier})"
    if a.transform:
        what += f", x = {a.transform}(M, gamma)"
    out = verdict_of(res, corr, what=what)
    if a.transform and out.verdict == "fails":
        out.message += (f" (this tests the construction through {a.transform}: it refutes "
                        "that pull-back, not a Hamiltonian form with an unprinted bracket)")
    return out


# --- symmetry field ---------------------------------------------------------------------------

@check("symmetry")
def check_symmetry(catalogue, case, claim):
    fid = claim.check_args.formula
    V = state_vars(catalogue, fid)
    if V not in ("(M, gamma)", "(M, r1, r2)"):
        raise LookupError(f"symmetry field {fid} is not written in the full state ({V})")
    X = implementation(fid)

    def residual(P, y):
        v = full_field(P, y)
        Xy = np.asarray(X(P, y)).real
        DXv = directional(lambda yy: X(P, yy), y, v)
        DvX = directional(lambda yy: complex_field(P, yy), y, Xy)
        return np.linalg.norm(DXv - DvX) / max(np.linalg.norm(DXv) + np.linalg.norm(DvX),
                                               1e-300)

    res = max_residual(sample_points(case, claim, 15), residual)[0]
    return verdict_of(res, what=f"[v, {fid}] = 0")


# --- functional dependence --------------------------------------------------------------------

def dependence_residual(catalogue, case, claim, seed=16):
    """Smallest singular value of the unit gradients (in the full state) of the formula and
    `against` (and any casimirs listed): 0 when they are functionally dependent."""
    fids = [claim.check_args.formula, claim.check_args.against, *claim.check_args.casimirs]
    fns = [(implementation(f), state_vars(catalogue, f)) for f in fids]

    def residual(P, y):
        G = []
        for F, V in fns:
            g = gradient(lambda yy, F=F, V=V: F(P, to_vars(V, P, yy)), y)
            G.append(g / max(np.linalg.norm(g), 1e-300))
        return np.linalg.svd(np.array(G), compute_uv=False)[-1]

    return max_residual(sample_points(case, claim, seed), residual)[0]


@check("functionally_dependent")
def check_functionally_dependent(catalogue, case, claim):
    res = dependence_residual(catalogue, case, claim)
    names = [claim.check_args.formula, claim.check_args.against, *claim.check_args.casimirs]
    return verdict_of(res, what=f"dependence of {', '.join(names)} (smallest singular value of "
                    "the unit gradients)")
