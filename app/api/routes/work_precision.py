"""GET /api/work-precision: the measured work-precision results (bench/work_precision.py,
committed in solvers/integrate/data/work_precision.json) with their summary, and the page
/work-precision that draws the diagram and says what a tolerance buys."""

from __future__ import annotations

from typing import Any

from fastapi import APIRouter, HTTPException
from fastapi.responses import HTMLResponse
from pydantic import BaseModel, Field

from app.api.deps import SettingsDep
from app.services.reader_pages import static_page
from solvers.integrate.workprecision import load_results

router = APIRouter(tags=["work-precision"])
pages = APIRouter(include_in_schema=False)


class WorkPrecisionPublic(BaseModel):
    tolerances: list[float]
    samples: int
    error: str = Field(description="how the error of a run is measured")
    cases: list[dict[str, Any]] = Field(description="each case: id, t_end, note, reference")
    runs: list[dict[str, Any]] = Field(description="one per (case, method, tolerance): error, "
                                       "wall_s, rhs_calls, steps, ok")
    summary: dict[str, Any] = Field(description="per case: the Pareto table (best of ours "
                                    "and each reference at each error level, ratios), the "
                                    "default method and what each tolerance of it buys")


@router.get("/work-precision", response_model=WorkPrecisionPublic)
async def work_precision() -> dict:
    """Error against cost for every method on representative cases, six marble and two
    rubber (ours: DOP853 and Verner 9(8), with and without projection; scipy DOP853, LSODA,
    Radau; heyoka)."""
    try:
        return load_results()
    except FileNotFoundError:
        raise HTTPException(404, "no work-precision results: run "
                                 "`rolling bench work-precision`") from None


@pages.get("/work-precision")
async def work_precision_page(settings: SettingsDep) -> HTMLResponse:
    return HTMLResponse(static_page(settings.static_dir / "work-precision.html"))
