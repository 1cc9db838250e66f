"""A scene: what one view of the explorer shows, declared as data (a preset or a request).

A scene names a run (case, parameters, initial state, t_end) and what is shown of it:

  shows       a non-empty subset of
                "series"      time series of some variables (`series`, default: the state)
                "drift"       the drift of every integral the case carries
                "section"     a Poincare section (`section`: variable = value, crossed in
                              a direction, `crossings` of them)
                "animation"   the body's orientation and its contact path (`samples`
                              frames)
                "gamma_path"  the path of gamma on the unit sphere (body axes)
  samples     how many points are plotted (frames of an animation)
  series      variables of the time series: the state labels of the case (M1 M2 M3 g1 g2
              g3, or M1 M2 M3 r1 r2) and, for a body of revolution, disk or Routh ball,
              the reduced variables gamma3 K1 K2 K3 of (2.5) / (3.3)

`solvers.scenes.planner` turns a scene into the smallest model that serves it and runs it.
Example (YAML, as in a catalogue of presets):

    case: plane/round-disk
    t_end: 200
    shows: [series]
    series: [gamma3, K1, K2]
    samples: 401

Parameters given here are merged over the case's example parameters; `state` defaults to
the case's example state.
"""

from __future__ import annotations

import math
from typing import Literal

from pydantic import BaseModel, ConfigDict, Field, field_validator, model_validator

from solvers.kernels import layout as L
from solvers.models.bodies import STATE_LABELS
from solvers.models.cases import get_case

Show = Literal["series", "drift", "section", "animation", "gamma_path"]
SHOWS = ("series", "drift", "section", "animation", "gamma_path")
REDUCED_LABELS = ("gamma3", "K1", "K2", "K3")
MAX_SAMPLES = 200_000


class SectionSpec(BaseModel):
    """The section `variable = value` (a state label), crossed with the variable
    increasing (direction 1), decreasing (-1) or either (0)."""

    model_config = ConfigDict(extra="forbid")
    variable: str
    value: float = 0.0
    direction: Literal[-1, 0, 1] = 1
    crossings: int = Field(200, ge=1, le=100_000)


class Scene(BaseModel):
    model_config = ConfigDict(extra="forbid")
    case: str
    params: dict[str, float] = Field(default_factory=dict)
    state: list[float] | None = None
    t_end: float = Field(gt=0)
    shows: set[Show] = Field(min_length=1)
    samples: int = Field(201, ge=2, le=MAX_SAMPLES)
    series: list[str] = Field(default_factory=list)
    section: SectionSpec | None = None
    rtol: float = Field(1e-10, ge=1e-16, le=0.1)
    atol: float = Field(1e-12, gt=0, le=1.0)

    @field_validator("t_end")
    @classmethod
    def _finite(cls, v):
        if not math.isfinite(v):
            raise ValueError("t_end must be finite")
        return v

    @model_validator(mode="after")
    def _consistent(self):
        case = get_case(self.case)
        labels = STATE_LABELS[L.MODEL_FLAT if case.body == "flat" else L.MODEL_FULL]
        allowed = set(labels) | (set(REDUCED_LABELS) if has_reduced(self.case) else set())
        bad = [v for v in self.series if v not in allowed]
        if bad:
            raise ValueError(f"series {bad}: not variables of {self.case}; choose from "
                             + " ".join(sorted(allowed)))
        if ("section" in self.shows) != (self.section is not None):
            raise ValueError("a scene shows a section exactly when it declares `section`")
        if self.section is not None and self.section.variable not in labels:
            raise ValueError(f"section variable {self.section.variable!r}: choose a state "
                             f"label of {self.case}: {' '.join(labels)}")
        return self

    @property
    def series_names(self) -> list[str]:
        """The variables of the time series (default: the state labels)."""
        if self.series:
            return list(self.series)
        case = get_case(self.case)
        return list(STATE_LABELS[L.MODEL_FLAT if case.body == "flat" else L.MODEL_FULL])


def has_reduced(case_id: str) -> bool:
    """Does the case have the compiled reduced system (gamma3, K1, K2, K3) of (2.6)
    (body of revolution, disk, Routh ball, on the plane or a sphere)?"""
    case = get_case(case_id)
    return case.symmetry == "axial" and case.body in ("revolution", "disk", "routh")
