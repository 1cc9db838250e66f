"""Dependencies of the routes: the settings, the worker pool and the verdict store live
on app.state (created by the lifespan in app.main), one per running app."""

from typing import Annotated

from fastapi import Depends, Request

from app.core.config import Settings
from app.core.pool import WorkerPool
from app.services.verdicts import VerdictStore


def get_settings(request: Request) -> Settings:
    return request.app.state.settings


def get_pool(request: Request) -> WorkerPool:
    return request.app.state.pool


def get_verdicts(request: Request) -> VerdictStore:
    return request.app.state.verdicts


SettingsDep = Annotated[Settings, Depends(get_settings)]
PoolDep = Annotated[WorkerPool, Depends(get_pool)]
VerdictsDep = Annotated[VerdictStore, Depends(get_verdicts)]
