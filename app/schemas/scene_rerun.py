"""Request and response of POST /api/scenes/{id}/run: a teaching scene run again with its
sliders moved, every check evaluated on the new run."""

from typing import Any

from pydantic import BaseModel, Field

from app.schemas.scenes import SceneCheck


class RerunRequest(BaseModel):
    values: dict[str, float] = Field(description="slider name -> value in the slider's "
                                     "units, within its range")


class RerunResponse(BaseModel):
    id: str
    values: dict[str, float]
    scene: dict[str, Any] = Field(description="the moved run: case, params, state, t_end, "
                                  "samples (POST /api/scene draws it)")
    checks: list[SceneCheck]
