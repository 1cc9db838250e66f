"""The bounds of the numbers that size a run, defined once: the API's request models
(app/schemas/simulate.py, poincare.py) declare their fields with these types, so the
OpenAPI schema says them, and the command line (app/cli) checks its options by them with
app.core.errors.refusal, in the API's words, before it imports the solvers (a refusal
costs the imports of pydantic and FastAPI, not the compiled kernels')."""

from typing import Annotated

from pydantic import BaseModel, BeforeValidator, Field

from app.schemas.common import FiniteFloat

MAX_SAMPLES = 20_000
# the smallest final time: from it up, the output times linspace(0, t_end, samples) are
# distinct for every number of samples accepted (a smaller one, such as 5e-324, cannot
# hold two); the largest, the bound of one request's work
T_END_MIN = 1e-300
T_END_MAX = 1e7


def _integral(v):
    """JSON Schema's integer includes 201.0; the strict models take it as 201 (a number
    with a fraction, a string or a boolean stays refused)."""
    return int(v) if isinstance(v, float) and v.is_integer() else v


# an integer as the OpenAPI schema says it: a number without a fraction (the bounds go
# before the validator, so that the schema shows them as minimum and maximum)
Int = Annotated[int, BeforeValidator(_integral)]

TEnd = Annotated[FiniteFloat, Field(ge=T_END_MIN, le=T_END_MAX)]
Samples = Annotated[int, Field(ge=2, le=MAX_SAMPLES), BeforeValidator(_integral)]
Rtol = Annotated[FiniteFloat, Field(ge=1e-16, le=0.1)]
Atol = Annotated[FiniteFloat, Field(gt=0, le=1.0)]
Step = Annotated[FiniteFloat, Field(gt=0, le=1e3)]
# the map's tolerances are tighter: a crossing is located to rtol
MapRtol = Annotated[FiniteFloat, Field(ge=1e-14, le=1e-3)]
# an int in [-1, 1] rather than Literal[-1, 0, 1]: a Literal accepts false for 0
Direction = Annotated[int, Field(ge=-1, le=1), BeforeValidator(_integral)]


class SimulateBounds(BaseModel):
    """The options of `rolling simulate` that SimulateRequest bounds, by its types."""

    t_end: TEnd
    samples: Samples
    rtol: Rtol
    atol: Atol
    step: Step | None = None


class PoincareBounds(BaseModel):
    """The options of `rolling poincare` that PoincareRequest bounds, by its types (a
    level whose starts overflow is refused later, by the map's own check)."""

    energy: FiniteFloat
    direction: Direction
    rtol: MapRtol
    atol: Atol
