"""POST /api/simulate, /api/scene and /api/validate; GET /api/methods.

A run is validated first (in a thread: building the model is cheap and a bad input is a
422 even when every worker is busy), then queued for a worker process with the step
budget and the deadline of the settings, and cancelled if the client goes away.
"""

from typing import Literal

import anyio
import numpy as np
from fastapi import APIRouter, Query, Request
from fastapi.responses import Response

from app.api.deps import JSON_ONLY, PoolDep, SettingsDep
from app.core.disconnect import cancel_on_disconnect
from app.schemas.common import (
    BUSY_RESPONSES,
    DEADLINE_RESPONSES,
    GUARD_RESPONSES,
    NOT_ACCEPTABLE_RESPONSES,
    PROBLEM_RESPONSES,
)
from app.schemas.simulate import (
    METHODS,
    CompilesPublic,
    MethodPublic,
    ScenePublic,
    SceneRequest,
    SimulateRequest,
    SimulateResponse,
    ValidatePublic,
)
from app.services import jobs, kernel_prepare, payloads, provenance
from catalogue.plain_words import invariant_name
from solvers.errors import InputError
from solvers.models.cases import build, get_case, initial_state
from solvers.models.observables import public_name
from solvers.simulate import check_step, symmetric_methods

router = APIRouter(tags=["simulate"])
_validation_threads = anyio.CapacityLimiter(2)


def resolve(req: SimulateRequest, max_steps: int | None = None) -> dict:
    """The run a request asks for, checked by the solvers' own validation (InputError);
    max_steps: the server's step budget, which a symmetric method's step must fit."""
    # the output times are linspace(0, t_end, samples); they must be distinct
    if not np.all(np.diff(np.linspace(0.0, req.t_end, req.samples)) > 0):
        raise InputError(f"t_end = {req.t_end!r}: too small to hold {req.samples} distinct "
                         "sample times")
    spec = get_case(req.case)
    params = {**(spec.example if req.example else {}), **req.params}
    state = req.state if req.state is not None else (spec.state if req.example else None)
    if state is None:
        raise InputError("state is required (or example = true for the case's demo state)")
    model = build(req.case, params, allow_any_inertia=req.allow_any_inertia)
    initial_state(model, state)
    if req.project and req.method.startswith("scipy-"):
        raise InputError(f"project = true needs a compiled method (projection happens inside "
                         f"the step); {req.method} is a scipy reference method")
    check_step(req.method, req.step, req.t_end, max_steps, req.project)
    if req.method == "taylor" or req.precision is not None:
        # lazy: the Taylor backend, for method taylor only, not at the server's start
        from solvers.integrate.taylor_backend import check_taylor_options

        check_taylor_options(req.method, req.precision, req.project, req.step)
    return {"case": req.case, "params": params, "state": list(state), "t_end": req.t_end,
            "method": req.method, "rtol": req.rtol, "atol": req.atol, "step": req.step,
            "samples": req.samples, "project": req.project, "precision": req.precision,
            "allow_any_inertia": req.allow_any_inertia, "field": req.field,
            "_model": model}


async def _resolved(req: SimulateRequest, settings=None) -> dict:
    if settings is not None and req.samples > settings.max_samples:
        raise InputError(f"samples = {req.samples}: this server returns at most "
                         f"{settings.max_samples} samples per run")
    frames = getattr(req, "frames", None)
    if settings is not None and frames is not None and frames > settings.max_frames:
        raise InputError(f"frames = {frames}: this server renders at most "
                         f"{settings.max_frames} frames per scene")
    max_steps = settings.max_steps if settings is not None else None
    return await anyio.to_thread.run_sync(resolve, req, max_steps, limiter=_validation_threads)


async def _prepare(request: Request, pool, settings, resolved: dict, job: dict) -> None:
    """The kernels the run needs, compiled (or loaded) in a job without a deadline before
    the run's own deadline starts (app/services/kernel_prepare.py)."""
    keys = await _keys(resolved)
    # the worker compiles the keys planned here: the request is planned once
    await kernel_prepare.prepare(pool, request.app.state.kernels, settings.kernels_warm,
                                 keys, jobs.prepare_kernels, job, keys)


async def _keys(resolved: dict) -> list[tuple]:
    """The kernels of the run (kernel_prepare.simulate_keys), off the event loop."""
    return await anyio.to_thread.run_sync(kernel_prepare.simulate_keys, resolved,
                                          limiter=_validation_threads)


def _job(resolved: dict) -> dict:
    return {k: v for k, v in resolved.items() if not k.startswith("_")}


_RUN_CONTENT = {
    "application/json": {},   # the SimulateResponse schema (response_model)
    payloads.ARROW: {"schema": {"type": "string", "format": "binary",
                                "description": "Arrow IPC stream, one record batch"}},
    payloads.CSV: {"schema": {"type": "string"}},
}
_RUN_DESCRIPTION = (
    "the run, in the type the Accept header prefers: application/json (the default, also "
    "for */*: the object below; a non-finite number is null), "
    "application/vnd.apache.arrow.stream (an Arrow IPC stream of one record batch: a "
    "float64 column per series named as in the JSON and the CSV, t, the state, the "
    "invariants under their output names such as M_squared; the other fields of the JSON "
    "object, each a JSON text, in the schema metadata under case, params, status, message, "
    "state_labels, invariants (their column names), stats and provenance), or text/csv (as "
    "format=csv: the provenance as '# ' lines, then a header row and one row per sample; "
    "the file name carries a hash of the run's inputs)")


