"""Checks on the paper's ODEs in reduced variables and on their solutions.

* `solves_ode`: a printed solution K(s; c) satisfies the printed ODE dK/ds = f(s, K)
  (`against`); dK/ds exact by a Cauchy contour (below), so complex-valued solutions
  ((3.23) is printed with sqrt(I1 - I3) for I1 < I3) are handled too.
* `linear_integrals`: the constants c of K = Phi(s) c + Kp(s) (fundamental matrix of the
  linear system `system`, or of the closed-form solution `formula`) are conserved along
  full trajectories: K(t) of a full run (compiled DOP853, rtol = atol = 1e-12) against the
  linear solution at s(t) started from the same point.
* extensions of two pointwise checks (checks/pointwise.py) to formulas that need more than
  their own variables:
  - `reduced_agrees` for second-order equations in (theta, omega3) and (x, omega3)
    ((2.17), (2.33), (3.5), the hypergeometric form): the formula returns the terms of its
    "lhs - rhs" at the jet (s, w, w', w''), computed along the flow (below); the residual
    is |sum of the terms| / sum of their moduli;
  - `identity` for the energies with a velocity (the energy after (3.4) and (3.25)):
    x = (s, K1, K2, ds/dt), ds/dt exact by complex step along the full field.

Second derivatives along the flow (the second-order equations, all for the disk). A
derivative along the flow of a quantity computed with a complex step cannot be taken by a
second complex step, and a finite difference or a Cauchy contour in t loses relative
accuracy where dtheta/dt is small (dw/dtheta = wdot/thetadot is a ratio of two small
numbers there: measured 1e-8 .. 5e-8 with a contour, too coarse for TOL). So d omega3/d theta
is taken in closed form from the compiled reduced field F (solvers.kernels.reduced, the full
field pushed forward; both numerator and denominator carry the factor K3 and their ratio is
exact), and d2 omega3/d theta2 = (d/dt of that)/(dtheta/dt) by one complex step along F.
At every point F is compared with the full field pushed forward (complex step of the map
(M, gamma) -> (gamma3, K1, K2, K3)) and the larger of the two residuals counts. Measured on
the corrected equations: <= 2e-11 (the consistency itself <= 1e-13); TOL is unchanged.

`solves_ode` needs dK/ds of a solution that may be complex-valued, where a complex step
does not apply: a Cauchy contour (trapezoidal rule on |t| = r, N = 32 points) gives it with
error ~ eps max|K|/r (r = 1e-2 (1 + |s|), far inside the radius of analyticity): measured
<= 2e-13 on the corrected forms.

Trajectory checks (linear_integrals) compare two integrations at rtol = atol = 1e-12 over a
few nutation periods; their measured floor is <= 5e-12 (runs of verify), so TOL applies.
"""

import numpy as np
from scipy.integrate import solve_ivp

from solvers.integrate.integrator import integrate
from solvers.kernels import layout as L
from solvers.kernels.fields import rhs
from solvers.kernels.integrals import ENERGY, integral
from solvers.models import reduced_systems as rd
from solvers.verify.checks import pointwise
from solvers.verify.checks.common import N_POINTS, N_SETTINGS, TOL, full_field, implementation
from solvers.verify.params import draw, random_states
from solvers.verify.registry import CHECKS, CORRECTED, check
from solvers.verify.variables import to_vars

N_CONTOUR = 32
JET_VARIABLES = frozenset({"(theta, omega3)", "(x, omega3)"})
# formulas whose printed form contains the rate of their first variable (role hamiltonian):
# they take x = (s, K1, K2, ds/dt)
RATE_FORMULAS = frozenset({"sphere_revolution_energy", "flat_axisym_energy"})
T_RUN = 5.0             # time span of a full run for linear_integrals
N_SAMPLES = 26          # samples along it
N_RUNS = 2              # runs per parameter draw
RUN_RTOL = 1e-12


