"""The kernel cache: the directory where generated kernel modules are written
(ROLLING_KERNEL_CACHE), the content hash of the kernels' sources that names them, and the
loading of those modules (written once, atomically; in memory where the disk cannot take
them).

A cache that cannot be written (a read-only mount, a full disk, a directory removed while
the server runs) is not an error: `degrade()` records what could not be used, with one
warning per process, and the kernels are compiled in memory for the process instead
(numba's side: solvers/kernels/numba_cache.py). /api/health reports it (the server's own
probe: app/services/kernel_cache.py).

The generated fields' modules are solvers/kernels/field_modules.py's; the small kernels'
are solvers/kernels/small.py's. What is compiled, for which request, is asked of
solvers/compile_state.py.
"""

from __future__ import annotations

import contextlib
import hashlib
import importlib.util
import linecache
import logging
import os
import sys
import tempfile
import threading
import types
from functools import cache
from pathlib import Path

log = logging.getLogger("rolling.kernels")
_KERNELS = Path(__file__).resolve().parent

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


def cache_dir() -> Path:
    """ROLLING_KERNEL_CACHE, else ~/.cache/rolling-hierarchy/kernels (generated code is not
    written into the package: an installed package may be read-only). Made when missing;
    a directory that cannot be made is returned all the same (what reads it finds
    nothing, what writes it falls back: cached_module, cache_probe)."""
    d = os.environ.get("ROLLING_KERNEL_CACHE")
    base = Path(d) if d else Path.home() / ".cache" / "rolling-hierarchy" / "kernels"
    try:
        base.mkdir(parents=True, exist_ok=True)
    except OSError as exc:
        degrade(f"the kernel cache {base}", exc)
    return base


def cache_probe() -> str | None:
    """None when the kernel cache and its __pycache__ (numba's files for the generated
    modules) take a written file now, else why not (a read-only mount, a full disk, a
    path under a file)."""
    base = cache_dir()
    try:
        for d in (base, base / "__pycache__"):
            d.mkdir(parents=True, exist_ok=True)
            with tempfile.TemporaryFile(dir=d) as f:
                f.write(b"probe")
                f.flush()
    except OSError as exc:
        return f"{base} cannot be written ({type(exc).__name__}: {exc.strerror or exc})"
    return None


_PROBED: list[str | None] = []


def disk_cache_ok() -> bool:
    """Whether this process writes its generated kernels to the disk cache (probed once
    per process). When not, a run that would compile a kernel per case structure (the
    small kernels, the generated field) runs the general kernels instead, which compile
    once per process whatever the case: the kernel cache degrades, the runs go on."""
    if not _PROBED:
        why = cache_probe()
        _PROBED.append(why)
        if why is not None:
            degrade("the kernel cache", why)
    return _PROBED[0] is None


@cache
def sources_hash() -> str:
    """The content hash of every source file of solvers/kernels: the kernels' code, the
    generator of the fields and of the small kernels, and the operations they share. It
    names every generated module (module_name, small.module_name) and stamps numba's
    cache of the kernels of solvers/kernels (numba_cache.py), so an edit of any of them
    compiles anew, with no version number to bump by hand."""
    h = hashlib.sha256()
    for f in sorted(_KERNELS.glob("*.py")):
        h.update(f.name.encode())
        h.update(f.read_bytes())
    return h.hexdigest()[:16]


_LOADED: dict[str, object] = {}


def cached_module(name: str, source):
    """The module `name` of cache_dir(): loaded once per process; on first use anywhere
    its text `source()` is written there (atomically: a concurrent process or thread sees
    all of it or nothing). Registered in sys.modules, so other generated modules (the
    small kernels' shared operations) import it by name."""
    mod = _LOADED.get(name)
    if mod is not None:
        return mod
    path = cache_dir() / f"{name}.py"
    text = None
    try:
        if not path.exists():
            text = source()
            tmp = path.with_suffix(f".{os.getpid()}.{threading.get_ident()}.tmp")
            try:
                tmp.write_text(text)
                os.replace(tmp, path)
            except OSError:
                with contextlib.suppress(OSError):
                    tmp.unlink(missing_ok=True)
                raise
        spec = importlib.util.spec_from_file_location(name, path)
        mod = importlib.util.module_from_spec(spec)
        sys.modules[name] = mod
        spec.loader.exec_module(mod)
    except OSError as exc:      # not written (read-only, full) or gone since: in memory
        degrade(f"the generated kernels' sources in {path.parent}", exc)
        mod = _memory_module(name, text if text is not None else source())
    _LOADED[name] = mod
    return mod


def _memory_module(name: str, text: str):
    """The module `name` made from its text without a file: numba finds no place to cache
    its functions and compiles them in memory (solvers/kernels/numba_cache.py). The text is
    put in linecache, so that tracebacks and inspect show it."""
    filename = f"<generated kernel {name}>"
    linecache.cache[filename] = (len(text), None, text.splitlines(True), filename)
    mod = types.ModuleType(name)
    mod.__file__ = filename
    sys.modules[name] = mod
    exec(compile(text, filename, "exec"), mod.__dict__)
    return mod


def bound_module(name: str, module, replace: dict, what: str):
    """The module `name` of cache_dir() holding the jitted functions of `module` (a module
    or a sequence of them) compiled over `replace` (solvers/kernels/bind.py: the same code
    objects, other callees; no source text is read or edited). Its file is a stub saying
    `what` it holds, beside which numba caches the machine code."""
    # lazy: numba, imported by the first bound module, not by what only reads the cache's
    # directory (the Taylor backend's disk cache, the server's probe)
    from solvers.kernels import bind

    mod = cached_module(name, lambda: bind.stub_source(name, what))
    bind.bind_into(mod, module, replace)
    return mod
