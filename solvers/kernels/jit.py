"""One place that decides how kernels are compiled."""

from pathlib import Path

import numba
from numba.core import caching

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


if _PackageStampedLocator not in caching.CacheImpl._locator_classes:
    caching.CacheImpl._locator_classes.insert(0, _PackageStampedLocator)

# cache=True writes the machine code next to the sources (__pycache__), so a second
# process loads it instead of compiling. error_model="numpy": 1/0 gives inf, no
# Python exception path in the hot loop; fastmath stays off (we compare to round-off).
kernel = numba.njit(cache=True, error_model="numpy", nogil=True)
