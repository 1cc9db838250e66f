"""`rolling serve`: the web explorer on uvicorn with the server's bounds."""

import os
from typing import Annotated

import typer

from app.cli.common import check_workers, interrupted


def serve(
    host: Annotated[str | None, typer.Option(help="address (default 127.0.0.1)")] = None,
    port: Annotated[int | None, typer.Option(help="port (default 8000)")] = None,
    workers: Annotated[int | None, typer.Option(help="worker processes for simulations "
                                                "(default 2)")] = None,
):
    """Start the web explorer (FastAPI + uvicorn) on http://127.0.0.1:8000."""
    check_workers(workers)
    if workers is not None:
        os.environ["ROLLING_WORKERS"] = str(workers)
    if host is not None:   # the app derives its Host allow-list from the address it serves
        os.environ["ROLLING_HOST"] = host
    # lazy: pydantic-settings (the server's settings), only for `rolling serve`, not at
    # the CLI's start
    from app.core.config import get_settings

    s = get_settings()
    host, port = host or s.host, port or s.port
    typer.echo(f"rolling-hierarchy explorer on http://{host}:{port}/  (API docs: /docs)")
    # lazy: uvicorn with bounds on what a client can hold (app.core.server) and the
    # explorer itself (app.main: FastAPI, the solvers), only for `rolling serve`
    from app.core.server import run
    from app.main import STOP_SIGNALS_SEEN

    try:
        run(host, port, log_level=s.log_level)
    except KeyboardInterrupt:
        # Ctrl-C, re-raised by uvicorn once it has shut down: the lifespan has killed the
        # workers and the warm-up (app/main.py), nothing is left to clean up, and the
        # interpreter's own teardown (numba's and LLVM's compiled code) takes seconds more,
        # and the explorer should stop at once. SIGTERM ends the process the same way.
        interrupted(130)
    if STOP_SIGNALS_SEEN:
        # stopped by a signal whose re-raise did nothing: the process started with SIGINT
        # ignored (a background job of a shell), which uvicorn restores before re-raising
        interrupted(128 + STOP_SIGNALS_SEEN[0])