# --- numerics ------------------------------------------------------------------------------

def taylor(g, r, n=N_CONTOUR):
    """(g(0), g'(0), g''(0)) of an analytic g of complex t from g on the circle |t| = r."""
    t = r * np.exp(2j * np.pi * np.arange(n) / n)
    vals = np.array([np.asarray(g(tk), dtype=complex) for tk in t])
    c = np.fft.fft(vals, axis=0) / n             # c_k = a_k r^k (+ aliasing of order n)
    return c[0], c[1] / r, 2.0 * c[2] / r**2


def _reduced_field(P, x):
    d = np.empty(4, dtype=np.result_type(x, float))
    st = rhs(L.MODEL_REV_REDUCED, 0.0, x, P.p, d)
    if st != L.OK:
        raise FloatingPointError(L.STATUS_TEXT[st])
    return d


# the independent variable of a second-order equation as a function of gamma3, and its
# derivative: theta = arccos(gamma3) ((2.17), (2.33), (3.5)), x = (1 - gamma3)/2 (after (2.17))
_ARG = {"(theta, omega3)": (np.arccos, lambda u: -1.0 / np.sqrt(1.0 - u * u)),
        "(x, omega3)": (lambda u: (1.0 - u) / 2.0, lambda u: -0.5 + 0.0 * u)}


def flow_jet(P, y, V):
    """(s, w, dw/ds, d2w/ds2) along the full flow at y for a disk, w = omega3 = rho0 K2
    (rho0 constant for the disk) and s = arccos(gamma3) or (1 - gamma3)/2.

    The derivatives use the compiled reduced field F (solvers.kernels.reduced: the full
    field pushed forward to (gamma3, K1, K2, K3)): dw/ds = rho0 F_K2 / (s'(gamma3) F_g3) is a
    closed form in x, free of cancellation (numerator and denominator are both
    proportional to K3), and d2w/ds2 = (d/dt dw/ds)/(ds/dt) with d/dt by complex step along
    F, exact. Returns the jet and the relative difference between F(x) and the full field
    pushed forward at y (exact, complex step), so that the check stays tied to the full
    field at every point."""
    b = rd.RevBody.from_params(P.p)
    if b.prof.b1 or b.prof.b3 or b.prof.c:
        raise LookupError("second-order equations in omega3 are implemented for disks "
                          "(rho0 constant)")
    x = rd.to_reduced(P.p, y)
    F = _reduced_field(P, x)
    push = pointwise.directional(lambda yy: rd.to_reduced(P.p, yy), y, full_field(P, y))
    consistency = pointwise.relative_difference(F, push)
    sfun, ds = _ARG[V]
    r0 = rd.rho0(b, 0.5)

    def slope(xx):
        FF = _reduced_field(P, xx)
        return r0 * FF[2] / (ds(xx[0]) * FF[0])

    w1 = slope(x)
    dw1 = pointwise.directional(slope, x, F)
    jet = np.array([sfun(x[0]), r0 * x[2], w1, float(dw1) / (ds(x[0]) * F[0])])
    return jet, consistency


def rate(P, y, V):
    """(to_vars(V), d/dt of its first variable) along the full field, exact."""
    v = full_field(P, y)
    x = np.asarray(to_vars(V, P, y), dtype=float)
    sd = pointwise.directional(lambda yy: to_vars(V, P, yy)[0], y, v)
    return np.array([*x, float(sd)])


