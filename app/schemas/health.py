from pydantic import BaseModel, Field


class PoolPublic(BaseModel):
    workers: int
    queue_size: int
    running: int
    waiting: int
    warming: int = Field(description="worker processes starting (loading the kernels)")
    completed: int
    rejected: int
    cancelled: int
    timed_out: int
    crashed: int = Field(0, description="worker processes that died in mid-job")
    replaced: int = Field(0, description="worker processes started warm after a death "
                          "or a deadline")
    alive: int = Field(0, description="worker processes alive now (none before the first "
                       "job or warm-up)")
    start_failures: int = Field(0, description="starts of a worker process that failed "
                                "(no access to the interpreter, out of file handles or "
                                "memory)")
    start_error: str = Field("", description="why the last start failed, while no start "
                             "has succeeded since (status is then degraded)")
    retry_in_s: float | None = Field(None, description="seconds until the pool tries to "
                                     "start a worker again")


class VerificationStatus(BaseModel):
    state: str = Field(description="idle | running | done | unavailable | failed")
    cases_done: int
    cases_total: int
    message: str = ""
    updated: float | None = Field(None, description="unix time of the last verdict")


class LimitsPublic(BaseModel):
    deadline_s: float = Field(description="wall-clock limit of one run in a worker")
    max_steps: int = Field(description="step budget of one run")
    max_samples: int
    max_frames: int


class ConnectionsPublic(BaseModel):
    """What the server's connection guards did since it started (app.core.server)."""
    open: int = Field(description="connections open now")
    peak: int = Field(description="most connections open at once")
    max_connections: int
    evicted: int = Field(description="idle or stalled connections closed to make room")
    evicted_by: dict[str, int] = Field(
        default_factory=dict, description="the evictions by rank, in the order they are "
        "chosen: stalled (a head or body silent for stall_grace_s, or timed out), slowest "
        "(the request arriving that began the longest ago, not a fast one), idle (keep-alive), "
        "young_body (a fast body or a lingering answer)")
    refused: int = Field(description="connections closed at once: the cap was reached")
    header_timeouts: int
    body_timeouts: int
    header_too_large: int
    lingered: int = Field(description="connections closed with a request body unread")


class KernelsPublic(BaseModel):
    """The compile of the kernels in the background (app/services/kernel_warmup.py)."""
    state: str = Field(description="off (no warm-up in this server: the caches are "
                       "assumed warm) | starting | running | done | failed | "
                       "stopped (with the server)")
    message: str = ""
    parts_done: int = Field(description="warm-up parts compiled (the general kernels, the "
                            "ensembles, one part per case structure)")
    parts_total: int
    warming_cases: list[str] = Field(description="cases whose kernels are still compiling: "
                                     "a run of one compiles its kernel before it starts")
    warming_parts: list[str]
    estimate_s: float = Field(description="seconds one case structure took to compile here "
                              "(a default before the first one finished)")
    elapsed_s: float | None = Field(None, description="seconds since the warm-up started "
                                    "(its duration once done)")
    prepared: list[dict] = Field(default_factory=list, description="the last compiles a "
                                 "request waited for before its deadline started: keys, "
                                 "seconds")


class KernelCachePublic(BaseModel):
    """Whether generated kernels can be written to the kernel cache
    (app/services/kernel_cache.py)."""
    state: str = Field(description="ok | degraded (the cache cannot be written: kernels "
                       "compile in memory in each worker, runs use the general kernels)")
    path: str = Field(description="the kernel cache's directory (ROLLING_KERNEL_CACHE)")
    message: str = ""


class HealthPublic(BaseModel):
    status: str = Field(description="ok, or degraded: the service answers, but a part of "
                        "it works in a lesser way (`degraded` names which)")
    degraded: list[str] = Field(default_factory=list, description="the parts that are "
                                "degraded: kernel_cache, workers")
    version: str
    kernel_cache: KernelCachePublic
    pool: PoolPublic
    limits: LimitsPublic
    verification: VerificationStatus
    kernels: KernelsPublic
    connections: ConnectionsPublic | None = Field(
        None, description="null when the app runs under a server other than rolling serve")
