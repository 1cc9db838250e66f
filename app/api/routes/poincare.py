"""POST /api/poincare: the 3D point map of a case (as `rolling poincare`), and the page
/poincare that draws it and the paper's Figs. 3, 5, 6 and 7
(app/static/data/paper_figures.json, written by bench/paper_figures.py).

The starts are resolved (validated, sampled with the seed) in a thread; then each
trajectory is one job of the worker pool (app/services/poincare_jobs.py), `workers` jobs
at a time. With
?stream=true the answer is NDJSON: {"event": "compiling", "estimate_s": s} first when the
map's kernels compile before it (first use on this machine; outside the deadline), then
{"event": "estimate", "seconds": s, ...} from a pilot
of the first start, {"event": "progress", "done": k, "total": n, "remaining": s} after
every trajectory that returns, then {"event": "result", "result": {...}} (or {"event":
"error", "detail": ...}); without it, one JSON object {"trajectories": [...], ...} when all
are done.

One deadline (Settings.deadline_s) holds for the whole request once its kernels are
compiled (app/services/kernel_prepare.py): every job gets the
time that is left, and when none is left the answer is 504 (in a stream: an error event
with "status": 504).
"""

from __future__ import annotations

import json
import math
from dataclasses import asdict

import anyio
from fastapi import APIRouter, Query, Request
from fastapi.responses import HTMLResponse, Response, StreamingResponse

from app.api.deps import JSON_ONLY, PoolDep, SettingsDep
from app.core.disconnect import cancel_on_disconnect
from app.core.pool import DeadlineExceeded
from app.schemas.common import (
    BUSY_RESPONSES,
    DEADLINE_RESPONSES,
    GUARD_RESPONSES,
    PROBLEM_RESPONSES,
)
from app.schemas.poincare import PoincarePublic, PoincareRequest
from app.services import kernel_prepare, poincare_jobs
from app.services.jobs import dumps
from app.services.reader_pages import static_page
from solvers.errors import InputError
from solvers.models.cases import get_case

router = APIRouter(tags=["poincare"])
pages = APIRouter(include_in_schema=False)
_threads = anyio.CapacityLimiter(2)


def resolve(req: PoincareRequest, max_steps: int) -> tuple[dict, dict, list[list[float]]]:
    """(header of the answer, the job every trajectory shares, the starts)."""
    # lazy: the Poincare maps (solvers.maps), not at the server's start
    from solvers.maps.poincare import MapSpec, map_model, resolve_kernel, starts_for

    spec_case = get_case(req.case)
    params = {**(spec_case.example if req.example else {}), **req.params}
    spec = MapSpec(energy=req.energy, g0=req.g0, direction=req.direction, points=req.points,
                   method=req.method, rtol=req.rtol, atol=req.atol, max_steps=max_steps)
    spec.validate()
    model = map_model(req.case, params, allow_any_inertia=req.allow_any_inertia)
    starts = starts_for(model, spec, trajectories=req.trajectories, initial=req.initial,
                        seed=req.seed)
    # the kernel by the whole map's size, before its trajectories become separate jobs
    spec = resolve_kernel(model, spec, len(starts))
    header = {"case": req.case, "params": model.params, "energy": spec.energy,
              "section": {"g0": spec.g0, "direction": spec.direction},
              "coordinates": ["L/G", "H/G", "l"], "points": spec.points,
              "method": spec.method, "rtol": spec.rtol, "atol": spec.atol,
              "kernel": spec.kernel}
    job = {"case": req.case, "params": params, "allow_any_inertia": req.allow_any_inertia,
           "spec": asdict(spec)}
    return header, job, [s.tolist() for s in starts]


_HINT = "ask for fewer trajectories or points, or loosen rtol (such as 1e-8)"
PILOT_POINTS = 20


async def _one(pool, settings, job, starts, lo, hi, end, results):
    """Trajectories lo..hi-1 as one job, with the time left until `end` (anyio clock)."""
    left = end - anyio.current_time()
    if left <= 0:
        raise DeadlineExceeded(settings.deadline_s, _HINT)
    try:
        results[lo:hi] = await pool.run(poincare_jobs.trajectories, job, starts[lo:hi],
                                        deadline=left)
    except DeadlineExceeded:
        raise DeadlineExceeded(settings.deadline_s, _HINT) from None


async def _run_all(pool, settings, job, starts, results, end, send=None):
    """Every trajectory, one job each, `workers` jobs at a time; `send` gets the number of
    trajectories finished after every job that returns (the page's progress is tied to the
    work done, not to rounds), or the first failure."""
    limit = anyio.Semaphore(max(1, settings.workers))
    done = 0

    async def one(lo):
        nonlocal done
        async with limit:
            await _one(pool, settings, job, starts, lo, lo + 1, end, results)
        done += 1
        if send is not None:
            await send.send(("progress", done))

    try:
        async with anyio.create_task_group() as tg:
            for lo in range(len(starts)):
                tg.start_soon(one, lo)
    except BaseExceptionGroup as group:   # the first failure, as the pool raised it
        raise group.exceptions[0] from None