def fundamental(f, s0, s_values, rtol=1e-12):
    """Phi(s), Kp(s) at s_values for the affine system dK/ds = f(s, K) in R^2 with
    K(s) = Phi(s) K(s0) + Kp(s), Phi(s0) = E, Kp(s0) = 0 (solve_ivp DOP853, dense output)."""
    s_values = np.asarray(s_values, dtype=float)
    n = 2
    f0 = lambda s: np.asarray(f(s, np.zeros(n)), dtype=float)  # noqa: E731

    def aug(s, Z):
        Kp, Phi = Z[:n], Z[n:].reshape(n, n)
        b = f0(s)
        A = np.stack([np.asarray(f(s, e), dtype=float) - b for e in np.eye(n)], axis=1)
        return np.concatenate([A @ Kp + b, (A @ Phi).ravel()])

    Z0 = np.concatenate([np.zeros(n), np.eye(n).ravel()])
    out = np.empty((len(s_values), n + n * n))
    out[s_values == s0] = Z0
    for side, pick in ((s_values < s0, np.min), (s_values > s0, np.max)):
        if not side.any():
            continue
        sol = solve_ivp(aug, (s0, pick(s_values[side])), Z0, method="DOP853", rtol=rtol,
                        atol=rtol * 1e-2, dense_output=True)
        if not sol.success:
            raise FloatingPointError(f"linear system: {sol.message}")
        out[side] = sol.sol(s_values[side]).T
    return out[:, n:].reshape(-1, n, n), out[:, :n]


def _points(case, claim, seed, n_points=N_POINTS):
    rng = np.random.default_rng(seed)
    for _ in range(N_SETTINGS):
        P = draw(case, claim, rng)
        for y in random_states(P, n_points, rng):
            yield P, y, rng


def _variables(catalogue, fid):
    return catalogue.formula(fid).variables.value


# --- solves_ode ------------------------------------------------------------------------------

