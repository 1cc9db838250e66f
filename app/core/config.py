"""Every setting of the explorer in one place (environment variables ROLLING_*).

    ROLLING_PORT=8080 ROLLING_WORKERS=1 rolling serve

The defaults are what `rolling serve` / `./dev serve` run with on a 2-core machine.
"""

from functools import cache
from pathlib import Path

from pydantic import Field, field_validator
from pydantic_settings import BaseSettings, SettingsConfigDict

ROOT = Path(__file__).resolve().parents[2]


class Settings(BaseSettings):
    model_config = SettingsConfigDict(env_prefix="ROLLING_", extra="ignore", frozen=True)

    host: str = "127.0.0.1"
    port: int = Field(8000, ge=0, le=65535)
    # CPU work (simulations, scenes, verification) runs in this many worker processes;
    # the event loop only parses requests and ships bytes.
    workers: int = Field(2, ge=1, le=64)
    # requests that may wait for a free worker; one more gets 503 + Retry-After
    queue_size: int = Field(8, ge=0, le=1000)
    retry_after_s: int = Field(2, ge=1)
    # hard wall-clock limit of one run in a worker (queueing time not counted): the
    # worker is killed when it is reached
    deadline_s: float = Field(20.0, gt=0)
    # step budget of one run (compiled integrators): a run that needs more stops there
    # with status "budget" and returns what it computed
    max_steps: int = Field(2_000_000, ge=100)
    max_samples: int = Field(20_000, ge=2)
    max_frames: int = Field(600, ge=2)
    # verification of the catalogue's claims
    verify_on_start: bool = True      # compute every verdict in the background at start
    verify_deadline_s: float = Field(300.0, gt=0)
    # verdicts are cached here, keyed by a hash of everything they depend on
    cache_dir: Path = Path.home() / ".cache" / "rolling-hierarchy"
    use_verdict_cache: bool = True
    warm_workers: bool = True         # start the worker processes (numba caches) at start
    # compile the kernels in the background (python -m solvers.warmup, a subprocess of the
    # app): the explorer serves at once (app/services/kernel_warmup.py)
    warm_kernels: bool = True
    # without the background warm-up: the caches hold what the warm-up compiles (the
    # tests run after ./dev test's warm-up), so only other kernels are prepared before a
    # request's deadline starts (app/services/kernel_prepare.py); false: every kind of
    # job is prepared on its first use
    kernels_warm: bool = False
    # the warm-up's command line (JSON list in ROLLING_WARMUP_COMMAND); None: python -m
    # solvers.warmup --progress. The tests give a scripted one that prints the same lines.
    warmup_command: list[str] | None = None
    # make the compressed forms of the static files at start (app.core.compress)
    precompress: bool = True
    # request bodies above this many bytes get 413 before anything parses them
    max_body_bytes: int = Field(1 << 20, ge=1024)
    # what one client may hold (app.core.server): open connections (at most half
    # the file limit), the request line and headers in bytes and in fields, the time a
    # request head may take to arrive and the longest gap inside a body, the idle time of
    # a keep-alive connection, and how long a connection refused mid-body lingers; at the
    # cap, a head or body silent for stall_grace_s is stalled and evicted first
    max_connections: int = Field(1000, ge=8, le=100_000)
    max_header_bytes: int = Field(64 * 1024, ge=4096, le=1 << 20)
    max_headers: int = Field(100, ge=8, le=10_000)
    header_timeout_s: float = Field(10.0, gt=0, le=3600)
    body_timeout_s: float = Field(10.0, gt=0, le=3600)
    # longer than a client pool's idle expiry (httpx: 5 s): with equal times the server
    # closes a connection while the client sends its next request on it (bench/load.py
    # --hostile finds unanswered requests then, none at this value); at the cap an idle one
    # is evicted before anything that holds a request
    keep_alive_s: float = Field(20.0, gt=0, le=3600)
    linger_s: float = Field(1.0, ge=0, le=60)
    stall_grace_s: float = Field(1.0, gt=0, le=60)
    # Host header allow-list (DNS rebinding): None = the loopback names when bound to a
    # loopback address, any host otherwise; a list (JSON in ROLLING_ALLOWED_HOSTS) replaces it
    allowed_hosts: list[str] | None = None
    # origins besides the server's own whose pages may POST (JSON in ROLLING_ALLOWED_ORIGINS)
    allowed_origins: list[str] = Field(default_factory=list)
    static_dir: Path = Path(__file__).resolve().parents[1] / "static"   # inside the package
    # the built user guide served at /guide/ (`mkdocs build` from docs/); None: site/ at the
    # repository root. Not built: /guide/ says how to build it (app/api/routes/guide.py)
    guide_dir: Path | None = None
    log_level: str = "info"
    # the public address of a published copy (https://example.org/rolling): the Cite boxes
    # and the errata's exports give it instead of the address the page was asked for
    public_url: str | None = None

    @field_validator("public_url")
    @classmethod
    def _no_trailing_slash(cls, v: str | None) -> str | None:
        return v.rstrip("/") or None if v else None

    def trusted_hosts(self) -> list[str]:
        if self.allowed_hosts is not None:
            return list(self.allowed_hosts)
        if self.host in LOOPBACK:
            return sorted(LOOPBACK)
        return ["*"]


LOOPBACK = {"127.0.0.1", "localhost", "::1", "[::1]"}


@cache
def get_settings() -> Settings:
    return Settings()
