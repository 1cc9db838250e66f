"""POST /api/verify/{id}: run the checks of one case's claims now; GET /api/verdicts."""

import time

from fastapi import APIRouter, HTTPException, Request

from app.api.deps import JSON_ONLY, PoolDep, SettingsDep, VerdictsDep
from app.core.disconnect import cancel_on_disconnect
from app.schemas.common import (
    BUSY_RESPONSES,
    DEADLINE_RESPONSES,
    GUARD_RESPONSES,
    NOT_FOUND,
    PROBLEM_RESPONSES,
    Problem,
)
from app.schemas.verify import MarksPublic, VerdictPublic, VerifyPublic, VerifyRequest
from app.services import verdicts as service
from app.services import views
from catalogue.load import load_catalogue

router = APIRouter(tags=["verify"])


@router.post("/verify/{case_id:path}", dependencies=[JSON_ONLY],
             response_model=VerifyPublic,
             responses={**NOT_FOUND, **BUSY_RESPONSES, **GUARD_RESPONSES, **DEADLINE_RESPONSES,
                        **PROBLEM_RESPONSES,
                        501: {"model": Problem, "description": "verification not installed"}})
async def verify_case(case_id: str, request: Request, pool: PoolDep, settings: SettingsDep,
                      store: VerdictsDep, body: VerifyRequest | None = None) -> dict:
    """Check every claim of the case (solvers.verify, in a worker) and keep the verdicts:
    verified, fails, evidence or unchecked, with the residual and a message."""
    try:
        load_catalogue().case(case_id)
    except KeyError:
        raise HTTPException(404, f"unknown case {case_id!r}; GET /api/cases lists them") from None
    # the checks run the case's kernels: while the background warm-up compiles them,
    # wait for it (its compile is outside the check's deadline)
    await cancel_on_disconnect(request, request.app.state.kernels.wait_done)
    t0 = time.perf_counter()
    try:
        records = await cancel_on_disconnect(request, lambda: service.verify_case(
            pool, case_id, settings.verify_deadline_s))
    except ImportError as exc:
        raise HTTPException(501, f"verification is not available: {exc}") from None
    store.put(case_id, records)
    return {"case": case_id, "records": [views.record(r) for r in records],
            "seconds": time.perf_counter() - t0}


@router.get("/marks", response_model=MarksPublic)
async def marks(store: VerdictsDep) -> dict:
    """The vocabulary of marks (one per meaning: what a check showed) that every cell and
    claim record carries in `mark`, and how many table cells carry each so far."""
    return views.marks_overview(store.by_claim(), store.pending())


@router.get("/verdicts", response_model=list[VerdictPublic])
async def all_verdicts(store: VerdictsDep) -> list[dict]:
    """Every verdict computed so far (claims not listed are unchecked)."""
    return [views.record(r) for recs in store.records.values() for r in recs]
