"""GET /api/tables/plane and /api/tables/sphere: Tables 1 and 2 as laid out in the paper."""

from typing import Literal

from fastapi import APIRouter

from app.api.deps import VerdictsDep
from app.schemas.tables import TablePublic
from app.services import views

router = APIRouter(tags=["tables"])


@router.get("/tables/{table_id}", response_model=TablePublic)
async def get_table(table_id: Literal["plane", "sphere"], verdicts: VerdictsDep) -> dict:
    """Rows, columns and the grid of cells (a merged cell once, with its colspan and the
    cases it spans), with the paper's shading and a verdict mark per checkable cell."""
    return views.table(table_id, verdicts.by_claim(), verdicts.pending())
