"""Cancel a request's work when its client goes away.

Once the body has been read, the ASGI `receive` of a request only returns when the client
disconnects (`http.disconnect`). A watcher task waits for that and cancels the work, so a
worker process computing for a closed browser tab is killed at once (app.core.pool).

This needs the raw ASGI receive: Starlette's BaseHTTPMiddleware breaks it, so the app uses
no such middleware (pure ASGI middleware only).
"""

from __future__ import annotations

from collections.abc import Awaitable, Callable
from typing import TypeVar

import anyio
from starlette.requests import Request

T = TypeVar("T")


class ClientDisconnected(Exception):
    """The client closed the connection before the answer was ready."""


async def cancel_on_disconnect(request: Request, work: Callable[[], Awaitable[T]]) -> T:
    """Await `work()`; if the client disconnects first, cancel it and raise
    ClientDisconnected."""
    outcome: dict[str, object] = {}

    async def watch(scope: anyio.CancelScope) -> None:
        while True:
            message = await request.receive()
            if message["type"] == "http.disconnect":
                scope.cancel()
                return

    with anyio.CancelScope() as work_scope:
        async with anyio.create_task_group() as tg:
            tg.start_soon(watch, work_scope)
            try:
                outcome["value"] = await work()
            except Exception as exc:  # re-raised below, not wrapped in an ExceptionGroup
                outcome["error"] = exc
            finally:
                tg.cancel_scope.cancel()
    if "error" in outcome:
        raise outcome["error"]
    if "value" not in outcome:
        raise ClientDisconnected
    return outcome["value"]  # type: ignore[return-value]
