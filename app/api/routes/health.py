"""GET /api/health: answers from the event loop at once, whatever the workers do."""

from dataclasses import asdict

from fastapi import APIRouter

from app import __version__
from app.api.deps import PoolDep, SettingsDep, VerdictsDep
from app.schemas.health import HealthPublic
from app.schemas.simulate import MAX_FRAMES, MAX_SAMPLES

router = APIRouter(tags=["health"])


@router.get("/health", response_model=HealthPublic)
async def health(pool: PoolDep, verdicts: VerdictsDep, settings: SettingsDep) -> dict:
    """Liveness and load: worker pool occupancy and the state of the verification."""
    return {"status": "ok", "version": __version__, "pool": asdict(pool.stats()),
            "limits": {"deadline_s": settings.deadline_s, "max_steps": settings.max_steps,
                       "max_samples": min(settings.max_samples, MAX_SAMPLES),
                       "max_frames": min(settings.max_frames, MAX_FRAMES)},
            "verification": {"state": verdicts.state, "message": verdicts.message,
                             "cases_done": len(verdicts.records),
                             "cases_total": len(verdicts.case_ids),
                             "updated": verdicts.updated}}
