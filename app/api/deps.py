"""Dependencies of the routes: the settings, the worker pool and the verdict store live
on app.state (created by the lifespan in app.main), one per running app.

They are `async def` on purpose: FastAPI runs a plain `def` dependency in the thread pool,
and three hops through a pool that the page routes also use made /api/health wait behind
them under load (bench/load.py)."""

from typing import Annotated

from fastapi import Depends, HTTPException, Request

from app.core.config import Settings
from app.core.guards import is_json, not_json
from app.core.pool import WorkerPool
from app.services.page_cache import PageCache
from app.services.verdicts import VerdictStore


async def get_settings(request: Request) -> Settings:
    return request.app.state.settings


async def get_pool(request: Request) -> WorkerPool:
    return request.app.state.pool


async def get_verdicts(request: Request) -> VerdictStore:
    return request.app.state.verdicts


async def get_pages(request: Request) -> PageCache:
    return request.app.state.pages


SettingsDep = Annotated[Settings, Depends(get_settings)]
PoolDep = Annotated[WorkerPool, Depends(get_pool)]
VerdictsDep = Annotated[VerdictStore, Depends(get_verdicts)]
PagesDep = Annotated[PageCache, Depends(get_pages)]


async def json_only(request: Request) -> None:
    """Every POST route is JSON, with a body or without one (POST /api/verify/{id} takes {}):
    a request without Content-Type: application/json is 415 there, as the guard answers
    one with a body (app.core.guards), after routing (an unknown route or method stays 404
    or 405)."""
    ctype = request.headers.get("content-type")
    if not is_json(ctype or ""):
        raise HTTPException(415, not_json(ctype))


JSON_ONLY = Depends(json_only)
