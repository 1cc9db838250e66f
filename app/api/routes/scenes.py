"""GET /api/scenes: the teaching scenes of catalogue/scenes.yaml (presets for a class), and
the page /scenes that lists them and plays each one (POST /api/scene with the case,
parameters, initial state and t_end of its `scene` declaration, frames = its samples).
/scenes#ID opens and plays scene ID."""

from __future__ import annotations

from fastapi import APIRouter, HTTPException, Request
from fastapi.responses import HTMLResponse, Response

from app.api.deps import JSON_ONLY, PoolDep, SettingsDep
from app.core.disconnect import cancel_on_disconnect
from app.schemas.common import (
    BUSY_RESPONSES,
    DEADLINE_RESPONSES,
    GUARD_RESPONSES,
    PROBLEM_RESPONSES,
)
from app.schemas.scene_rerun import RerunRequest, RerunResponse
from app.schemas.scenes import SceneCheck, ScenePreset
from app.services import kernel_prepare
from app.services.jobs import dumps, prepare_scene_check
from app.services.reader_pages import static_page
from catalogue.numbering import cite, printed
from solvers.scenes.teaching import load_scenes

router = APIRouter(tags=["scenes"])
pages = APIRouter(include_in_schema=False)


def _public(s) -> dict:
    # what a reader sees carries the paper's printed numbers; the labels stay as data
    d = s.model_dump(mode="json")
    return {**d, "title": cite(d["title"]), "explanation": cite(d["explanation"]),
            "claim": cite(d["claim"]), "paper_numbers": [printed(x) or x for x in d["paper"]]}


@router.get("/scenes", response_model=list[ScenePreset])
async def scenes() -> list[dict]:
    """Every teaching scene, in the catalogue's order."""
    return [_public(s) for s in load_scenes().values()]


@router.get("/scenes/{scene_id}", response_model=ScenePreset,
            responses={404: {"description": "no such scene"}})
async def scene_preset(scene_id: str) -> dict:
    s = load_scenes().get(scene_id)
    if s is None:
        raise HTTPException(404, f"unknown scene {scene_id!r}; known scenes: "
                            + ", ".join(load_scenes()))
    return _public(s)


# the presets are fixed: a check's answer is computed once per server process
_checks: dict[tuple[str, int], bytes] = {}


@router.get("/scenes/{scene_id}/checks/{k}", response_model=SceneCheck,
            responses={404: {"description": "no such scene or check"}, **BUSY_RESPONSES,
                       **DEADLINE_RESPONSES})
async def scene_check(scene_id: str, k: int, request: Request, pool: PoolDep,
                      settings: SettingsDep) -> Response:
    """Check k of the scene on the scene's own run (solvers/scenes/scene_checks.py), with the
    plot of exactly the data its verdict was taken from: what /scenes draws."""
    # lazy: the scenes' checks (solvers.scenes.scene_checks), not at the server's start
    from solvers.scenes.scene_checks import check_json

    s = load_scenes().get(scene_id)
    if s is None:
        raise HTTPException(404, f"unknown scene {scene_id!r}; known scenes: "
                            + ", ".join(load_scenes()))
    if not 0 <= k < len(s.checks):
        raise HTTPException(404, f"scene {scene_id!r} has checks 0 … {len(s.checks) - 1}")
    body = _checks.get((scene_id, k))
    if body is None:
        # the scene's kernels compile (first use) before the check's deadline starts
        await kernel_prepare.prepare(pool, request.app.state.kernels, settings.kernels_warm,
                                     [("scene-check", scene_id)], prepare_scene_check,
                                     scene_id)
        d = await cancel_on_disconnect(request, lambda: pool.run(
            check_json, scene_id, k, deadline=settings.deadline_s))
        body = _checks.setdefault((scene_id, k), dumps(d))
    return Response(body, media_type="application/json")


@router.post("/scenes/{scene_id}/run", dependencies=[JSON_ONLY], response_model=RerunResponse,
             responses={404: {"description": "no such scene"}, **PROBLEM_RESPONSES,
                        **GUARD_RESPONSES, **BUSY_RESPONSES, **DEADLINE_RESPONSES})
async def scene_rerun(scene_id: str, req: RerunRequest, request: Request, pool: PoolDep,
                      settings: SettingsDep) -> Response:
    """The scene run again with its sliders moved, every check evaluated on the new run
    (solvers/scenes/rerun.py): what /scenes draws after a slider changes."""
    # lazy: the scenes' re-runs (solvers.scenes.rerun), not at the server's start
    from solvers.scenes.rerun import moved, rerun_json

    s = load_scenes().get(scene_id)
    if s is None:
        raise HTTPException(404, f"unknown scene {scene_id!r}; known scenes: "
                            + ", ".join(load_scenes()))
    moved(s, req.values)           # bad input answers here, before any work is queued
    await kernel_prepare.prepare(pool, request.app.state.kernels, settings.kernels_warm,
                                 [("scene-check", scene_id)], prepare_scene_check, scene_id)
    d = await cancel_on_disconnect(request, lambda: pool.run(
        rerun_json, scene_id, req.values, deadline=settings.deadline_s))
    return Response(dumps(d), media_type="application/json")


@pages.get("/scenes")
async def scenes_page(settings: SettingsDep) -> HTMLResponse:
    return HTMLResponse(static_page(settings.static_dir / "scenes.html"))
