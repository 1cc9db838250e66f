"""Every use of numba's private caching internals, in one place (tests/test_numba_cache.py
checks that they still exist and do what is used here; a numba upgrade that moves them
fails there first).

  - the locators (numba.core.caching.CacheImpl._locator_classes): the kernels of
    solvers/kernels are stamped with the content hash of all their sources
    (module_cache.sources_hash), not with their own file's time: numba stamps a cached
    function with its own file only, so after an edit of fields.py a cached caller in
    rk.py would keep running the old inlined field; and a generated module's __pycache__
    that can be read but not written still loads;
  - the cache of one function (Dispatcher.enable_caching): a failure to read or write the
    disk costs a compile, not the run (module_cache.degrade records it);
  - whether a dispatcher's on-disk index holds machine code for this machine
    (`holds`: solvers/compile_state.py's test of a compiled kernel).
"""

from __future__ import annotations

import os
from pathlib import Path

import numba
from numba.core import caching
from numba.core import dispatcher as _dispatcher

from solvers.kernels.module_cache import degrade, sources_hash

_DIR = Path(__file__).resolve().parent


class _PackageStampedLocator(caching.InTreeCacheLocator):
    """The kernels of solvers/kernels, stamped with the content hash of all their sources:
    any edit of any of them recompiles every one."""

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
        return sources_hash()


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


def install() -> None:
    """Put the locators and the tolerant cache in place (idempotent): before any kernel
    with cache=True is defined (solvers/kernels/jit.py calls it on import)."""
    locators = caching.CacheImpl._locator_classes
    if _PackageStampedLocator not in locators:
        locators.insert(0, _PackageStampedLocator)
    if _ReadOnlyInTreeLocator not in locators:
        locators.append(_ReadOnlyInTreeLocator)
    _dispatcher.Dispatcher.enable_caching = _enable_caching


def holds(dispatcher) -> bool:
    """Whether the jitted function is compiled in this process, or its on-disk index has
    an entry for this machine's code generator (a file of a wiped or another machine's
    cache does not count). False for what is not a caching numba dispatcher."""
    try:
        if dispatcher.signatures:
            return True
        magic = dispatcher.targetctx.codegen().magic_tuple()
        return any(k[1] == magic for k in dispatcher._cache._cache_file._load_index())
    except Exception:   # not a dispatcher, no cache, an unreadable index: a run compiles it
        return False
