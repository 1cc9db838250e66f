"""The explorer: FastAPI app `app.main:app`, served by `rolling serve` (app.core.server:
uvicorn with bounds on what a client can hold; plain `uvicorn app.main:app` lacks them).

    /                 Tables 1 and 2 as in the paper, verdict marks, links to the cases
    /case/{id}        a case: claims with sources and verdicts, simulate panel, plots
    /api/...          JSON API (OpenAPI at /docs and /openapi.json)

CPU work runs in worker processes (app.core.pool); the lifespan below creates the pool,
starts the workers and, in the background, the verification of every claim.

Stopping (Ctrl-C, SIGTERM) takes a second or two, whatever is compiling: the first signal
kills the worker processes and the warm-up's process group at once (`_stop_now`), before
the server waits for its open requests (a prepare job compiling for a minute now fails at
once, 503) and before the lifespan's end, which waits until those processes are gone.
"""

from __future__ import annotations

import asyncio
import logging
import signal
import threading
from collections.abc import Callable
from contextlib import asynccontextmanager
from pathlib import Path

import anyio
from fastapi import FastAPI
from fastapi.openapi.docs import get_swagger_ui_html
from fastapi.responses import HTMLResponse
from starlette.middleware.trustedhost import TrustedHostMiddleware

from app import __version__
from app.api.main import api_router
from app.api.routes import guide, pages, poincare, reader, scenes, work_precision
from app.api.routes.pages import plotly_js
from app.core import compress, errors
from app.core.config import Settings, get_settings
from app.core.guards import CSP, HeadAsGet, HeaderLimit, RequestGuard, SecurityHeaders
from app.core.pool import WorkerPool
from app.services import jobs
from app.services.kernel_cache import KernelCache
from app.services.kernel_warmup import KernelWarmup
from app.services.page_cache import PageCache
from app.services.verdicts import VerdictStore
from catalogue.load import load_catalogue
from solvers.kernels.module_cache import degrade
from solvers.models.cases import build, initial_state, registry, table_case_ids

log = logging.getLogger("rolling")

DESCRIPTION = """
Knowledge base and explorer of a rigid body rolling without sliding on a plane and a
sphere, after A. V. Borisov & I. S. Mamaev, *The rolling motion of a rigid body on a plane
and a sphere. Hierarchy of dynamics*, Regular and Chaotic Dynamics 7(2), 2002.

Case ids contain a slash (`plane/chaplygin-ball`): `GET /api/cases/plane/chaplygin-ball`.
Bad input is a 422 whose `detail` names the field, the value and why. When every worker
is busy and the queue is full the answer is 503 with `Retry-After`.
"""


def _prepare() -> None:
    """Load the catalogue and the registry, off the event loop."""
    load_catalogue()
    registry()


def _validate_examples() -> None:
    """Validate every case's demo run, in a thread after the server answers: validation
    calls compiled functions (the support function, the fit on a sphere) whose first call
    loads them from numba's cache while holding the GIL, or on a fresh machine compiles
    them (tens of seconds on a loaded machine): the first page must not wait for that."""
    for cid, spec in registry().items():
        initial_state(build(cid, spec.example), spec.state)


async def _warm(pool: WorkerPool) -> None:
    try:
        await pool.prewarm()
    except Exception as exc:  # serve anyway: the first run will say what is wrong
        log.warning("warming a worker failed: %r", exc)


def _log_to_stderr(level: str) -> None:
    """The explorer's own log lines (verdict progress) on stderr beside uvicorn's."""
    if not log.handlers:
        handler = logging.StreamHandler()
        handler.setFormatter(logging.Formatter("%(levelname)s:     %(name)s: %(message)s"))
        log.addHandler(handler)
        log.propagate = False
    log.setLevel(level.upper())


def _stop_now(pool: WorkerPool, kernels: KernelWarmup) -> None:
    """Stop all computing at once: the warm-up's process group (SIGTERM; its compile
    processes included) and every worker process (SIGKILL: a compile in a worker cannot be
    interrupted, and nothing in a worker needs saving). In the event loop's thread."""
    kernels.stop()
    if pool.kill_all():
        log.info("stopping: worker processes killed")


