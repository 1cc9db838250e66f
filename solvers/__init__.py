"""Rigid bodies rolling on a plane and on a sphere (Borisov & Mamaev 2002): the models of
the paper's Tables 1-2, integrators that hold their first integrals, three-dimensional
point maps, and checks of the paper's claims.

Everything a user calls is importable from here::

    simulate, SimulationResult, methods     run a case and read the result
    cases, CaseSpec                         the cases, their parameters and example values
    poincare, MapSpec, PoincareResult       a point map on one energy level
    sweep, parameter_tasks, energy_tasks,   many maps over a parameter or energy levels,
    MapTask, SweepResult, DaskSettings      on dask.distributed
    verify                                  check the paper's claims
    InputError                              the error raised for bad input

The names are loaded on first use (PEP 562 `__getattr__`, as scipy does): ``import
solvers.errors`` or any light submodule does not import numba and the integrators. Two
names are also submodules, ``solvers.simulate`` (solvers/simulate.py) and
``solvers.verify`` (the package solvers/verify/), which code across the project imports
as modules (``import solvers.verify.params as params``). Python's import system binds a
submodule to its package's attribute of the same name, so these two attributes are the
submodules, made callable: ``solvers.simulate(...)`` calls
``solvers.simulate.simulate(...)`` and ``solvers.verify(...)`` calls
``solvers.verify.run.verify(...)``; ``inspect.signature`` and ``inspect.unwrap`` give the
function.

Examples
--------
>>> import solvers
>>> spec = solvers.cases()["plane/chaplygin-ball"]
>>> res = solvers.simulate(spec.id, spec.example, spec.state, t_end=1.0, samples=3)
>>> res.status, res.drift("energy") < 1e-10
('ok', True)
"""

import importlib
import sys
import types

# typing.TYPE_CHECKING without importing typing (which costs more than the rest of this
# file): static tools read the name TYPE_CHECKING as true
TYPE_CHECKING = False
if TYPE_CHECKING:   # for static tools (type checkers, griffe/mkdocstrings): the real names
    from solvers.errors import InputError
    from solvers.maps.poincare import MapSpec, PoincareResult, poincare
    from solvers.maps.sweeps import (
        DaskSettings,
        MapTask,
        SweepResult,
        energy_tasks,
        parameter_tasks,
        sweep,
    )
    from solvers.models.cases import CaseSpec, cases
    from solvers.simulate import SimulationResult, methods, simulate
    from solvers.verify.run import verify

# public name -> the module that defines it
_HOME = {
    "simulate": "solvers.simulate",
    "SimulationResult": "solvers.simulate",
    "methods": "solvers.simulate",
    "cases": "solvers.models.cases",
    "CaseSpec": "solvers.models.cases",
    "poincare": "solvers.maps.poincare",
    "MapSpec": "solvers.maps.poincare",
    "PoincareResult": "solvers.maps.poincare",
    "sweep": "solvers.maps.sweeps",
    "parameter_tasks": "solvers.maps.sweeps",
    "energy_tasks": "solvers.maps.sweeps",
    "MapTask": "solvers.maps.sweeps",
    "SweepResult": "solvers.maps.sweeps",
    "DaskSettings": "solvers.maps.sweeps",
    "verify": "solvers.verify.run",
    "InputError": "solvers.errors",
}
# a literal list, for static tools (griffe reads it); the names of _HOME
__all__ = [
    "CaseSpec",
    "DaskSettings",
    "InputError",
    "MapSpec",
    "MapTask",
    "PoincareResult",
    "SimulationResult",
    "SweepResult",
    "cases",
    "energy_tasks",
    "methods",
    "parameter_tasks",
    "poincare",
    "simulate",
    "sweep",
    "verify",
]

# the public names that are also submodules of this package: submodule -> its function
_CALLABLE = {"simulate": "solvers.simulate", "verify": "solvers.verify.run"}


class _CallableModule(types.ModuleType):
    """A submodule named like the function it stands for: calling it calls the function,
    looked up at each call (so a test's monkeypatch of `solvers.simulate.simulate` holds)."""

    @property
    def __wrapped__(self):
        short = self.__name__.rpartition(".")[2]
        return getattr(importlib.import_module(_CALLABLE[short]), short)

    def __call__(self, *args, **kwargs):
        return self.__wrapped__(*args, **kwargs)


class _Package(types.ModuleType):
    """This package's module type: when the import system binds the submodule
    solvers.simulate or solvers.verify to the package's attribute, it becomes callable."""

    def __setattr__(self, name, value):
        if name in _CALLABLE and isinstance(value, types.ModuleType) \
                and value.__name__ == f"{self.__name__}.{name}":
            value.__class__ = _CallableModule
        super().__setattr__(name, value)


sys.modules[__name__].__class__ = _Package
for _name in _CALLABLE:   # already imported (a reload of this package): made callable now
    if (_sub := sys.modules.get(f"{__name__}.{_name}")) is not None:
        setattr(sys.modules[__name__], _name, _sub)
del _name, _sub


def __getattr__(name: str):
    home = _HOME.get(name)
    if home is None:
        raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
    if name in _CALLABLE:   # the submodule; importing it binds it here, made callable
        return importlib.import_module(f"{__name__}.{name}")
    value = getattr(importlib.import_module(home), name)
    globals()[name] = value
    return value


def __dir__() -> list[str]:
    return sorted({*globals(), *__all__})
