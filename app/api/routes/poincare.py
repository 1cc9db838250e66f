"""POST /api/poincare: the 3D point map of a case (as `rolling poincare`), and the page
/poincare that draws it and the paper's Figs ris-*1..ris-*4 (app/static/data/paper_figures.json,
written by bench/paper_figures.py).

The starts are resolved (validated, sampled with the seed) in a thread; then they are cut
into slices of consecutive trajectories, each slice one job of the worker pool (one
compiled ensemble, app/services/poincare_jobs.py), `workers` jobs at a time. With
?stream=true the answer is NDJSON: {"event": "progress", "done": k, "total": n} after
each round of jobs, then {"event": "result", "result": {...}} (or {"event": "error",
"detail": ...}); without it, one JSON object {"trajectories": [...], ...} when all are done.

One deadline (Settings.deadline_s) holds for the whole request: every job gets the
time that is left, and when none is left the answer is 504 (in a stream: an error event
with "status": 504).
"""

from __future__ import annotations

import json
import math

import anyio
from fastapi import APIRouter, Query, Request
from fastapi.responses import HTMLResponse, Response, StreamingResponse

from app.api.deps import PoolDep, SettingsDep
from app.core.disconnect import cancel_on_disconnect
from app.core.pool import DeadlineExceeded
from app.schemas.common import (
    BUSY_RESPONSES,
    DEADLINE_RESPONSES,
    GUARD_RESPONSES,
    PROBLEM_RESPONSES,
)
from app.schemas.poincare import PoincarePublic, PoincareRequest
from app.services import poincare_jobs
from app.services.jobs import dumps
from app.services.reader_pages import static_page
from solvers.errors import InputError

router = APIRouter(tags=["poincare"])
pages = APIRouter(include_in_schema=False)
_threads = anyio.CapacityLimiter(2)


def resolve(req: PoincareRequest, max_steps: int) -> tuple[dict, dict, list[list[float]]]:
    """(header of the answer, the job every trajectory shares, the starts)."""
    from dataclasses import asdict

    from solvers.maps.poincare import MapSpec, map_model, starts_for
    from solvers.models.cases import get_case

    spec_case = get_case(req.case)
    params = {**(spec_case.example if req.example else {}), **req.params}
    spec = MapSpec(energy=req.energy, g0=req.g0, direction=req.direction, points=req.points,
                   method=req.method, rtol=req.rtol, atol=req.atol, max_steps=max_steps)
    spec.validate()
    model = map_model(req.case, params, allow_any_inertia=req.allow_any_inertia)
    starts = starts_for(model, spec, trajectories=req.trajectories, initial=req.initial,
                        seed=req.seed)
    from solvers.models.cases import check_derived

    for s in starts:   # a level so high that its starts overflow (energy = 1e308)
        check_derived(model, s, blame=f"energy = {req.energy!r}")
    header = {"case": req.case, "params": model.params, "energy": spec.energy,
              "section": {"g0": spec.g0, "direction": spec.direction},
              "coordinates": ["L/G", "H/G", "l"], "points": spec.points,
              "method": spec.method, "rtol": spec.rtol, "atol": spec.atol}
    job = {"case": req.case, "params": params, "allow_any_inertia": req.allow_any_inertia,
           "spec": asdict(spec)}
    return header, job, [s.tolist() for s in starts]


_HINT = "ask for fewer trajectories or points, or loosen rtol"


def _slices(n: int, width: int) -> list[tuple[int, int]]:
    """The starts cut into jobs of consecutive trajectories: about four rounds of `width`
    jobs (progress after each round), each job one compiled ensemble."""
    per_job = max(1, math.ceil(n / (4 * width)))
    return [(lo, min(n, lo + per_job)) for lo in range(0, n, per_job)]


async def _batch(pool, settings, job, starts, results, jobs, end):
    """The jobs (lo, hi) at once, each with the time left until `end` (anyio clock)."""
    async def one(lo, hi):
        left = end - anyio.current_time()
        if left <= 0:
            raise DeadlineExceeded(settings.deadline_s, _HINT)
        try:
            results[lo:hi] = await pool.run(poincare_jobs.trajectories, job, starts[lo:hi],
                                            deadline=left)
        except DeadlineExceeded:
            raise DeadlineExceeded(settings.deadline_s, _HINT) from None

    try:
        async with anyio.create_task_group() as tg:
            for lo, hi in jobs:
                tg.start_soon(one, lo, hi)
    except BaseExceptionGroup as group:   # the first failure, as the pool raised it
        raise group.exceptions[0] from None


@router.post("/poincare", response_model=PoincarePublic,
             responses={**PROBLEM_RESPONSES, **BUSY_RESPONSES, **GUARD_RESPONSES,
                        **DEADLINE_RESPONSES,
                        200: {"content": {"application/x-ndjson": {}},
                              "description": "the map (JSON), or with stream=true NDJSON "
                              "progress events and the result"}})
async def poincare(req: PoincareRequest, request: Request, pool: PoolDep,
                   settings: SettingsDep,
                   stream: bool = Query(False, description="NDJSON progress events")):
    """The 3D point map of eq an-dp: `trajectories` starts on the level E = energy and the
    section g = g0, `points` crossings each, as (L/G, H/G, l)."""
    header, job, starts = await anyio.to_thread.run_sync(resolve, req, settings.max_steps,
                                                         limiter=_threads)
    n = len(starts)
    end = anyio.current_time() + settings.deadline_s
    width = max(1, settings.workers)
    jobs = _slices(n, width)
    rounds = [jobs[k:k + width] for k in range(0, len(jobs), width)]
    results: list[dict | None] = [None] * n

    if not stream:
        async def work():
            for group in rounds:
                await _batch(pool, settings, job, starts, results, group, end)

        await cancel_on_disconnect(request, work)
        return Response(dumps({**header, "trajectories": results}),
                        media_type="application/json")

    async def events():
        yield json.dumps({"event": "progress", "done": 0, "total": n}) + "\n"
        for group in rounds:
            try:
                await _batch(pool, settings, job, starts, results, group, end)
            except Exception as exc:   # a Problem for the page, then stop
                status = (504 if isinstance(exc, DeadlineExceeded) else
                          422 if isinstance(exc, InputError) else 503)
                yield json.dumps({"event": "error", "status": status,
                                  "detail": str(exc)}) + "\n"
                return
            yield json.dumps({"event": "progress", "done": group[-1][1], "total": n}) + "\n"
        yield (b'{"event":"result","result":' + dumps({**header, "trajectories": results})
               + b"}\n").decode()

    return StreamingResponse(events(), media_type="application/x-ndjson")


@pages.get("/poincare")
async def poincare_page(settings: SettingsDep) -> HTMLResponse:
    return HTMLResponse(static_page(settings.static_dir / "poincare.html"))
