"""The Butcher tableaux the small kernels bake in as literals (solvers/kernels/small.py).

The tableaux are data of solvers/integrate (a layer above this one): that layer hands them
in with `set_provider(fn)`, fn() -> {name: (A, c, b, E, P, meth)} (integrator.method_arrays).
`tableaux_stamp` hashes their exact doubles into the names of the kernels that bake them,
so a changed coefficient gives another module, never a stale cached one.

The loop kernel's tableau loops are not written out as straight-line code for the generated
integrators: that saved little time per rhs call on that opt-in path for twice the compile
(docs/performance.md)."""

from __future__ import annotations

import hashlib

import numpy as np

_PROVIDER = None
_TABLEAUX: dict = {}       # the provider's answer, asked once


def set_provider(fn) -> None:
    """fn() -> {name: (A, c, b, E, P, meth)}: the tableaux the kernels may bake."""
    global _PROVIDER
    _PROVIDER = fn
    _TABLEAUX.clear()


def baked_tableaux(names) -> dict:
    """{name: arrays} for the named tableaux (a name the provider lacks is an error)."""
    if names and not _TABLEAUX:
        if _PROVIDER is None:
            raise ValueError("no tableaux provided (solvers.integrate.integrator sets them)")
        _TABLEAUX.update(_PROVIDER())
    unknown = [n for n in names if n not in _TABLEAUX]
    if unknown:
        raise ValueError(f"unknown tableaux {unknown}; known: {sorted(_TABLEAUX)}")
    return {n: _TABLEAUX[n] for n in names}


def tableaux_stamp(tabs: dict) -> str:
    h = hashlib.sha256()
    for name in sorted(tabs):
        h.update(name.encode())
        for a in tabs[name]:
            a = np.ascontiguousarray(a)
            h.update(str((a.dtype, a.shape)).encode())
            h.update(a.tobytes())
    return h.hexdigest()[:16]
