"""Request and response of POST /api/simulate (and /api/scene, /api/validate)."""

from typing import Annotated, Any, Literal

from pydantic import BaseModel, ConfigDict, Field

# the bounds of t_end, samples and the tolerances, one definition with the command line's
# (MAX_SAMPLES and T_END_MIN are imported from here too)
from app.schemas.bounds import (  # noqa: F401
    MAX_SAMPLES,
    T_END_MIN,
    Atol,
    Int,
    Rtol,
    Samples,
    Step,
    TEnd,
)
from app.schemas.common import FiniteFloat
from solvers.models.bodies import param_bounds, param_upper_bounds
from solvers.models.cases import case_ids, registry

try:
    from solvers.simulate import methods

    METHODS = tuple(methods())
except ImportError:  # the compiled integrator is missing: list what the API promises
    METHODS = ("dop853", "vern9", "rk45", "gauss4", "gauss6", "gauss8", "taylor", "auto",
               "scipy-dop853", "scipy-rk45", "scipy-lsoda", "scipy-radau")

MAX_FRAMES = 600
CASE_IDS = tuple(case_ids())
CaseId = Literal[CASE_IDS]  # type: ignore[valid-type]
Method = Literal[METHODS]  # type: ignore[valid-type]

EXAMPLE = {"case": "plane/chaplygin-ball",
           "params": {"I1": 1, "I2": 2, "I3": 3, "m": 1, "R": 1},
           "state": [0.5, -0.3, 0.8, 0.3, 0.4, 0.8660254037844386],
           "t_end": 100, "method": "dop853", "rtol": 1e-10, "atol": 1e-12, "samples": 201}


# the methods by what they take besides rtol and atol (solvers/simulate.py checks the same):
# a Gauss method a `step` and no projection (it is symmetric: it holds the integrals without
# one), taylor a `precision` and no projection, a scipy method neither (projection happens
# inside a compiled step), the compiled adaptive ones (and auto, and no method: dop853) a
# projection but no precision
GAUSS = [m for m in METHODS if m.startswith("gauss")]
SCIPY = [m for m in METHODS if m.startswith("scipy-")]
ADAPTIVE = [m for m in METHODS if m not in GAUSS and m not in SCIPY and m != "taylor"]
# the rules between fields, in the schema (JSON Schema 2020-12, as OpenAPI 3.1 has it), so
# that a request valid by the schema is not refused for them: what each method takes (above);
# without example = true, params and state are required; each case's parameter names and
# their bounds (also in GET /api/cases/{id}: runnable.params). The rules between numbers
# (I1 = I2, the triangle inequality, |gamma| = 1, the step budget) JSON Schema cannot say:
# those stay refusals of validation alone (tests/test_schema_valid_accepted.py lists them).
METHOD_RULES = {"anyOf": [
    {"required": ["method", "step"],
     "properties": {"method": {"enum": GAUSS}, "step": {"type": "number"},
                    "project": {"const": False}, "precision": {"type": "null"}}},
    {"required": ["method"],
     "properties": {"method": {"const": "taylor"}, "step": {"type": "null"},
                    "project": {"const": False}}},
    {"required": ["method"],
     "properties": {"method": {"enum": SCIPY}, "step": {"type": "null"},
                    "project": {"const": False}, "precision": {"type": "null"}}},
    {"properties": {"method": {"enum": ADAPTIVE}, "step": {"type": "null"},
                    "precision": {"type": "null"}}},
]}


def param_schema(kind: str, symmetry: str) -> dict[str, dict]:
    """The bounds of a body's parameters as JSON Schema, from the tables that the
    model's validation checks (solvers.models.bodies.param_bounds, param_upper_bounds):
    exclusiveMinimum 0 for a positive parameter, minimum 0 for a non-negative one,
    exclusiveMaximum 0 for a negative one."""
    out = {name: ({"type": "number", "minimum": b["min"]} if b["min_inclusive"]
                  else {"type": "number", "exclusiveMinimum": b["min"]})
           for name, b in param_bounds(kind, symmetry).items()}
    for name, b in param_upper_bounds(kind).items():
        out.setdefault(name, {"type": "number"})[
            "maximum" if b["max_inclusive"] else "exclusiveMaximum"] = b["max"]
    return out


