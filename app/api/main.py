"""All API routes under /api, one router per topic."""

from fastapi import APIRouter

from app.api.routes import (
    cases,
    catalogue,
    errata,
    health,
    observables,
    poincare,
    reader,
    scenes,
    simulate,
    tables,
    verify,
    work_precision,
)
from app.schemas.common import GUARD_RESPONSES, PROBLEM_RESPONSES

# every error answer is a Problem (app.core.errors), 422 included: documented once here so
# that FastAPI does not advertise its own HTTPValidationError shape
# (and 400, which the Host allow-list answers to any request)
api_router = APIRouter(prefix="/api", responses={**PROBLEM_RESPONSES,
                                                 400: GUARD_RESPONSES[400]})
for module in (health, reader, cases, tables, simulate, observables, verify, errata, catalogue,
               poincare, scenes, work_precision):
    api_router.include_router(module.router)
