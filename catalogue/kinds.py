"""The catalogue's vocabularies: supports, bodies, table rows, shades, claim kinds, check
names, origins, state variables, formula roles, potentials, gyrostats and inertia
restrictions (catalogue/schema.py builds the models on them), and `Strict`, the base of
every catalogue model.
"""

from __future__ import annotations

from enum import StrEnum

from pydantic import BaseModel, ConfigDict


class Strict(BaseModel):
    """Base of every catalogue model: unknown keys are errors, loaded data is read-only."""

    model_config = ConfigDict(extra="forbid", frozen=True, populate_by_name=True)


class Support(StrEnum):
    PLANE = "plane"
    SPHERE = "sphere"


class Body(StrEnum):
    BALL = "ball"
    ELLIPSOID = "ellipsoid"
    BODY_OF_REVOLUTION = "body-of-revolution"
    ROUND_DISK = "round-disk"
    FLAT_BASE = "flat-base"
    ARBITRARY = "arbitrary"


class RowKey(StrEnum):
    """Rows of Tables 1 and 2 (Table 2 has no `authors` row)."""

    TENSOR_OF_INERTIA = "tensor_of_inertia"
    SURFACE = "surface"
    RESTRICTIONS = "restrictions"
    MEASURE = "measure"
    INTEGRALS = "integrals"
    GYROSTAT = "gyrostat"
    HAMILTONIAN_FORM = "hamiltonian_form"
    AUTHORS = "authors"
    GENERALIZATIONS = "generalizations"


# Rows that describe the case rather than an invariant: the paper's gray never applies.
DESCRIPTIVE_ROWS = frozenset(
    {RowKey.TENSOR_OF_INERTIA, RowKey.SURFACE, RowKey.RESTRICTIONS, RowKey.AUTHORS}
)


class Shade(StrEnum):
    """The paper's shading (remark under each table): gray where the invariant exists,
    partial fill where the set of integrals is incomplete."""

    FULL = "full"
    PARTIAL = "partial"
    NONE = "none"


class ClaimKind(StrEnum):
    MEASURE = "measure"
    INTEGRAL = "integral"
    POISSON = "poisson"
    GYROSTAT = "gyrostat"
    BRUN = "brun"
    REDUCTION = "reduction"
    HAMILTONIAN_AFTER_TIME_CHANGE = "hamiltonian-after-time-change"
    NEGATIVE = "negative"
    IDENTITY = "identity"  # two printed expressions are equal (alternative forms, definitions)
    STATIONARY = "stationary"  # families of permanent rotations ((2.40), (2.42))


class CheckName(StrEnum):
    """Names of the check functions the solver side registers (one per name)."""

    INTEGRAL = "integral"  # dF/dt = grad F . v = 0 at random phase points
    MEASURE = "measure"  # div(rho v) = 0 at random phase points
    IDENTITY = "identity"  # printed expression == `against` (or its own second form)
    REDUCED_AGREES = "reduced_agrees"  # printed (reduced) system == full field pushed forward
    SOLVES_ODE = "solves_ode"  # printed solution satisfies the printed ODE `against`
    LINEAR_INTEGRALS = "linear_integrals"  # integrals from the fundamental matrix of `system`
    SYMMETRY = "symmetry"  # the field commutes with the printed symmetry field
    JACOBI = "jacobi"  # the printed bracket satisfies the Jacobi identity
    CASIMIR = "casimir"  # the listed functions are Casimirs of the bracket
    BRACKET_RANK = "bracket_rank"  # rank of the bracket (number of Casimirs)
    HAMILTONIAN_FIELD = "hamiltonian_field"  # after d tau = N dt the field is {x, H}
    # the same on the zero level of the integral `against` only
    HAMILTONIAN_FIELD_ON_LEVEL = "hamiltonian_field_on_level"
    # a construction tried for an unprinted Hamiltonian form: Jacobi + flow everywhere;
    # unchecked (inconclusive) when it fails: a failed attempt decides nothing
    HAMILTONIAN_ATTEMPT = "hamiltonian_attempt"
    FUNCTIONALLY_DEPENDENT = "functionally_dependent"  # dF ^ dG ^ ... = 0
    PERMANENT_ROTATIONS = "permanent_rotations"  # dimension of the family of rotations
    # negative statements: each expects a failure or collects evidence of absence
    MEASURE_FAILS = "measure_fails"  # the printed density is NOT invariant here
    INTEGRAL_FAILS = "integral_fails"  # the printed integral is NOT conserved here
    JACOBI_FAILS = "jacobi_fails"  # the printed tensor does NOT satisfy Jacobi
    NEGATIVE_MEASURE = "negative_measure"  # evidence of no smooth measure (attractors, ...)
    NEGATIVE_INTEGRAL = "negative_integral"  # evidence of no further integral (3D maps)
    NO_MEASURE = "no_measure"  # proof of no smooth measure: exact obstruction at a rest point
    # formula-free: a property tested without any printed formula
    LINEAR_INTEGRALS_RETURN = "linear_integrals_return"  # two integrals linear in M: (M, gamma)
    # and M3 return to the same values at every crossing of one level of gamma3
    # nothing to compute; recorded so the catalogue lists them
    OPEN_PROBLEM = "open_problem"  # the paper says it is unknown
    FORMULA_NOT_PRINTED = "formula_not_printed"  # asserted, but the paper prints no formula
    NOT_CHECKABLE = "not_checkable"  # asserted, not decidable pointwise ("only one", ...)