STOP_SIGNALS = (signal.SIGINT, signal.SIGTERM)
# the stop signals this process received while serving (app/cli/serve.py's serve exits 128 + the
# first one: uvicorn's re-raise of it does nothing where the process was started with
# SIGINT ignored, as a shell's background job is, and the server then exited 0)
STOP_SIGNALS_SEEN: list[int] = []


def _on_stop_signal(stop: Callable[[], None]) -> Callable[[], None]:
    """Call `stop` in the event loop when SIGINT or SIGTERM arrives, then the handler that
    was there (uvicorn's, which first waits for the open requests, then ends the lifespan;
    a second Ctrl-C skips the lifespan's end). Only in the main thread (a server in a
    thread, as the tests' TestClient, gets no signals). Returns the undo."""
    if threading.current_thread() is not threading.main_thread():
        return lambda: None
    loop = asyncio.get_running_loop()
    installed = {}

    def make(prev):
        def handler(signum, frame):
            STOP_SIGNALS_SEEN.append(signum)
            if callable(prev):
                loop.call_soon_threadsafe(stop)
                prev(signum, frame)
            else:       # SIG_DFL, no server handler: stop now, then the signal's own effect
                stop()
                signal.signal(signum, signal.SIG_DFL)
                signal.raise_signal(signum)
        return handler

    for sig in STOP_SIGNALS:
        prev = signal.getsignal(sig)
        if prev == signal.SIG_IGN:
            continue
        installed[sig] = (prev, make(prev))
        signal.signal(sig, installed[sig][1])

    def undo() -> None:
        for sig, (prev, ours) in installed.items():
            if signal.getsignal(sig) is ours:
                signal.signal(sig, prev)
    return undo


