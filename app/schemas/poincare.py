"""Request and response of POST /api/poincare (the 3D point map, as `rolling poincare`)."""

import math
from typing import Annotated, Any, Literal

from pydantic import BaseModel, ConfigDict, Field, field_validator

from app.schemas.bounds import Atol, Direction, Int, MapRtol
from app.schemas.common import FiniteFloat
from app.schemas.simulate import CaseId, case_rules
from solvers.models.cases import registry


def _map_cases() -> list[str]:
    """The cases with the state (M, gamma): the flat-base ones (M, r1, r2) have no map, nor
    the rubber ones (solvers.maps.map_spec.map_model: starts off (omega, gamma) = 0)."""
    return [cid for cid, c in registry().items()
            if len(c.state) == 6 and c.constraint == "marble"]

MAX_TRAJECTORIES = 32
MAX_POINTS = 5000
# g = a decimal number (the grammar of a JSON number, with an optional sign)
SECTION = r"^\s*g\s*=\s*[-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?\s*$"

EXAMPLE = {"case": "plane/chaplygin-ball", "params": {"I1": 1, "I2": 2, "I3": 3, "m": 1, "R": 1},
           "energy": 1.0, "section": "g=0", "trajectories": 4, "points": 200}


class PoincareRequest(BaseModel):
    """The map of `rolling poincare CASE --set ... --energy E0 --section g=G0
    --trajectories N --points P`: at energy E0, the crossings of the section g = g0 in
    Andoyer-Deprit variables, as points (L/G, H/G, l)."""

    model_config = ConfigDict(extra="forbid", strict=True,
                              json_schema_extra={"examples": [EXAMPLE],
                                                 "allOf": [case_rules(with_state=False)]})

    # the schema lists the cases that have a map; the others are refused with the reason
    case: CaseId = Field(description="a case with state (M, gamma) (not the flat-base ones)",
                         json_schema_extra={"enum": _map_cases()})
    params: Annotated[dict[Annotated[str, Field(max_length=16)], FiniteFloat],
                      Field(max_length=32)] = Field(default_factory=dict)
    example: bool = Field(False, description="start from the case's demo parameters")
    energy: FiniteFloat = Field(1.0, description="energy level E0")
    section: str = Field("g=0", max_length=40, pattern=SECTION,
                         description="the section g=g0 (radians)")
    direction: Direction = Field(1, description="+1: g increasing, -1: decreasing, "
                                 "0: both")
    trajectories: Int = Field(8, ge=1, le=MAX_TRAJECTORIES, description="sampled starts")
    points: Int = Field(200, ge=1, le=MAX_POINTS, description="crossings per trajectory")
    initial: Annotated[list[Annotated[list[FiniteFloat], Field(min_length=3, max_length=3)]],
                       Field(min_length=1, max_length=MAX_TRAJECTORIES)] | None = Field(
        None, description="starts (L/G, H/G, l) on the section; replace sampling")
    seed: Int = Field(0, ge=0, le=2**32 - 1, description="seed of the sampled starts")
    method: Literal["dop853", "vern9", "rk45"] = "dop853"
    rtol: MapRtol = 1e-10
    atol: Atol = 1e-12
    allow_any_inertia: bool = False

    @field_validator("section")
    @classmethod
    def _section_angle(cls, v: str) -> str:
        # the pattern admits only numbers; one so large that it is infinite is refused here
        if not math.isfinite(float(v.split("=", 1)[1])):
            raise ValueError("the angle g0 must be a finite number of radians")
        return v

    @property
    def g0(self) -> float:
        return float(self.section.split("=", 1)[1])


class TrajectoryPublic(BaseModel):
    initial: list[float] = Field(description="(L/G, H/G, l) of the start, on the section")
    state0: list[float] = Field(description="the start (M, gamma)")
    points: list[list[float]] = Field(description="one row (L/G, H/G, l) per crossing")
    t: list[float] = Field(description="crossing times")
    status: str = Field(description="ok | singular | budget | no-return")
    message: str
    check: dict[str, Any] = Field(description="missed-crossing check: kernel and dense "
                                  "counts, missed, extra, unresolved_intervals")
    spread: dict[str, float] = Field(description="(max-min)/|mean| of each integral over "
                                     "the crossings; absolute spread of H/G")
    steps: int
    rhs_calls: int


class PoincarePublic(BaseModel):
    case: str
    params: dict[str, float]
    energy: float
    section: dict[str, float]
    coordinates: list[str]
    points: int
    method: str
    rtol: float
    atol: float
    kernel: str = Field(description="which kernel ran the trajectories: small (the case's "
                        "generated field, for a map of at least 100000 crossings in all) "
                        "or general")
    trajectories: list[TrajectoryPublic]
