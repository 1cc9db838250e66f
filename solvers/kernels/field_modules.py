"""The modules of a case's generated field, in the kernel cache (module_cache.py): the field
itself (generate.py's text for the case's structure) and the loop kernel bound to it (the
generated integrator: loop_kernel.py's `rk_integrate` and rk.py's functions that call the
field). Each is named by the structure and the content hash of the sources
of solvers/kernels: any edit of them gives other names, never a stale module."""

from __future__ import annotations

import hashlib

from solvers.kernels import generate, loop_kernel, rk
from solvers.kernels.module_cache import bound_module, cached_module, sources_hash


def module_name(model: int, p, fold: bool = False) -> str:
    key = repr((generate.structure(model, p, fold), sources_hash()))
    return "gen_" + hashlib.sha256(key.encode()).hexdigest()[:20]


def generated(model: int, p, fold: bool = False):
    """The generated module of the case (written on first use, then loaded from the cache):
    it holds `field(p, y, dydt)` and `rhs(model, t, y, p, dydt)`."""
    return cached_module(module_name(model, p, fold),
                         lambda: generate.numba_source(model, p, fold))


def generated_integrator(model: int, p, fold: bool = False):
    """The loop kernel (loop_kernel.py, with rk.py's functions that call the field) bound
    to the case's generated field instead of the general `fields.rhs` (bound_module): the
    same code (tableau as data, dense output, projection, sections, statuses), every stage
    call the lean field, inlined. `rk_integrate` has the loop kernel's signature. One
    numba compile per structure (a long one), then numba's on-disk cache."""
    field_mod = generated(model, p, fold)
    name = f"rk{field_mod.__name__[3:]}_loops"
    return bound_module(name, (rk, loop_kernel.loop_module()), {"rhs": field_mod.rhs},
                        f"the loop kernel on the field {field_mod.__name__}")