@asynccontextmanager
async def lifespan(app: FastAPI):
    settings: Settings = app.state.settings
    _log_to_stderr(settings.log_level)
    kernels = KernelWarmup(settings.warmup_command)
    # a kernel cache that cannot be written: one warning here (the processes started
    # below inherit that it was given), no warm-up, the general kernels in every worker
    cache = app.state.kernel_cache = KernelCache()
    why = await anyio.to_thread.run_sync(cache.check)
    warm_kernels = settings.warm_kernels and why is None
    if why is not None:
        degrade("the kernel cache", why)
        kernels.message = ("not run: the kernel cache cannot be written; runs use the "
                           "general kernels, compiled in each worker")
    if warm_kernels:
        kernels.expect()    # "warming" from the first request
    # while the kernels compile, a new worker only imports (it would compile them too)
    # verifications (minutes each) hold at most all workers but one, and a quarter of the
    # queue: a burst of them leaves the runs a worker (app/services/verdicts.py)
    shares = {"verify": (max(1, settings.workers - 1), max(1, settings.queue_size // 4))}
    pool = WorkerPool(settings.workers, settings.queue_size, settings.retry_after_s,
                      warm=jobs.warm_imports if warm_kernels else jobs.warm, shares=shares)

    store = VerdictStore(table_case_ids(), settings.cache_dir)
    app.state.pool, app.state.verdicts, app.state.kernels = pool, store, kernels
    await anyio.to_thread.run_sync(_prepare)
    if settings.use_verdict_cache:
        await anyio.to_thread.run_sync(store.load_cache)
    if settings.verify_on_start:
        store.expect_checks()   # "checking" from the first request, while the workers warm

    async def compile_kernels() -> None:
        await kernels.run()
        if kernels.state != "done":
            return      # a failed warm-up: jobs.warm would compile everything in a worker
        pool.warm = jobs.warm      # now every kernel loads from the caches
        if settings.warm_workers:
            async with anyio.create_task_group() as tg:
                for _ in range(settings.workers):
                    tg.start_soon(_warm, pool)

    async def background() -> None:
        # the workers warm beside the validation (separate processes), so that /api/health
        # reports them "warming" from the first answer on: app.testing.wait_idle and
        # bench/load.py wait for an idle pool, which must not mean "not started yet"
        async with anyio.create_task_group() as tg:
            if settings.warm_workers:
                for _ in range(settings.workers):
                    tg.start_soon(_warm, pool)
            try:
                await pool.starting(_validate_examples)
            except Exception as exc:  # serve anyway: that case's run will say what is wrong
                log.warning("validating the cases' demo runs failed: %r", exc)
        if settings.precompress:
            paths = [plotly_js(), *compress.static_paths(settings.static_dir)]
            made = await anyio.to_thread.run_sync(app.state.assets.precompress, paths)
            if made:
                log.info("static files: %d compressed forms made", made)
        if settings.verify_on_start:
            # the checks run every case's kernels: after the warm-up compiled them, not
            # each worker compiling them again beside it
            await kernels.wait_done()
            await store.verify_all(pool, settings.verify_deadline_s)

    undo = _on_stop_signal(lambda: _stop_now(pool, kernels))
    try:
        async with anyio.create_task_group() as tg:
            pool.attach(tg)
            if warm_kernels:
                tg.start_soon(compile_kernels)
            tg.start_soon(background)
            yield
            _stop_now(pool, kernels)    # also when no signal came (a test, an embedding)
            tg.cancel_scope.cancel()
        with anyio.CancelScope(shield=True):
            await kernels.reap()        # none of the warm-up's processes is left behind
            await pool.close()          # nor a worker
    finally:
        undo()


def create_app(settings: Settings | None = None) -> FastAPI:
    settings = settings or get_settings()
    # docs_url=None: /docs is served below with Swagger UI from static/vendor (no CDN)
    app = FastAPI(title="rolling-hierarchy explorer", version=__version__,
                  description=DESCRIPTION, lifespan=lifespan, docs_url=None, redoc_url=None)
    app.state.settings = settings
    app.state.pages = PageCache()      # server-rendered pages, until their verdicts change
    errors.install(app)
    app.include_router(api_router)
    app.include_router(pages.router)
    app.include_router(reader.pages)
    app.include_router(poincare.pages)
    app.include_router(scenes.pages)
    app.include_router(work_precision.pages)
    app.include_router(guide.router)
    # static files compressed once (Brotli or gzip), the routes' answers by GZipMiddleware
    app.state.assets = compress.AssetCache(settings.cache_dir)
    app.mount("/static", compress.CompressedStaticFiles(
        directory=Path(settings.static_dir), assets=app.state.assets), name="static")
    compress.install(app, app.state.assets)
    # outermost last: headers on every answer (the guards' own included), then the Host
    # allow-list, HEAD as GET, and the checks of state-changing requests
    app.add_middleware(RequestGuard, max_body=settings.max_body_bytes,
                       allowed_origins=tuple(settings.allowed_origins))
    app.add_middleware(HeadAsGet)
    app.add_middleware(HeaderLimit, max_headers=settings.max_headers)
    app.add_middleware(TrustedHostMiddleware, allowed_hosts=settings.trusted_hosts())
    app.add_middleware(SecurityHeaders)

    @app.get("/docs", include_in_schema=False)
    async def docs() -> HTMLResponse:
        page = get_swagger_ui_html(
            openapi_url=app.openapi_url, title=f"{app.title} — API",
            swagger_js_url="/static/vendor/swagger-ui/swagger-ui-bundle.js",
            swagger_css_url="/static/vendor/swagger-ui/swagger-ui.css",
            swagger_favicon_url="/static/favicon.svg",
            swagger_ui_parameters={"validatorUrl": None, "defaultModelsExpandDepth": 0})
        # Swagger UI starts from an inline script: allowed on this page only
        page.headers["content-security-policy"] = CSP.replace(
            "script-src 'self'", "script-src 'self' 'unsafe-inline'")
        return page

    return app


app = create_app()
