"""Responses of GET /api/scenes, /api/scenes/{id} (a teaching scene of catalogue/scenes.yaml)
and /api/scenes/{id}/checks/{k} (one of its checks with the plot its verdict was taken from)."""

from typing import Any

from pydantic import BaseModel, Field


class ScenePreset(BaseModel):
    id: str
    title: str
    explanation: str
    claim: str
    paper: list[str]
    paper_numbers: list[str] = Field(default_factory=list, description="`paper` as the "
                                     "printed paper numbers it: (2.24), Fig. 3")
    scene: dict[str, Any] = Field(description="the run as the scene planner declares it "
                                  "(solvers/scenes/scenes.py): case, params, state, t_end, shows, "
                                  "samples (the frames of the animation)")
    checks: list[dict[str, Any]]
    plot: str | None = Field(None, description="the series of POST /api/scene plotted "
                             "against time beside the animation")
    sentence: str = Field("", description="the claim in one plain sentence (presentation)")
    sliders: list[dict[str, Any]] = Field(default_factory=list, description="controls "
                                          "that change the physics: name, label, symbol "
                                          "(TeX), units, param or state, min, max, step, "
                                          "factor (run value = shown value * factor)")
    beside: dict[str, Any] | None = Field(None, description="a second body rolled from the "
                                          "same start beside the scene's own: case (the "
                                          "same run on it), label, main_label")


class SceneCheck(BaseModel):
    kind: str
    passed: bool
    value: float | None
    detail: str
    caption: str = Field(description="plain words: what to look for in the plot")
    index: int
    count: int = Field(description="how many checks the scene has")
    plot: dict[str, Any] | None = Field(description="the data the verdict was taken from: "
                                        "title, x_title, y_title, log_y, traces [{name, x, y, "
                                        "role: claim | contrast | limit | raw | event}], "
                                        "headline")