NEGATIVE_CHECKS = frozenset(
    {
        CheckName.MEASURE_FAILS,
        CheckName.INTEGRAL_FAILS,
        CheckName.JACOBI_FAILS,
        CheckName.NEGATIVE_MEASURE,
        CheckName.NEGATIVE_INTEGRAL,
        CheckName.NO_MEASURE,
    }
)

# Arguments each check needs in `check_args`.
REQUIRED_ARGS: dict[CheckName, tuple[str, ...]] = {
    CheckName.INTEGRAL: ("formula",),
    CheckName.MEASURE: ("formula",),
    CheckName.IDENTITY: ("formula",),
    CheckName.REDUCED_AGREES: ("formula",),
    CheckName.SOLVES_ODE: ("formula", "against"),
    CheckName.LINEAR_INTEGRALS: ("system",),
    CheckName.SYMMETRY: ("formula",),
    CheckName.JACOBI: ("bracket",),
    CheckName.CASIMIR: ("bracket", "casimirs"),
    CheckName.BRACKET_RANK: ("bracket", "rank"),
    CheckName.HAMILTONIAN_FIELD: ("bracket", "hamiltonian"),
    CheckName.HAMILTONIAN_FIELD_ON_LEVEL: ("bracket", "hamiltonian", "multiplier", "against"),
    CheckName.HAMILTONIAN_ATTEMPT: ("bracket", "hamiltonian", "multiplier"),
    CheckName.FUNCTIONALLY_DEPENDENT: ("formula", "against"),
    CheckName.PERMANENT_ROTATIONS: ("formula",),
    CheckName.MEASURE_FAILS: ("formula",),
    CheckName.INTEGRAL_FAILS: ("formula",),
    CheckName.JACOBI_FAILS: ("bracket",),
    CheckName.NEGATIVE_MEASURE: (),
    CheckName.NEGATIVE_INTEGRAL: (),
    CheckName.NO_MEASURE: (),
    CheckName.LINEAR_INTEGRALS_RETURN: (),
    CheckName.OPEN_PROBLEM: (),
    CheckName.FORMULA_NOT_PRINTED: (),
    CheckName.NOT_CHECKABLE: (),
}


# The role the formula named by a check argument must have (formulas.yaml `role`).
ARG_ROLES: dict[str, str] = {
    "system": "system",
    "bracket": "bracket",
    "hamiltonian": "hamiltonian",
    "multiplier": "time-change",
    "potential": "potential",
}
FORMULA_ROLE_OF_CHECK: dict[CheckName, tuple[str, ...]] = {
    CheckName.INTEGRAL: ("integral",),
    CheckName.INTEGRAL_FAILS: ("integral",),
    CheckName.MEASURE: ("density",),
    CheckName.MEASURE_FAILS: ("density",),
    CheckName.REDUCED_AGREES: ("system",),
    CheckName.SOLVES_ODE: ("solution",),
    CheckName.FUNCTIONALLY_DEPENDENT: ("integral",),
    CheckName.PERMANENT_ROTATIONS: ("condition",),
    CheckName.SYMMETRY: ("definition",),
}


class Origin(StrEnum):
    """Whose statement a claim or formula records."""

    PAPER = "paper"
    PROJECT = "project"  # the paper asserts the property but prints no formula: the formula
    #                      and its check are the project's (e.g. hamiltonian_sphere.py)


