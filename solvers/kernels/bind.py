"""Kernel modules' compiled functions bound to other callees: the loop kernel (loop_kernel.py
with rk.py's functions that call the field) on a case's generated field, the ensemble loop
(ensemble.py) on such a loop kernel.

    bind_into(mod, (rk, loop), {"rhs": generated.rhs})

makes the module `mod` whose jitted functions are the modules' own code objects (the same
bytecode: numba builds the same IR from it, so on the same callee the same machine code),
each compiled anew with its global names looked up in `mod`: a copy of the modules'
namespaces in which `replace` (here the field) and their other jitted functions, bound in
turn, stand for the originals. So the loop is the same for every field, and nothing reads
or edits source text.

Why globals and not closures (a factory returning jitted closures over the field): numba
keys a cached closure by the pickled bytes of its cells, and a dispatcher pickles with a
uuid drawn anew in each process (numba/core/caching.py `_index_key`,
numba/core/dispatcher.py `_reduce_states`), so a closure over a jitted field would never
load from the on-disk cache in another process: each process would compile it again.

numba's cache finds a function's files by the file its code names (co_filename) and keys
it by its qualified name, signature and bytecode, which the bound functions share with the
originals: so their code objects name the module's own file, a short stub in the kernel
cache (module_cache.bound_module writes it: its docstring says what was bound), and numba
keeps their machine code beside it. Without a writable kernel cache the module is made in
memory, its code names no file, and numba compiles it in memory (numba_cache.py).
"""

from __future__ import annotations

import threading
import types

import numba
from numba.core.dispatcher import Dispatcher

_BIND = threading.Lock()
_BOUND = "__bound_from__"       # set on a module once its functions are bound


def stub_source(name: str, what: str) -> str:
    """The text of a bound module's file: only a docstring (the functions are bound into
    the module when it is loaded, bound_module)."""
    return f'"""{name}: {what} (made by solvers/kernels/bind.py)."""\n'


def jitted(module) -> dict:
    """The module's own jitted functions (name -> dispatcher), not those it imports."""
    return {k: v for k, v in vars(module).items()
            if isinstance(v, Dispatcher) and v.py_func.__module__ == module.__name__}


def bind_into(target, modules, replace: dict) -> None:
    """Fill the module `target` with the names of `modules` (a module or a sequence of
    them, later ones taking precedence), `replace` standing for some of them, and the
    modules' jitted functions compiled anew over target's namespace (module docstring).
    Done once per target (later calls return at once)."""
    modules = tuple(modules) if isinstance(modules, list | tuple) else (modules,)
    with _BIND:
        if getattr(target, _BOUND, None) is not None:
            return
        space = vars(target)
        for module in modules:
            for k, v in vars(module).items():
                if not (k.startswith("__") and k.endswith("__")):
                    space[k] = v
        space.update(replace)
        filename = getattr(target, "__file__", None) or f"<bound kernels {target.__name__}>"
        own = {k: d for module in modules for k, d in jitted(module).items()}
        for k, disp in own.items():
            if k in replace:
                continue
            f = disp.py_func
            fn = types.FunctionType(f.__code__.replace(co_filename=filename), space,
                                    f.__name__, f.__defaults__, f.__closure__)
            fn.__qualname__ = f.__qualname__
            fn.__doc__ = f.__doc__
            fn.__kwdefaults__ = f.__kwdefaults__
            opts = {o: x for o, x in disp.targetoptions.items() if o != "nopython"}
            space[k] = numba.njit(cache=True, **opts)(fn)
        setattr(target, _BOUND, ", ".join(m.__name__ for m in modules))

