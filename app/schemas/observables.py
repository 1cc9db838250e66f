"""Request and response of POST /api/observables: named quantities (the rubber constraint,
|gamma| - 1, a rubber case's integrals beyond the energy) along the states of a run, from
solvers/models/observables.py, so that a page plots them under the one name each has."""

from typing import Annotated

from pydantic import BaseModel, ConfigDict, Field

from app.schemas.common import FiniteFloat
from app.schemas.simulate import CaseId

# rows of (M, gamma) a request carries: within the server's body limit (1 MB) at full
# precision; a page sends every k-th row of a longer run
MAX_ROWS = 4000

Row = Annotated[list[FiniteFloat], Field(min_length=6, max_length=6)]


class ObservablesRequest(BaseModel):
    # strict: a string "1.5" or false for 0 is a mistake to report, not to guess around
    model_config = ConfigDict(extra="forbid", strict=True)
    case: CaseId
    params: dict[str, FiniteFloat] = Field(description="the run's parameters (as given to "
                                           "POST /api/simulate; the case's example fills "
                                           "the rest)")
    state: list[Row] = Field(min_length=1, max_length=MAX_ROWS, description="rows "
                             "(M1, M2, M3, g1, g2, g3) of the run")
    names: list[str] | None = Field(None, description="the quantities (default: the "
                                    "constraint, |gamma| - 1 and the case's integrals)")


class ObservablesResponse(BaseModel):
    case: str
    names: list[str]
    labels: dict[str, str] = Field(description="name -> what a reader calls it")
    series: dict[str, list[float | None]] = Field(description="name -> one value per row "
                                                  "(null where the state is singular)")