class StateVariables(StrEnum):
    """Variables a claim or formula is written in (the phase space of the check)."""

    M_GAMMA = "(M, gamma)"
    OMEGA_GAMMA = "(omega, gamma)"
    K_GAMMA = "(K, gamma)"  # K = rho M, (2.27)
    M_R = "(M, r1, r2)"  # flat base on a sphere, (3.16)-(3.17)
    OMEGA_R = "(omega, r1, r2)"
    GAMMA3_K1_K2_K3 = "(gamma3, K1, K2, K3)"  # (2.6)
    GAMMA3_K1_K2 = "(gamma3, K1, K2)"  # linear systems (2.13), (3.4), ...
    THETA_K1_K2 = "(theta, K1, K2)"  # (2.16)
    THETA_OMEGA3 = "(theta, omega3)"  # (2.17), (3.5)
    X_OMEGA3 = "(x, omega3)"  # hypergeometric form
    U_K1_K2 = "(u, K1, K2)"  # (3.22)
    U_K1_K2_K3 = "(u, K1, K2, K3)"  # flat base reduced to 4 variables (hamiltonian_sphere.py)
    GAMMA = "(gamma)"  # shape of the body
    GAMMA3 = "(gamma3)"  # meridian of a body of revolution
    PARAMETERS = "(parameters)"  # conditions on parameters only


class FormulaRole(StrEnum):
    SYSTEM = "system"  # equations of motion (full, rewritten or reduced)
    DENSITY = "density"  # density of an invariant measure
    INTEGRAL = "integral"  # a first integral
    BRACKET = "bracket"  # a Poisson bracket or antisymmetric tensor
    HAMILTONIAN = "hamiltonian"  # energy written in particular variables
    DEFINITION = "definition"  # variables, shape functions, constants
    POTENTIAL = "potential"
    TIME_CHANGE = "time-change"
    SOLUTION = "solution"  # explicit solution of a printed ODE
    CONDITION = "condition"  # a restriction on parameters or shape
    IDENTITY = "identity"  # a printed equality between expressions


class Potential(StrEnum):
    NONE = "none"  # U = 0
    GRAVITY = "gravity"  # U = m g (r, gamma)
    BRUN = "brun"  # U = eps/2 (I gamma, gamma)
    AXISYMMETRIC = "axisymmetric"  # arbitrary U(gamma3)
    ANY = "any"  # arbitrary U(gamma)


class Gyrostat(StrEnum):
    ZERO = "zero"
    AXIAL = "axial"  # S = (0, 0, s) along the axis of dynamical symmetry
    ANY = "any"  # arbitrary constant S


class InertiaRestriction(StrEnum):
    ANY = "any"
    NONSYMMETRIC = "I1!=I2!=I3!=I1"
    AXIAL = "I1=I2"
    AXIAL_I1_GT_I3 = "I1=I2, I1>I3"
    AXIAL_I1_LT_I3 = "I1=I2, I1<I3"
    AXIAL_I1_NE_I3 = "I1=I2!=I3"
    AXIAL_I3_2I1 = "I1=I2, I3=2*I1"
    SPHERICAL = "I1=I2=I3"
    ELLIPSOID_FAMILY = "I=mu*E+lambda*m*B"  # (2.40)
    FLAT_PLATE = "I3=I1+I2"
    WORONETZ = "I1=I2=I3/2"


# --- the tables beyond the 2002 paper (rubber_plane.yaml, rubber_sphere.yaml) -------------


class BeyondRowKey(StrEnum):
    """Rows of the tables beyond the paper: the invariant rows of Tables 1 and 2 (same keys
    as RowKey), the Brun field that Table 1 lists among its generalizations, and
    integrability, which Tables 1 and 2 show by their shading."""

    MEASURE = "measure"
    INTEGRALS = "integrals"
    GYROSTAT = "gyrostat"
    BRUN = "brun"
    HAMILTONIAN_FORM = "hamiltonian_form"
    INTEGRABILITY = "integrability"


class Access(StrEnum):
    """How much of a source was read for a claim: its text, part of it (a first page, the
    contents), only its abstract, nothing; or the claim is the project's own."""

    TEXT_READ = "text-read"
    PARTIAL = "partial"
    ABSTRACT_ONLY = "abstract-only"
    NOT_REACHED = "not-reached"
    DERIVED = "derived-here"


class Agreement(StrEnum):
    """How a check of the project's relates to what a source states."""

    CONFIRMED = "confirmed"  # our check shows what the source states
    CONSISTENT = "consistent"  # agrees under a stated reading or convention
    CONTRADICTED = "contradicted"  # our check disagrees, with the evidence
    UNCHECKED = "unchecked"
    NOT_APPLICABLE = "n/a"  # a derived-here claim


class CheckLevel(StrEnum):
    """What backs a cell's mark: a symbolic identity or exact exclusion (sympy), a residual
    at round-off at random points, or numerical evidence (a run, a floating-point search)."""

    EXACT = "exact"
    POINTWISE = "pointwise"
    NUMERICAL = "numerical"


# The marks a cell beyond the paper may carry: ids of the one vocabulary of marks
# (solvers/verify/marks.yaml; tests/test_rubber_tables.py keeps them in it).
BEYOND_MARKS = ("project-formula", "evidence-for", "evidence-against", "fails",
                "inconclusive", "not-checkable")
