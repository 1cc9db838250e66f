"""What the page /how-we-check says about each kind of check, with the numbers read from
the checking code itself (solvers/verify/checks), so the page cannot drift from the code."""

from __future__ import annotations

from catalogue.schema import CheckName
from solvers.verify.checks import common, formula_free, negative, nonexistence
from solvers.verify.exact import certify as exact_certify
from solvers.verify.exact import points as exact_points
from solvers.verify.marks import verdicts, vocabulary


def constants() -> dict[str, float]:
    """The tolerances and sample sizes the checks use, as the code defines them."""
    return {"TOL": common.TOL, "N_SETTINGS": common.N_SETTINGS, "N_POINTS": common.N_POINTS,
            "H": common.H, "N_POINTS_NEG": negative.N_POINTS_NEG,
            "N_SETTINGS_NEG": negative.N_SETTINGS_NEG, "T_MAP": negative.T_MAP,
            "N_MAP_ORBITS": negative.N_MAP_ORBITS, "MIN_CROSSINGS": negative.MIN_CROSSINGS,
            "T_LONG": negative.T_LONG, "FF_T_LONG": formula_free.T_LONG,
            "FF_N_RUNS": formula_free.N_RUNS, "FF_MIN_CROSSINGS": formula_free.MIN_CROSSINGS,
            "FF_CONTROL_BREAKS": formula_free.CONTROL_BREAKS,
            "EXACT_BITS": exact_points.BITS, "EXACT_K": exact_certify.K_POINTS}


