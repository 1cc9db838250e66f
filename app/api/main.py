"""All API routes under /api, one router per topic."""

from fastapi import APIRouter

from app.api.routes import (
    cases,
    catalogue,
    errata,
    health,
    poincare,
    scenes,
    simulate,
    tables,
    verify,
    work_precision,
)
from app.schemas.common import PROBLEM_RESPONSES

# every error answer is a Problem (app.core.errors), 422 included: documented once here so
# that FastAPI does not advertise its own HTTPValidationError shape
api_router = APIRouter(prefix="/api", responses=PROBLEM_RESPONSES)
for module in (health, cases, tables, simulate, verify, errata, catalogue, poincare, scenes,
               work_precision):
    api_router.include_router(module.router)