def solves_residual(catalogue, case, claim, sol_corrected=False, ode_corrected=False, seed=4):
    """max over random s (from the case's phase points) and random constants of
    |dK/ds - f(s, K)| / max(|dK/ds|, |f|) for the solution `formula` and the ODE `against`."""
    sol = implementation(claim.check_args.formula, sol_corrected)
    ode = implementation(claim.check_args.against, ode_corrected)
    V = _variables(catalogue, claim.check_args.against)
    worst = 0.0
    for P, y, rng in _points(case, claim, seed, n_points=N_POINTS // 5):
        s = float(to_vars(V, P, y)[0])
        c = rng.standard_normal(2)
        r = 1e-2 * (1.0 + abs(s))
        K, dK, _ = taylor(lambda t, P=P, c=c, s=s: sol(P, np.array([s + t, *c])), r)
        f = np.asarray(ode(P, np.array([s, *K])), dtype=complex)
        worst = max(worst, pointwise.relative_difference(dK, f))
    return worst


@check("solves_ode")
def check_solves_ode(catalogue, case, claim):
    sid, oid = claim.check_args.formula, claim.check_args.against
    res = solves_residual(catalogue, case, claim)
    evidence = {"printed solution, printed ODE": res}
    corr = None
    if sid in CORRECTED or oid in CORRECTED:
        combos = [(s, o) for s in (False, sid in CORRECTED) for o in (False, oid in CORRECTED)]
        for s, o in sorted(set(combos)):
            name = (f"{'corrected' if s else 'printed'} solution, "
                    f"{'corrected' if o else 'printed'} ODE")
            evidence[name] = solves_residual(catalogue, case, claim, s, o)
        corr = solves_residual(catalogue, case, claim, sid in CORRECTED, oid in CORRECTED)
    out = pointwise.verdict_of(res, corr if res > TOL else None,
                             what=f"{sid} solves {oid}")
    out.evidence = evidence
    return out


# --- linear_integrals --------------------------------------------------------------------------

def _good_run(P, y0, V):
    """A full run from y0 (compiled DOP853) sampled at N_SAMPLES times, or None if it
    meets a singularity or comes close to gamma3 = +-1 (reduced variables undefined)."""

    t = np.linspace(0.0, T_RUN, N_SAMPLES)
    # generated=False: the general field, compiled once for every case, as the section runs
    # of the other trajectory checks; the parameters drawn here have other structures than
    # the examples the warm-up compiled, and their small kernels would each cost a compile
    run = integrate(P.model.model, P.p, y0, t, method="dop853", rtol=RUN_RTOL, atol=RUN_RTOL,
                    generated=False)
    if not run.success or len(run.t) < len(t):
        return None
    if P.model.model == L.MODEL_FULL and np.max(np.abs(run.y[:, 5])) > 0.97:
        return None
    xs = np.array([np.asarray(to_vars(V, P, y), dtype=float) for y in run.y])
    return xs if np.all(np.isfinite(xs)) else None


def _basis(P, xs, system, solution):
    """Phi, Kp at the samples s_j = xs[:, 0]: from the closed-form solution if given
    (Phi e_i = K(s; e_i) - K(s; 0), Kp = K(s; 0)), else by integrating `system` from s_0."""
    s = xs[:, 0]
    if solution is None:
        return fundamental(lambda ss, K: system(P, np.array([ss, *K])), s[0], s)
    Kp = np.array([solution(P, np.array([sj, 0.0, 0.0])) for sj in s])
    cols = [np.array([solution(P, np.array([sj, *e])) for sj in s]) - Kp for e in np.eye(2)]
    return np.stack(cols, axis=2), Kp


def linear_deviation(catalogue, case, claim, use_corrected=False, use_formula=True, seed=5):
    """max over runs of max_t |K(t) - K_lin(s(t))| / max_t |K(t)| and of the spread of the
    constants c(t) = Phi(s(t))^-1 (K(t) - Kp(s(t))), relative to |c(0)|."""
    args = claim.check_args
    sys_id = args.system
    system = implementation(sys_id, use_corrected and sys_id in CORRECTED)
    V = _variables(catalogue, sys_id)
    solution = None
    if use_formula and args.formula is not None and \
            catalogue.formula(args.formula).role.value == "solution":
        solution = implementation(args.formula, use_corrected and args.formula in CORRECTED)
    rng = np.random.default_rng(seed)
    dev, spread, moved, runs = 0.0, 0.0, 0.0, 0
    for _ in range(N_SETTINGS):
        P = draw(case, claim, rng)
        done = 0
        for y0 in random_states(P, 40, rng):
            xs = _good_run(P, y0, V)
            if xs is None:
                continue
            Phi, Kp = _basis(P, xs, system, solution)
            K = xs[:, 1:3]
            c = np.array([np.linalg.solve(Phi[j], K[j] - Kp[j]) for j in range(len(K))])
            Klin = np.einsum("jab,b->ja", Phi, c[0]) + Kp
            scale = np.max(np.abs(K))
            dev = max(dev, float(np.max(np.abs(K - Klin)) / scale))
            spread = max(spread, float(np.max(np.abs(c - c[0])) / np.max(np.abs(c[0]))))
            moved = max(moved, float(np.ptp(xs[:, 0])))
            done += 1
            runs += 1
            if done == N_RUNS:
                break
    if runs == 0:
        raise LookupError(f"{claim.id}: no full run stayed away from the singular set")
    return dev, {"max |K - K_lin| / max |K|": dev, "spread of c / |c(0)|": spread,
                 "range of the independent variable": moved, "runs": runs}


@check("linear_integrals")
def check_linear_integrals(catalogue, case, claim):
    args = claim.check_args
    dev, ev = linear_deviation(catalogue, case, claim)
    fixable = args.system in CORRECTED or args.formula in CORRECTED
    corr = None
    if dev > TOL and fixable:
        corr = linear_deviation(catalogue, case, claim, use_corrected=True)[0]
        ev["corrected: max |K - K_lin| / max |K|"] = corr
    if args.formula is not None and catalogue.formula(args.formula).role.value == "solution" \
            and args.formula != "linear_superposition":
        # the closed form decides; say what the linear system itself does
        ev[f"{args.system} as printed, integrated"] = linear_deviation(
            catalogue, case, claim, use_formula=False)[0]
        if args.system in CORRECTED:
            ev[f"{args.system} corrected, integrated"] = linear_deviation(
                catalogue, case, claim, use_corrected=True, use_formula=False)[0]
    what = (f"constants of {args.formula or args.system} conserved along full runs "
            f"(K(t) vs the solution of {args.system} at s(t))")
    out = pointwise.verdict_of(dev, corr, what=what)
    if corr is not None and args.formula is None:
        # run.py files a corrected record under check_args.formula only: say it here
        out.message += (f" [correction of {args.system}: "
                        f"{'verified' if corr <= TOL else 'fails'}]")
    out.evidence = ev
    return out


# --- extensions of the pointwise checks ----------------------------------------------------------

def jet_residual(catalogue, case, claim, use_corrected=False, seed=3):
    """Second-order equation: |sum of its terms| / sum |terms| at the flow's jet (and the
    reduced field's agreement with the full field there, whichever is larger)."""
    fid = claim.check_args.formula
    f = implementation(fid, use_corrected)
    V = _variables(catalogue, fid)
    worst = 0.0
    for P, y, _ in _points(case, claim, seed):
        jet, consistency = flow_jet(P, y, V)
        terms = np.asarray(f(P, jet), dtype=float)
        res = abs(terms.sum()) / max(np.abs(terms).sum(), 1e-300)
        worst = max(worst, float(res), consistency)
    return worst


def rate_identity_residual(catalogue, case, claim, use_corrected=False, seed=2):
    fid, other = claim.check_args.formula, claim.check_args.against
    f = implementation(fid, use_corrected)
    g = implementation(other)
    V, W = _variables(catalogue, fid), _variables(catalogue, other)
    worst, note = 0.0, None
    for P, y, _ in _points(case, claim, seed):
        try:
            ref = g(P, to_vars(W, P, y))
        except (IndexError, ValueError, np.linalg.LinAlgError) as e:
            if other != "energy":
                raise
            ref = integral(ENERGY, P.model.model, y, P.p)
            note = (f"formula {other!r} cannot evaluate this model's state ({e}); "
                    "compared with the model's compiled energy (eq1.7) instead")
        worst = max(worst, pointwise.relative_difference(f(P, rate(P, y, V)), ref))
    return worst, note


def _extend(name, applies, handler):
    """Route the claims `applies` selects to `handler`, the others to the check as it was."""
    base = CHECKS[name]

    def dispatch(catalogue, case, claim):
        if applies(catalogue, claim):
            return handler(catalogue, case, claim)
        return base(catalogue, case, claim)

    dispatch.__name__ = f"check_{name}"
    CHECKS[name] = dispatch


def is_jet_claim(catalogue, claim):
    fid = claim.check_args.formula
    return fid is not None and _variables(catalogue, fid) in JET_VARIABLES


def _jet_check(catalogue, case, claim):
    fid = claim.check_args.formula
    res = jet_residual(catalogue, case, claim)
    corr = jet_residual(catalogue, case, claim, True) if res > TOL and fid in CORRECTED \
        else None
    return pointwise.verdict_of(res, corr, what=f"{fid} holds along the full flow "
                              "(jet from the reduced field)")


def _rate_check(catalogue, case, claim):
    fid = claim.check_args.formula
    res, note = rate_identity_residual(catalogue, case, claim)
    corr = None
    if res > TOL and fid in CORRECTED:
        corr = rate_identity_residual(catalogue, case, claim, True)[0]
    out = pointwise.verdict_of(res, corr, what=f"{fid} (with the exact ds/dt) == "
                             f"{claim.check_args.against}")
    if note:
        out.message += f" [{note}]"
    return out


_extend("reduced_agrees", is_jet_claim, _jet_check)
_extend("identity", lambda cat, claim: claim.check_args.formula in RATE_FORMULAS, _rate_check)

