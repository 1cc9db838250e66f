"""One place that decides how kernels are compiled.

A kernel cache that cannot be written (a read-only mount, a full disk, a directory removed
while the server runs) is not an error: numba then finds no place for a function's cache
(no locator), or fails to save or load one, and the function is compiled in memory for
this process instead (`_enable_caching`, `_TolerantCache`). `degrade()` records what
could not be used, with one warning per process; /api/health reports it (the server's
own probe: app/api/routes/health.py).
"""

import logging
import os
from pathlib import Path

import numba
from numba.core import caching
from numba.core import dispatcher as _dispatcher

log = logging.getLogger("rolling.kernels")

# what could not use the disk cache in this process: what -> why (the first reason)
DEGRADED: dict[str, str] = {}
# set once a warning was logged, inherited by the processes started after it (the
# server's workers and warm-up): the log says it once, not once per process
WARNED_ENV = "ROLLING_KERNEL_CACHE_WARNED"


def degrade(what: str, exc: BaseException | str) -> None:
    """Record that `what` works without the disk cache here (compiled in memory, or the
    general kernels); the first record of a process logs one warning, unless a parent
    process has said it already."""
    reason = exc if isinstance(exc, str) else f"{type(exc).__name__}: {exc}"
    first = not DEGRADED
    DEGRADED.setdefault(what, reason)
    if first and not os.environ.get(WARNED_ENV):
        os.environ[WARNED_ENV] = "1"
        log.warning("the kernel cache cannot be used (%s: %s): kernels compile in memory "
                    "in each process, and runs use the general kernels", what, reason)

_DIR = Path(__file__).resolve().parent


class _PackageStampedLocator(caching.InTreeCacheLocator):
    """numba stamps a cached function with its own file only, so after an edit of
    fields.py a cached caller in rk.py would keep running the old inlined field. Stamp
    every kernel with all solvers/kernels/*.py files instead: any edit recompiles."""

    @classmethod
    def from_function(cls, py_func, py_file):
        if Path(py_file).resolve().parent != _DIR:
            return None
        return super().from_function(py_func, py_file)

    def __init__(self, py_func, py_file):
        super().__init__(py_func, py_file)
        # NUMBA_CACHE_DIR wins, as for numba's own locators: a cold measurement
        # (bench/warmup_cost.py) or a read-only checkout points it at an empty directory
        if numba.config.CACHE_DIR:
            self._cache_path = str(Path(numba.config.CACHE_DIR)
                                   / self.get_suitable_cache_subpath(py_file))

    def get_source_stamp(self):
        return tuple((f.name, f.stat().st_mtime_ns, f.stat().st_size)
                     for f in sorted(_DIR.glob("*.py")))


class _ReadOnlyInTreeLocator(caching.InTreeCacheLocator):
    """The __pycache__ of a generated module that can be read but not written (a filled
    kernel cache on a read-only mount): what it holds loads; a new compile stays in memory
    (its save fails, _TolerantCache). Last of the locators: only where no other has a
    place. Not for solvers/kernels/*.py, whose stamp is the package's."""

    @classmethod
    def from_function(cls, py_func, py_file):
        if Path(py_file).resolve().parent == _DIR:
            return None
        return super().from_function(py_func, py_file)

    def ensure_cache_path(self):
        if not os.access(self.get_cache_path(), os.R_OK | os.X_OK):
            raise OSError(f"{self.get_cache_path()} cannot be read")


if _PackageStampedLocator not in caching.CacheImpl._locator_classes:
    caching.CacheImpl._locator_classes.insert(0, _PackageStampedLocator)
if _ReadOnlyInTreeLocator not in caching.CacheImpl._locator_classes:
    caching.CacheImpl._locator_classes.append(_ReadOnlyInTreeLocator)

# cache=True writes the machine code next to the sources (__pycache__), so a second
# process loads it instead of compiling. error_model="numpy": 1/0 gives inf, no
# Python exception path in the hot loop; fastmath stays off (we compare to round-off).
kernel = numba.njit(cache=True, error_model="numpy", nogil=True)


class _TolerantCache(caching.FunctionCache):
    """numba's cache of one function, where a failure to read or write the disk (full,
    read-only, removed) costs a compile, not the run."""

    def load_overload(self, sig, target_context):
        try:
            return super().load_overload(sig, target_context)
        except OSError as exc:
            degrade("numba's cache of the compiled kernels (reading)", exc)
            return None

    def save_overload(self, sig, data):
        try:
            super().save_overload(sig, data)
        except OSError as exc:
            degrade("numba's cache of the compiled kernels (writing)", exc)


def _enable_caching(self) -> None:
    """Dispatcher.enable_caching (cache=True): the tolerant cache, or none at all when no
    locator has a place for it (numba raises RuntimeError 'no locator available')."""
    try:
        self._cache = _TolerantCache(self.py_func)
    except RuntimeError as exc:
        degrade("numba's cache of the compiled kernels", exc)
        self._cache = caching.NullCache()
    except OSError as exc:
        degrade("numba's cache of the compiled kernels", exc)
        self._cache = caching.NullCache()


_dispatcher.Dispatcher.enable_caching = _enable_caching