def case_rules(with_state: bool = True) -> dict:
    """Per case, what JSON Schema can say of its inputs (the names of solvers.models.cases):
    the parameter names it takes, their lower bounds (param_schema), the ones it requires
    unless example = true, and the length of its state (5 for the flat-base cases, 6 for the
    others), required too unless example = true (with_state).

    Two branches a case (with example = true, or without it), not an if/then a case: the
    schema's generators expand each if/then into two, and 17 of them into 2^17. The branches
    exclude each other (by case and by example), so they are a oneOf: schemathesis's
    canonical form multiplies an anyOf beside another anyOf (METHOD_RULES) out into one list
    of every pair and gives up past a budget, where it leaves a oneOf standing and meets its
    branches one at a time while drawing."""
    branches = []
    for cid, c in registry().items():
        props: dict[str, Any] = {"case": {"const": cid},
                                 "params": {"propertyNames": {"enum": c.param_names},
                                            "properties": param_schema(c.body, c.symmetry)}}
        if with_state:
            n = len(c.state)
            props["state"] = {"minItems": n, "maxItems": n}
        branches.append({"required": ["example"],
                         "properties": {**props, "example": {"const": True}}})
        without_example = {**props, "example": {"const": False},
                           "params": {**props["params"], "required": list(c.required)}}
        if with_state:
            without_example["state"] = {**props["state"], "type": "array"}
        branches.append({"required": ["params", "state"] if with_state else ["params"],
                         "properties": without_example})
    return {"oneOf": branches}


CROSS_FIELD_RULES = [METHOD_RULES, case_rules()]


class SimulateRequest(BaseModel):
    """A run, as `rolling simulate`: the case, its named parameters, the initial state
    (M, gamma) or (M, r1, r2) and the final time. Rules between fields: `step` is given
    with the Gauss methods (gauss4/6/8) and only with them; `precision` only with method
    taylor; `project` = true only with the compiled adaptive methods and auto (GET
    /api/methods); `params` and `state` are required unless `example` is true; the
    parameter names are the case's own (GET /api/cases/{id}: runnable.params)."""

    # strict: a string "1.5" or 0 for false is a mistake to report, not to guess around
    model_config = ConfigDict(extra="forbid", strict=True,
                              json_schema_extra={"examples": [EXAMPLE],
                                                 "allOf": CROSS_FIELD_RULES})

    case: CaseId = Field(description="case id, e.g. plane/chaplygin-ball (GET /api/cases)")
    params: Annotated[dict[Annotated[str, Field(max_length=16)], FiniteFloat],
                      Field(max_length=32)] = Field(
        default_factory=dict, description="named parameters (GET /api/cases/{id}: "
        "runnable.params); with example = true, the case's demo values fill the rest")
    state: Annotated[list[FiniteFloat], Field(min_length=5, max_length=6)] | None = Field(
        None, description="initial state: M1 M2 M3 g1 g2 g3 (|g| = 1), or M1 M2 M3 r1 r2 "
        "for the flat-base cases; null with example = true: the case's demo state")
    t_end: TEnd = Field(description="final time")
    method: Method = Field("dop853", description="integrator (GET /api/methods)")
    rtol: Rtol = 1e-10
    atol: Atol = 1e-12
    step: Step | None = Field(None, description="the constant step of a symmetric method "
                              "(gauss4/6/8; required there, refused elsewhere: the others "
                              "choose theirs)")
    precision: Literal["double", "long double", "quad"] | None = Field(
        None, description="method taylor only: the floating-point type of the Taylor "
        "integrator; null: chosen from rtol and t_end (results are float64 either way)")
    samples: Samples = Field(201, description="output times, evenly spaced on [0, t_end]")
    project: bool = Field(False, description="project onto the known integrals after "
                          "every step (compiled methods only)")
    allow_any_inertia: bool = Field(False, description="accept moments that violate the "
                                    "triangle inequality")
    example: bool = Field(False, description="start from the case's demo parameters and "
                          "state; given params / state override them")
    field: Literal["auto", "general"] = Field(
        "auto", description="vector field of the compiled Runge-Kutta methods: auto, the "
        "case's generated field (solvers/kernels/generate.py) in its small kernel for a "
        "plain run (dop853 or vern9, no projection), else the general one, whatever is "
        "compiled (the same request gives the same numbers); general, the general "
        "support-function field (the reference). stats.field and stats.kernel say which "
        "ran")