def kinds() -> list[dict]:
    """Each kind of check: the check names it covers, what is computed, where, how strict."""
    c = constants()
    pts = f"{c['N_SETTINGS']} random parameter draws × {c['N_POINTS']} random phase points"
    tol = f"relative residual ≤ {c['TOL']:g}"
    cs = f"complex-step derivatives (step {c['H']:g}i, exact to round-off)"
    return [
        {"id": "integral", "title": "First integrals",
         "checks": [CheckName.INTEGRAL, CheckName.FUNCTIONALLY_DEPENDENT],
         "computed": f"dF/dt = grad F · v, the rate of change of the printed F along the "
                     f"equations of motion v, by {cs}, divided by |grad F|·|v|.",
         "points": pts, "tolerance": tol},
        {"id": "measure", "title": "Invariant measures",
         "checks": [CheckName.MEASURE],
         "computed": f"div(ρ v), the Liouville equation of the printed density ρ, by {cs}, "
                     "relative to the sum of the absolute values of its terms.",
         "points": pts, "tolerance": tol},
        {"id": "bracket", "title": "Poisson brackets and Hamiltonian form",
         "checks": [CheckName.JACOBI, CheckName.CASIMIR, CheckName.BRACKET_RANK,
                    CheckName.HAMILTONIAN_FIELD, CheckName.HAMILTONIAN_FIELD_ON_LEVEL,
                    CheckName.HAMILTONIAN_ATTEMPT, CheckName.SYMMETRY],
         "computed": "the Jacobi identity of the printed bracket, its Casimir functions, its "
                     "rank, and that after the change of time the field equals {x, H}, by exact "
                     "derivatives; where a bracket is shown on one level of an integral only, "
                     "the random states are first moved onto that level. A construction the "
                     "project tried for a Hamiltonian form the paper does not print is "
                     "inconclusive when it fails: a failed attempt decides nothing.",
         "points": pts, "tolerance": tol},
        {"id": "reduced", "title": "Reduced systems and solutions",
         "checks": [CheckName.REDUCED_AGREES, CheckName.IDENTITY, CheckName.SOLVES_ODE,
                    CheckName.LINEAR_INTEGRALS, CheckName.PERMANENT_ROTATIONS],
         "computed": "the printed reduced equations against the full field pushed forward to "
                     "the reduced variables; printed identities and solutions substituted into "
                     "their equations.", "points": pts, "tolerance": tol},
        {"id": "negative", "title": "Negative claims (no measure, no further integral)",
         "checks": [CheckName.MEASURE_FAILS, CheckName.INTEGRAL_FAILS, CheckName.JACOBI_FAILS,
                    CheckName.NEGATIVE_MEASURE, CheckName.NEGATIVE_INTEGRAL],
         "computed": "that the printed object fails where the paper says it does (a residual "
                     f"above {c['TOL']:g}); for 'no measure' an obstruction to any density of "
                     f"the position ({c['N_SETTINGS_NEG']} draws × {c['N_POINTS_NEG']} points) "
                     "and orbits that settle on attractors in runs of "
                     f"{c['T_LONG']:g} time units; for 'no further integral' 3D point maps of "
                     f"up to {c['N_MAP_ORBITS']} orbits over {c['T_MAP']:g} time units "
                     f"(at least {c['MIN_CROSSINGS']} crossings) whose points fill a layer "
                     "instead of a surface. This is evidence, never proof.",
         "points": f"{c['N_SETTINGS_NEG']} draws × {c['N_POINTS_NEG']} points, long runs",
         "tolerance": f"obstruction: residual > {c['TOL']:g}"},
        {"id": "no-measure", "title": "No invariant measure, proved",
         "checks": [CheckName.NO_MEASURE],
         "computed": "for the cases whose field is homogeneous in M (no potential, no "
                     "gyrostat: dM/dt quadratic, the position's rate linear in M), scaling "
                     "M to 0 turns any smooth positive invariant density into one of the "
                     "position alone (Kozlov's argument), which needs c · γ = 0 (c3 = 0 for "
                     "the flat base) where div v = c · ω. The project computes c exactly in "
                     "rational arithmetic (exact first derivatives of the exact field) at a "
                     "rational point and finds it nonzero: a proof, for the example's "
                     "parameters and every parameter value off the zero set of that rational "
                     "function, and for each drawn parameter set. The control that restores "
                     "a known measure gives exactly 0.",
         "points": f"{len(nonexistence.GAMMAS)} rational points, the example and "
                   f"{c['N_SETTINGS']} drawn parameter sets",
         "tolerance": "none: exact rationals, the obstruction is ≠ 0"},
        {"id": "formula-free", "title": "Formula-free existence tests",
         "checks": [CheckName.LINEAR_INTEGRALS_RETURN],
         "computed": "that a property holds without using any printed formula for it: for "
                     "two integrals linear in M (gyrostat along the symmetry axis on a "
                     f"sphere), runs of {c['FF_T_LONG']:g} time units must bring (M, γ) and "
                     "M3 back to the same values at every upward crossing of one level of "
                     f"γ3 (at least {c['FF_MIN_CROSSINGS']} crossings per run). A control run "
                     "with the gyrostat moved off the axis must break this (spread above "
                     f"{c['FF_CONTROL_BREAKS']:g}); if it does not, the test says "
                     "'unchecked' instead of 'verified'.",
         "points": f"{c['N_SETTINGS']} parameter draws × {c['FF_N_RUNS']} runs, plus the "
                   "off-axis control",
         "tolerance": f"spread of the returns ≤ {c['TOL']:g}"},
        {"id": "exact", "title": "Exact certificates and proofs",
         "checks": [],
         "computed": "the residual of a polynomial (or rational) identity, in exact rational "
                     "arithmetic. Proof: with every free coordinate (parameters, γ's angle "
                     "parameters, M) a symbol, the residual is a rational function; its "
                     "numerator expanded over Q is the zero polynomial, so the identity holds "
                     "with certainty. Certificate, where the expansion is too large: the "
                     f"residual at k = {c['EXACT_K']} random rational points, every coordinate "
                     f"(parameters included) uniform over N = 2^{c['EXACT_BITS']} exact grid "
                     "values; a nonzero value proves the identity false; zero at all k points "
                     "means a nonzero numerator of degree ≤ d (tracked through the arithmetic) "
                     "would vanish there with probability at most (d/N)^k (Schwartz–Zippel "
                     "lemma). A record whose degree is not known states no probability. The "
                     "points are seeded by the claim id: reproducible, but not random against "
                     "someone who picks a formula after seeing them.",
         "points": f"a proof, or k = {c['EXACT_K']} points with the bound (d/N)^k, "
                   f"N = 2^{c['EXACT_BITS']}",
         "tolerance": "exactly zero (no floating point)"},
        {"id": "recorded", "title": "Recorded, not computed",
         "checks": [CheckName.OPEN_PROBLEM, CheckName.FORMULA_NOT_PRINTED,
                    CheckName.NOT_CHECKABLE],
         "computed": "nothing: the paper states an open problem, asserts a result without "
                     "printing a formula, or says something a pointwise computation cannot "
                     "decide ('only one integral').", "points": "—", "tolerance": "—"},
    ]


def marks() -> list[dict]:
    """What each mark means: the vocabulary itself (solvers/verify/marks.yaml), which
    solvers/verify/levels.py assigns and every page draws; one source of truth."""
    return [m.model_dump() for m in vocabulary()]


# the coarse `verdict` every record also keeps (for compatibility); the mark says which:
# (verdict, sign, meaning), from the vocabulary (solvers/verify/marks.yaml)
VERDICTS = [(v.id, v.shape, v.meaning) for v in verdicts()]
