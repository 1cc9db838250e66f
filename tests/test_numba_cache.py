"""numba's private caching internals, which solvers/kernels/numba_cache.py alone touches:
they exist in the installed numba and do what that module relies on (a numba upgrade that
moves them fails here first), and `holds` reads numba's own index."""

import os
import subprocess
import sys
import textwrap
from pathlib import Path

from numba.core import caching
from numba.core import dispatcher as numba_dispatcher

from solvers.kernels import numba_cache, rk
from solvers.kernels.module_cache import sources_hash

ROOT = Path(__file__).resolve().parents[1]


def test_the_locators_and_the_tolerant_cache_are_installed_once():
    numba_cache.install()
    numba_cache.install()
    locators = caching.CacheImpl._locator_classes
    assert locators[0] is numba_cache._PackageStampedLocator
    assert locators[-1] is numba_cache._ReadOnlyInTreeLocator
    assert locators.count(numba_cache._PackageStampedLocator) == 1
    assert locators.count(numba_cache._ReadOnlyInTreeLocator) == 1
    assert numba_dispatcher.Dispatcher.enable_caching is numba_cache._enable_caching


def test_a_kernel_is_stamped_with_the_content_hash_of_the_kernels_sources():
    cache = rk.stages._cache
    assert isinstance(cache, numba_cache._TolerantCache)
    locator = cache._impl.locator
    assert isinstance(locator, numba_cache._PackageStampedLocator)
    assert locator.get_source_stamp() == sources_hash()


def test_holds_is_false_for_what_is_not_a_caching_dispatcher():
    assert numba_cache.holds(len) is False
    assert numba_cache.holds(None) is False


PROBE = textwrap.dedent('''
    import sys
    from solvers.kernels import module_cache, numba_cache
    import solvers.kernels.jit  # noqa: F401  (installs the cache)

    src = "import numba\\n\\n@numba.njit(cache=True)\\ndef f(x):\\n    return x + 1\\n"
    mod = module_cache.cached_module("holds_probe", lambda: src)
    before = numba_cache.holds(mod.f)
    if sys.argv[1] == "call":
        assert mod.f(1) == 2
    print(before, numba_cache.holds(mod.f))
''')


def _probe(tmp_path: Path, what: str) -> str:
    env = {**os.environ, "PYTHONPATH": str(ROOT), "ROLLING_KERNEL_CACHE": str(tmp_path)}
    env.pop("NUMBA_CACHE_DIR", None)
    out = subprocess.run([sys.executable, "-c", PROBE, what], cwd=ROOT, env=env,
                         capture_output=True, text=True, timeout=300)
    assert out.returncode == 0, out.stderr[-2000:]
    return out.stdout.split()[-2:]


def test_holds_reads_numbas_index_on_disk(tmp_path):
    """Not compiled in a fresh cache; compiled in the process that called it; compiled in
    a later process (numba's index on disk, nothing called); not once the index is gone."""
    assert _probe(tmp_path, "call") == ["False", "True"]
    assert _probe(tmp_path, "look") == ["True", "True"]
    for f in (tmp_path / "__pycache__").glob("holds_probe*"):
        f.unlink()
    assert _probe(tmp_path, "look") == ["False", "False"]