class SceneRequest(SimulateRequest):
    """A run for the 3D animation: the body's orientation and contact path at `frames`
    evenly spaced times (solvers.models.kinematics)."""

    model_config = ConfigDict(extra="forbid", strict=True)
    # the schema says a scene's only field; "general" is refused with the reason
    field: Literal["auto", "general"] = Field(
        "auto", description="a scene runs the default field (auto); field applies to "
        "/api/simulate", json_schema_extra={"enum": ["auto"]})
    frames: Int = Field(200, ge=2, le=MAX_FRAMES)


class RunProvenance(BaseModel):
    """Where the run's data came from (app/services/provenance.py)."""
    case: str
    inputs: dict[str, Any] = Field(description="the inputs that decide the numbers: case, "
                                   "params (every one, defaults filled in), state, t_end, "
                                   "samples, method, rtol, atol, step, project, precision, "
                                   "field, allow_any_inertia")
    version: str = Field(description="the package version that ran it")
    hash: str = Field(description="the first 8 hex digits of the SHA-256 of the inputs as "
                      "canonical JSON (sorted keys, no spaces)")
    file_stem: str = Field(description="the download's file name without extension: case, "
                           "t_end and hash, e.g. plane_chaplygin-ball_t100_3f2a9c1b")
    permalink: str = Field(description="the case page's address that runs it again")
    computed_at: str | None = Field(description="when the run finished, UTC (ISO 8601)")
    header: list[str] = Field(description="the CSV's commented header, one '# ' line each")


class SimulateResponse(BaseModel):
    case: str
    params: dict[str, float]
    status: Literal["ok", "singular", "budget"] = Field(
        description="ok; singular: stopped at a singularity (message says where); budget: "
        "the step budget was used up (the samples before it are returned)")
    message: str
    state_labels: list[str]
    t: list[float]
    state: list[list[float]] = Field(description="one row per sample, columns state_labels")
    invariants: dict[str, list[float | None]] = Field(
        description="name -> values aligned with t ('energy' always). The names are the "
        "same in the CSV's and the Arrow stream's columns: gamma_squared is |gamma|^2, "
        "M_squared is |M|^2 (M2 is only ever the state's component), M_plus_S_squared is "
        "|M + S|^2; the glossary (/glossary) says what each one is")
    stats: dict[str, Any] = Field(description="steps, rejected, rhs_calls, wall_s, method, "
                                  "rtol, atol, projected, samples, drift (max relative "
                                  "drift of every invariant), max_steps; taylor: "
                                  "precision, taylor_order, compiled (this run compiled "
                                  "its integrator: compile_s), integrator_cache (memory, "
                                  "disk or null), load_s; auto: the method chosen, why and "
                                  "the front point, compiled_runs")
    provenance: RunProvenance | None = None


class ValidatePublic(BaseModel):
    ok: bool
    params: dict[str, float] = Field(description="the parameters the run would use, "
                                     "defaults filled in")
    state_labels: list[str]
    invariants: list[str] = Field(description="integrals the run will report")
    invariants_text: list[str] = Field(default_factory=list, description="the same "
                                       "integrals as a reader names them, e.g. 'energy H'")


class ScenePublic(BaseModel):
    case: str
    surface: str
    body: str
    k: float
    support_radius: float | None
    support_inside_body: bool
    t: list[float]
    Q: list[list[float]] = Field(description="rotation body -> space per frame, row-major")
    x_G: list[list[float]]
    contact: list[list[float]]
    mesh: dict[str, Any]
    status: str
    message: str
    stats: dict[str, Any]
    checks: dict[str, float]
    series: dict[str, list[float]] = Field(
        default_factory=dict, description="per frame: vertical_spin -(omega, gamma) and tilt "
        "sqrt(g1^2 + g2^2) (sine of the angle of the body's e3 axis to the vertical); "
        "bodies with the state (M, gamma) only")


class MethodPublic(BaseModel):
    name: str
    kind: str


class CompilesPublic(BaseModel):
    compiles: bool = Field(description="true: the run compiles its kernels first (first use "
                           "on this machine, or the background warm-up has not reached "
                           "them); the compile happens before the run's deadline starts")
    estimate_s: float = Field(description="seconds one case structure's kernels took to "
                              "compile on this machine (a default before the first)")