async def _pilot(pool, settings, starts, job, points, end) -> float:
    """Seconds the whole map should take: PILOT_POINTS crossings of the first start timed
    in a worker (a real run of this case on this server), times the crossings asked for,
    times the rounds of `workers` trajectories."""
    left = end - anyio.current_time()
    if left <= 0:
        raise DeadlineExceeded(settings.deadline_s, _HINT)
    try:
        # the deadline covers the wait for a worker too, not only the run
        with anyio.fail_after(left):
            per_point = await pool.run(poincare_jobs.seconds_per_point, job, starts[0],
                                       min(points, PILOT_POINTS), deadline=left)
    except (DeadlineExceeded, TimeoutError):
        raise DeadlineExceeded(settings.deadline_s, _HINT) from None
    rounds = math.ceil(len(starts) / max(1, settings.workers))
    return per_point * points * rounds


@router.post("/poincare", dependencies=[JSON_ONLY],
             response_model=PoincarePublic,
             responses={**PROBLEM_RESPONSES, **BUSY_RESPONSES, **GUARD_RESPONSES,
                        **DEADLINE_RESPONSES,
                        200: {"content": {"application/x-ndjson": {}},
                              "description": "the map (JSON), or with stream=true NDJSON "
                              "events: an estimate, progress after every trajectory and "
                              "the result"}})
async def poincare(req: PoincareRequest, request: Request, pool: PoolDep,
                   settings: SettingsDep,
                   stream: bool = Query(False, description="NDJSON progress events")):
    """The 3D point map of (2.22): `trajectories` starts on the level E = energy and the
    section g = g0, `points` crossings each, as (L/G, H/G, l)."""
    header, job, starts = await anyio.to_thread.run_sync(resolve, req, settings.max_steps,
                                                         limiter=_threads)
    n = len(starts)
    results: list[dict | None] = [None] * n
    kernels = request.app.state.kernels
    keys = [kernel_prepare.map_key(job)]

    async def prepare():
        # the map's kernels compile (first use) in a job without a deadline; the map's
        # one deadline starts after it (app/services/kernel_prepare.py)
        await kernel_prepare.prepare(pool, kernels, settings.kernels_warm, keys,
                                     poincare_jobs.prepare, job, starts[0])
        return anyio.current_time() + settings.deadline_s

    if not stream:
        end = await prepare()
        await cancel_on_disconnect(request, lambda: _run_all(pool, settings, job, starts,
                                                             results, end))
        return Response(dumps({**header, "trajectories": results}),
                        media_type="application/json")

    def problem(exc) -> str:
        status = (504 if isinstance(exc, DeadlineExceeded) else
                  422 if isinstance(exc, InputError) else 503)
        event = {"event": "error", "status": status, "detail": str(exc)}
        if status == 503:   # busy, no worker, the server stopping: when to come back
            event["retry_after"] = getattr(exc, "retry_after", 1)
        return json.dumps(event) + "\n"

    async def events():
        t0 = anyio.current_time()
        try:
            if kernel_prepare.needed(kernels, settings.kernels_warm, keys):
                yield json.dumps({"event": "compiling", "estimate_s": kernels.estimate_s(),
                                  "detail": "compiling the map's kernels (first use on "
                                  "this machine)"}) + "\n"
            end = await prepare()
            estimate = await _pilot(pool, settings, starts, job, req.points, end)
        except Exception as exc:
            yield problem(exc)
            return
        yield json.dumps({"event": "estimate", "seconds": round(estimate, 3),
                          "total": n, "deadline": settings.deadline_s}) + "\n"
        yield json.dumps({"event": "progress", "done": 0, "total": n}) + "\n"
        send, recv = anyio.create_memory_object_stream(math.inf)
        failure: list[BaseException] = []

        async def work():
            try:
                await _run_all(pool, settings, job, starts, results, end, send)
            except Exception as exc:
                failure.append(exc)
            finally:
                send.close()

        t1 = anyio.current_time()
        async with anyio.create_task_group() as tg:
            tg.start_soon(work)
            async with recv:
                async for _, done in recv:
                    elapsed = anyio.current_time() - t1
                    yield json.dumps({"event": "progress", "done": done, "total": n,
                                      "elapsed": round(anyio.current_time() - t0, 3),
                                      "remaining": round(elapsed / done * (n - done), 3)}
                                     ) + "\n"
        if failure:
            yield problem(failure[0])
            return
        yield (b'{"event":"result","result":' + dumps({**header, "trajectories": results})
               + b"}\n").decode()

    return StreamingResponse(events(), media_type="application/x-ndjson")


@pages.get("/poincare")
async def poincare_page(settings: SettingsDep) -> HTMLResponse:
    return HTMLResponse(static_page(settings.static_dir / "poincare.html"))
