"""GET /api/scenes: the teaching scenes of catalogue/scenes.yaml (presets for a class), and
the page /scenes that lists them and plays each one (POST /api/scene with the case,
parameters, initial state and t_end of its `scene` declaration, frames = its samples).
/scenes#ID opens and plays scene ID."""

from __future__ import annotations

from typing import Any

from fastapi import APIRouter, HTTPException
from fastapi.responses import HTMLResponse
from pydantic import BaseModel, Field

from app.api.deps import SettingsDep
from app.services.reader_pages import static_page

router = APIRouter(tags=["scenes"])
pages = APIRouter(include_in_schema=False)


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


def _public(s) -> dict:
    from catalogue.numbering import cite, printed

    # what a reader sees carries the paper's printed numbers; the labels stay as data
    d = s.model_dump(mode="json")
    return {**d, "title": cite(d["title"]), "explanation": cite(d["explanation"]),
            "claim": cite(d["claim"]), "paper_numbers": [printed(x) or x for x in d["paper"]]}


@router.get("/scenes", response_model=list[ScenePreset])
async def scenes() -> list[dict]:
    """Every teaching scene, in the catalogue's order."""
    from catalogue.scenes import load_scenes

    return [_public(s) for s in load_scenes().values()]


@router.get("/scenes/{scene_id}", response_model=ScenePreset,
            responses={404: {"description": "no such scene"}})
async def scene_preset(scene_id: str) -> dict:
    from catalogue.scenes import load_scenes

    s = load_scenes().get(scene_id)
    if s is None:
        raise HTTPException(404, f"unknown scene {scene_id!r}; known scenes: "
                            + ", ".join(load_scenes()))
    return _public(s)


@pages.get("/scenes")
async def scenes_page(settings: SettingsDep) -> HTMLResponse:
    return HTMLResponse(static_page(settings.static_dir / "scenes.html"))
