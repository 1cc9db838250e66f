"""The kernel cache as the server sees it: whether generated kernels can be written to it
(solvers/kernels/module_cache.py cache_dir: ROLLING_KERNEL_CACHE, else
~/.cache/rolling-hierarchy/kernels).

A cache that cannot be written (a read-only mount, a full disk, a path under a file, a
directory removed while the server runs) degrades the service, it does not stop it: the
kernels compile in memory in each process and the runs use the general kernels
(solvers/kernels/numba_cache.py), the background warm-up does not run (it would compile into a
cache nobody can read back), and /api/health says "degraded" with the reason. The check
writes a small file; it runs at start and then at most every PROBE_EVERY_S seconds, when
/api/health asks.
"""

from __future__ import annotations

import time

from solvers.kernels.module_cache import cache_dir, cache_probe

PROBE_EVERY_S = 10.0


class KernelCache:
    def __init__(self) -> None:
        self.path = ""
        self.reason: str | None = None
        self._checked = -float("inf")

    def check(self) -> str | None:
        """Probe the cache now: None when it takes a written file, else why not."""
        self.reason = cache_probe()
        self.path = str(cache_dir())
        self._checked = time.monotonic()
        return self.reason

    def recheck(self) -> None:
        """check() again when the last one is older than PROBE_EVERY_S."""
        if time.monotonic() - self._checked >= PROBE_EVERY_S:
            self.check()

    @property
    def degraded(self) -> bool:
        return self.reason is not None

    def public(self) -> dict:
        if self.reason is None:
            return {"state": "ok", "path": self.path, "message": ""}
        return {"state": "degraded", "path": self.path,
                "message": f"{self.reason}: kernels compile in memory in each worker and "
                           "runs use the general kernels (stats.field says which ran); no "
                           "background warm-up"}
