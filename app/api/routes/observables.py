"""POST /api/observables: named quantities along the states of a run (a rubber case page's
plots of the no-spin constraint, |gamma| - 1 and the case's integrals), computed by
solvers/models/observables.py in a worker process."""

from __future__ import annotations

import numpy as np
from fastapi import APIRouter, Request
from fastapi.responses import Response

from app.api.deps import JSON_ONLY, PoolDep, SettingsDep
from app.core.disconnect import cancel_on_disconnect
from app.schemas.common import (
    BUSY_RESPONSES,
    DEADLINE_RESPONSES,
    GUARD_RESPONSES,
    PROBLEM_RESPONSES,
)
from app.schemas.observables import ObservablesRequest, ObservablesResponse
from app.services.jobs import dumps
from solvers.errors import InputError
from solvers.models.cases import build, get_case
from solvers.models.observables import RUBBER, rubber_integrals, series

router = APIRouter(tags=["simulate"])


def default_names(case_id: str, params: dict) -> list[str]:
    """The constraint and |gamma| - 1, then the case's integrals beyond the energy."""
    return ["spin", "gamma_norm_defect", *rubber_integrals(case_id, params)]


def resolve(req: ObservablesRequest) -> tuple[dict, list[str]]:
    """The parameters (the case's example under the request's) and the names, checked."""
    spec = get_case(req.case)
    if len(spec.state) != 6:
        raise InputError(f"case = {req.case!r}: its state is not (M, gamma)")
    params = {**spec.example, **req.params}
    build(req.case, params)
    names = req.names if req.names is not None else default_names(req.case, params)
    bad = [n for n in names if n not in RUBBER]
    if bad:
        raise InputError(f"names = {bad}: not quantities of solvers/models/observables.py; "
                         f"known: {', '.join(RUBBER)}")
    return params, names


def observables_json(case_id: str, params: dict, rows: list, names: list[str]) -> dict:
    """The named quantities along `rows` (a worker process)."""
    out = series(build(case_id, params), np.asarray(rows, dtype=float), names)
    return {"case": case_id, "names": names, "labels": {n: RUBBER[n][0] for n in names},
            "series": {n: [float(v) if np.isfinite(v) else None for v in out[n]]
                       for n in names}}


@router.post("/observables", dependencies=[JSON_ONLY], response_model=ObservablesResponse,
             responses={**PROBLEM_RESPONSES, **GUARD_RESPONSES, **BUSY_RESPONSES,
                        **DEADLINE_RESPONSES})
async def observables(req: ObservablesRequest, request: Request, pool: PoolDep,
                      settings: SettingsDep) -> Response:
    """The no-spin constraint (omega, gamma), |gamma| - 1 and the case's integrals beyond
    the energy (solvers/models/observables.py RUBBER) along the given states."""
    params, names = resolve(req)        # bad input answers here, before any work is queued
    d = await cancel_on_disconnect(request, lambda: pool.run(
        observables_json, req.case, params, req.state, names, deadline=settings.deadline_s))
    return Response(dumps(d), media_type="application/json")
