"""Formula-free checks: a property of a table cell tested without any printed formula.

Where the paper's formula for a property is misprinted ((3.14), (3.15)) or
missing, the property itself can still be decided from full runs of the equations of motion.

* `linear_integrals_return`: a body of revolution on a sphere with the gyrostat S = (0, 0, s)
  along its axis keeps two integrals linear in M (Table 2, gyrostat row). The reduced motion
  is then a curve K(gamma3) fixed by the two constants: every quantity linear in M that is
  invariant under rotations about the axis -- A = (M, gamma) and B = M3 span them together
  with the velocity of nutation, which the energy fixes up to sign -- takes the SAME values at
  every crossing of one level gamma3 = c in the same direction. No formula of the paper is
  used: only the full field ((1.1), the sphere's Poisson equation) and these two projections.
  The test must be able to fail: the same check runs a control with S moved off the axis
  (S1, S2 != 0), which breaks the symmetry and with it the integrals; the spread at the
  crossings must then be large. If the control does not break, the check cannot tell and
  says so (unchecked), instead of claiming the property.

Crossings are located by the integrator's section (Henon's trick) on compiled DOP853 runs at
rtol = atol = 1e-12; the measured floor of the spread is <= 1e-10 over T = 150 (a few dozen
nutation periods), so the project-wide TOL applies unchanged.
"""

import numpy as np

from solvers.integrate.integrator import Section, integrate
from solvers.kernels import layout as L
from solvers.verify.checks.common import N_SETTINGS, TOL
from solvers.verify.params import draw, random_states
from solvers.verify.registry import Outcome, check

T_LONG = 150.0          # length of a run
N_PRE = 3001            # samples of the pre-run that picks the level gamma3 = c
MIN_CROSSINGS = 4       # a run must cross its level at least this often
N_RUNS = 2              # runs per parameter draw
CONTROL_BREAKS = 1e3 * TOL   # the control must exceed this spread to count as broken
POLE = 0.97             # the reduced variables are undefined at gamma3 = +-1


def crossing_spread(P, p, y0, T=T_LONG):
    """(spread, crossings) of A = (M, gamma), B = M3 at the upward crossings of the median
    level of gamma3 along a run of the full field with parameters p from y0; None if the
    run is singular, comes near a pole or crosses too rarely."""
    # generated=False: the general field, as the section run below (a drawn structure's
    # small kernel would cost a compile of its own: solvers/verify/checks/ode.py _good_run)
    pre = integrate(P.model.model, p, y0, np.linspace(0.0, T, N_PRE), rtol=1e-12, atol=1e-12,
                    generated=False)
    if not pre.success or len(pre.t) < N_PRE or np.max(np.abs(pre.y[:, 5])) > POLE:
        return None
    level = float(np.median(pre.y[:, 5]))
    run = integrate(P.model.model, p, y0, np.array([0.0, T]), rtol=1e-12, atol=1e-12,
                    section=Section(coef=(0, 0, 0, 0, 0, 1.0), offset=level, direction=1),
                    max_crossings=10_000)
    Y = run.crossings_y
    if not run.success or len(Y) < MIN_CROSSINGS:
        return None
    A = np.einsum("ij,ij->i", Y[:, :3], Y[:, 3:])
    B = Y[:, 2]
    scale = max(np.max(np.abs(A)), np.max(np.abs(B)), 1e-300)
    return float(max(np.ptp(A), np.ptp(B)) / scale), len(Y)


def off_axis(P):
    """The control's parameters: the same body with S moved off the axis of symmetry."""
    p = P.p.copy()
    s = abs(p[L.S3]) or 0.4
    p[L.S1], p[L.S2] = 0.6 * s, -0.3 * s
    return p


def return_spreads(case, claim, seed=17, control=False):
    """max spread over N_SETTINGS draws x N_RUNS runs, total crossings, runs."""
    rng = np.random.default_rng(seed)
    worst, crossings, runs = 0.0, 0, 0
    for _ in range(N_SETTINGS):
        P = draw(case, claim, rng)
        p = off_axis(P) if control else P.p
        done = 0
        for y0 in random_states(P, 40, rng):
            res = crossing_spread(P, p, y0)
            if res is None:
                continue
            worst, crossings = max(worst, res[0]), crossings + res[1]
            done += 1
            if done == N_RUNS:
                break
        runs += done
    if runs == 0:
        raise LookupError(f"{claim.id}: no long run stayed away from the poles")
    return worst, crossings, runs


@check("linear_integrals_return")
def check_linear_integrals_return(catalogue, case, claim):
    spread, n, runs = return_spreads(case, claim)
    c_spread, c_n, c_runs = return_spreads(case, claim, control=True)
    ev = {"max spread of (M, gamma), M3 at crossings / scale": spread,
          "crossings": n, "runs": runs, "run length": T_LONG,
          "control": "the same body with S = (0.6 s, -0.3 s, s), off the axis",
          "control: max spread": c_spread, "control: crossings": c_n, "control: runs": c_runs}
    what = (f"(M, gamma) and M3 return to the same values at {n} crossings of one level of "
            f"gamma3 in {runs} runs of length {T_LONG:g}: spread {spread:.1e}")
    ctl = f"; control with S off the axis: spread {c_spread:.1e}"
    if c_spread <= CONTROL_BREAKS:
        return Outcome("unchecked", spread, what + ctl + ": the control does not break the "
                       "returns, so this test cannot decide here", evidence=ev)
    if spread <= TOL:
        return Outcome("verified", spread, what + f" <= {TOL:g} (two integrals linear in M)"
                       + ctl + " (the test can fail)", evidence=ev)
    return Outcome("fails", spread, what + f" > {TOL:g}: no two integrals linear in M" + ctl,
                   evidence=ev)