@router.post("/simulate", dependencies=[JSON_ONLY],
             response_model=SimulateResponse,
             responses={**PROBLEM_RESPONSES, **BUSY_RESPONSES, **GUARD_RESPONSES,
                        **DEADLINE_RESPONSES, **NOT_ACCEPTABLE_RESPONSES,
                        200: {"content": _RUN_CONTENT, "description": _RUN_DESCRIPTION}})
async def simulate(req: SimulateRequest, request: Request, pool: PoolDep,
                   settings: SettingsDep,
                   format: Literal["json", "csv", "arrow"] | None = Query(
                       None, description="csv: one row per sample (t, state, invariants), "
                       "whatever the Accept header says; json: the JSON object; arrow: the "
                       "Arrow IPC stream (as Accept: application/vnd.apache.arrow.stream); "
                       "none: the type the Accept header prefers")) -> Response:
    """Integrate one case from an initial state over [0, t_end]: the state and every
    invariant the case carries at `samples` times, and the cost of the run."""
    if format is None:
        media = payloads.negotiate(request.headers.get("accept"))
    else:
        media = {"csv": payloads.CSV, "arrow": payloads.ARROW}.get(format, payloads.JSON)
    resolved = await _resolved(req, settings)
    job = _job(resolved)
    # the address of the case page that reproduces the run: the configured public one,
    # else the one this request was made to
    prov = provenance.of_run(job, settings.public_url or str(request.base_url))
    await _prepare(request, pool, settings, resolved, job)
    fn = {payloads.CSV: jobs.simulate_csv, payloads.ARROW: jobs.simulate_arrow}.get(
        media, jobs.simulate_json)
    body = await cancel_on_disconnect(request, lambda: pool.run(
        fn, job, settings.max_steps, prov, deadline=settings.deadline_s))
    if media == payloads.CSV:
        return Response(body, media_type="text/csv; charset=utf-8", headers={
            "Content-Disposition": f'attachment; filename="{prov["file_stem"]}.csv"',
            "Vary": "Accept"})
    return Response(body, media_type=media, headers={"Vary": "Accept"})


@router.post("/validate", dependencies=[JSON_ONLY],
             response_model=ValidatePublic,
             responses={**PROBLEM_RESPONSES, **GUARD_RESPONSES})
async def validate(req: SimulateRequest, settings: SettingsDep) -> dict:
    """Check a run without running it (the explorer calls this as you type): 200 with the
    parameters it would use, or 422 naming the field, the value and why."""
    resolved = await _resolved(req, settings)
    model = resolved["_model"]
    return {"ok": True, "params": model.params, "state_labels": list(model.state_labels),
            "invariants": [public_name(n) for n in model.integral_names],
            "invariants_text": [invariant_name(n) for n in model.integral_names]}


@router.post("/scene", dependencies=[JSON_ONLY],
             response_model=ScenePublic,
             responses={**PROBLEM_RESPONSES, **BUSY_RESPONSES, **GUARD_RESPONSES,
                        **DEADLINE_RESPONSES})
async def scene(req: SceneRequest, request: Request, pool: PoolDep,
                settings: SettingsDep) -> Response:
    """The 3D animation of a run: the body's rotation, its centre of mass and its contact
    point at `frames` times, a mesh of the body, and checks (solvers.models.kinematics)."""
    if req.field != "auto":
        raise InputError(f"field = {req.field!r}: a scene runs the default field (auto); "
                         "field applies to /api/simulate")
    job = _job(await _resolved(req, settings))
    await kernel_prepare.prepare(pool, request.app.state.kernels, settings.kernels_warm,
                                 [("scene", req.case)], jobs.prepare_scene, job)
    body = await cancel_on_disconnect(request, lambda: pool.run(
        jobs.scene_json, job, req.frames, min(settings.max_steps, 200_000),
        deadline=settings.deadline_s))
    return Response(body, media_type="application/json")


@router.get("/methods", response_model=list[MethodPublic])
async def methods() -> list[dict]:
    """Integration methods: compiled Runge-Kutta pairs and scipy reference methods."""
    return [{"name": m, "kind": "scipy reference" if m.startswith("scipy-") else
             "symmetric" if m in symmetric_methods() else
             "taylor" if m == "taylor" else "auto" if m == "auto" else "compiled"}
            for m in METHODS]


@router.post("/simulate/compiles", dependencies=[JSON_ONLY],
             response_model=CompilesPublic,
             responses={**PROBLEM_RESPONSES, **GUARD_RESPONSES})
async def simulate_compiles(req: SimulateRequest, request: Request,
                            settings: SettingsDep) -> dict:
    """Whether POST /api/simulate with this body would first compile its kernels (first
    use on this machine; outside the run's deadline), and about how long that takes: the
    explorer says "compiling" while it waits."""
    resolved = await _resolved(req, settings)
    return _compiles(request, settings, await _keys(resolved))


@router.post("/scene/compiles", dependencies=[JSON_ONLY],
             response_model=CompilesPublic,
             responses={**PROBLEM_RESPONSES, **GUARD_RESPONSES})
async def scene_compiles(req: SceneRequest, request: Request, settings: SettingsDep) -> dict:
    """As /api/simulate/compiles, for POST /api/scene."""
    await _resolved(req, settings)
    return _compiles(request, settings, [("scene", req.case)])


def _compiles(request: Request, settings, keys: list[tuple]) -> dict:
    kernels = request.app.state.kernels
    return {"compiles": kernel_prepare.needed(kernels, settings.kernels_warm, keys),
            "estimate_s": kernels.estimate_s()}
