"""GET /api/health: answers from the event loop at once, whatever the workers do."""

from dataclasses import asdict

from fastapi import APIRouter, Request

from app import __version__
from app.api.deps import PoolDep, SettingsDep, VerdictsDep
from app.schemas.health import HealthPublic
from app.schemas.simulate import MAX_FRAMES, MAX_SAMPLES

router = APIRouter(tags=["health"])


@router.get("/health", response_model=HealthPublic)
async def health(request: Request, pool: PoolDep, verdicts: VerdictsDep,
                 settings: SettingsDep) -> dict:
    """Liveness and load: worker pool occupancy, the state of the verification and of the
    kernels' compile (which parts are still warming), and whether a part of the service
    works in a lesser way: status "degraded" then, and `degraded` names each part."""
    cache = request.app.state.kernel_cache
    cache.recheck()
    degraded = []
    if cache.degraded:
        degraded.append("kernel_cache")
    if pool.degraded:
        degraded.append("workers")
    return {"status": "degraded" if degraded else "ok", "degraded": degraded,
            "version": __version__, "pool": asdict(pool.stats()),
            "kernel_cache": cache.public(),
            "limits": {"deadline_s": settings.deadline_s, "max_steps": settings.max_steps,
                       "max_samples": min(settings.max_samples, MAX_SAMPLES),
                       "max_frames": min(settings.max_frames, MAX_FRAMES)},
            "verification": {"state": verdicts.state, "message": verdicts.message,
                             "cases_done": len(verdicts.records),
                             "cases_total": len(verdicts.case_ids),
                             "updated": verdicts.updated},
            "kernels": request.app.state.kernels.public(),
            "connections": _connections()}


def _connections() -> dict | None:
    # lazy: uvicorn's protocol and the connection guards (app.core.server), which a served
    # app has loaded and `import app.main` (the tests' TestClient) does not
    from app.core import server

    if server.ACTIVE is None:
        return None
    st = server.STATS
    return {"open": st["connections"], "peak": st["peak_connections"],
            "max_connections": server.ACTIVE.max_connections,
            **{k: st[k] for k in ("evicted", "refused", "header_timeouts", "body_timeouts",
                                  "header_too_large", "lingered")},
            "evicted_by": dict(st["evicted_by"])}
