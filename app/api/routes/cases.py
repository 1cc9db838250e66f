"""GET /api/cases and GET /api/cases/{id}: the sixteen cases of Tables 1 and 2, and the
runnable cases beyond them (the rattleback)."""

from fastapi import APIRouter, HTTPException
from fastapi.responses import RedirectResponse

from app.api.deps import VerdictsDep
from app.schemas.cases import CasePublic, CaseSummary
from app.schemas.common import NOT_FOUND
from app.services import param_info, views

router = APIRouter(tags=["cases"])


@router.get("/cases", response_model=list[CaseSummary])
async def list_cases() -> list[dict]:
    """Every case: the columns of Tables 1 and 2 in the paper's order, then the runnable
    cases the tables do not have (`in_tables` false, no table and column). Each gives its
    parameters with their meaning, units and valid range."""
    return [{**s, "params": list(param_info.describe(s["id"]))}
            for s in views.case_summaries()]


@router.get("/cases/{case_id:path}", response_model=CasePublic, responses=NOT_FOUND)
async def get_case(case_id: str, verdicts: VerdictsDep) -> dict | RedirectResponse:
    """One case: its cells in the table, every claim with its source and its verdict, and
    what POST /api/simulate accepts for it. Ids contain a slash: /api/cases/plane/routh-ball."""
    if not case_id or case_id.endswith("/"):   # a trailing slash: the same, redirected
        return RedirectResponse(f"/api/cases/{case_id.rstrip('/')}".rstrip("/"),
                                status_code=308)
    if not views.is_case(case_id):
        raise HTTPException(404, f"unknown case {case_id!r}; GET /api/cases lists them")
    out = views.case_detail(case_id, verdicts.by_claim(), verdicts.corrections(),
                            verdicts.case_state(case_id))
    out["runnable"] = {**out["runnable"], "params": list(param_info.describe(case_id)),
                       "units_convention": param_info.units_convention()}
    return out
