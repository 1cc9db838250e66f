"""What is compiled: the one owner of the compiled kernels' state. Three questions:

  plan(request) -> keys     the kernels a simulate request needs, from the request alone;
  is_compiled(key) -> bool  whether a key's kernel is compiled, in this process or in the
                            on-disk caches for this machine;
  compile(keys, request)    compile (or load) them, each on a tiny run of the request.

The warm-up (solvers/warmup.py), the explorer's prepare jobs (app/services/jobs.py, whose
routes decide when to prepare: app/services/kernel_prepare.py) and the tests ask here, and
nothing keeps a file saying what is compiled: the answer is read from numba's own index of
the kernel (solvers/kernels/numba_cache.py `holds`: a wiped or another machine's cache
reads as not compiled) and from the Taylor backend's disk cache. What names a compiled
kernel, and so invalidates it, is the content hash of the kernels' sources
(solvers/kernels/module_cache.py sources_hash) with the tableau's for a small kernel.

Keys (tuples: /api/health lists the prepared ones):
  ("small", model, slots, method)        a plain run's small kernel (solvers/kernels/small.py)
  ("generated", model, slots)            the loop kernel on the generated field (generated
                                         = True with a projection; one compile per
                                         structure: the tableau is data)
  ("general", model, method, project, fixed)   the general loop kernel (the collocation
                                         kernel for a symmetric method)
  ("taylor", structure, k > 0, precision, tol)   heyoka's integrator (taylor_backend)
slots: the nonzero parameter slots of the case (its structure).

A run of method "taylor" compiles heyoka's integrator of its case structure for the
precision and the tol it runs in: taylor_backend.run picks them from rtol and the length
of the WHOLE run (choose_precision, snap_tol), so a tiny run would compile another one
(rtol 1e-15: double over 1 time unit, long double over 100). A run of method "auto"
(solvers/integrate/auto.py) runs its choice and, beside it, a check run of the same
method looser by auto.CHECK_LOOSER (auto.plan): those two rungs are fixed by the request.
A tighter round, when the estimate misses the request, runs at a tolerance computed from
the measured estimate, which no plan knows before the run (a Taylor run compiled then
says so: stats "compiled"). The Runge-Kutta kernels do not depend on the tolerance
(compensated summation is a run-time flag of the same kernel), so their rungs name only
the method.
"""

from __future__ import annotations

import numpy as np

from solvers.integrate import auto, collocation, tableaux, taylor_backend
from solvers.integrate.integrator import SMALL_METHODS, small_module
from solvers.kernels import field_modules, gauss, generate, loop_kernel, numba_cache
from solvers.kernels import layout as L
from solvers.models.cases import build
from solvers.simulate import simulate

TAYLOR = "taylor"
SMALL, GENERATED, GENERAL = "small", "generated", "general"
MIN_RTOL = 1e-16     # simulate's smallest rtol (solvers/simulate.py)


def structure(model: int, p) -> tuple:
    """(model code, nonzero parameter slots): what a small kernel or a generated field is
    compiled for (generate.structure without folded values)."""
    return generate.structure(model, p)[:2]


def small_key(model: int, p, method: str) -> tuple:
    return (SMALL, *structure(model, p), method)


def generated_key(model: int, p) -> tuple:
    return (GENERATED, *structure(model, p))


def request(case_id: str, params: dict, state, *, method: str = "dop853", **over) -> dict:
    """A simulate request as plan() and compile() read it (the explorer's requests are
    dicts of SimulateRequest's fields): simulate()'s defaults, `over` on top."""
    return {"case": case_id, "params": dict(params), "state": list(state), "t_end": 1.0,
            "method": method, "rtol": 1e-10, "atol": 1e-12, "project": False, "step": None,
            "field": "auto", "precision": None, "allow_any_inertia": False, **over}


def rungs(case_id: str, model, method: str, rtol: float, t_end: float | None, *,
          project: bool = False, step=None, precision: str | None = None) -> list[dict]:
    """The distinct runs (method, tol, precision) whose compiled code a run of `method`
    needs, in the order it needs them (module doc). model: the case's built Model; t_end:
    the run's length (read by "taylor" and "auto" only)."""
    if method == TAYLOR:
        prec = precision or taylor_backend.choose_precision(rtol, t_end)
        taylor_backend.check_precision(prec)
        return [{"method": TAYLOR, "tol": taylor_backend.snap_tol(rtol), "precision": prec}]
    if method != "auto":
        return [{"method": method, "tol": rtol, "precision": None}]
    choice = auto.choose(case_id, model.model, rtol, t_end, project, step, precision)
    seen, out = set(), []
    for r in auto.plan(choice, t_end):
        key = (r["method"], r["tol"] if r["method"] == TAYLOR else None, r["precision"])
        if key not in seen:
            seen.add(key)
            out.append({"method": r["method"], "tol": r["tol"], "precision": r["precision"]})
    return out


def _model(request: dict):
    model = request.get("_model")
    if model is None:
        model = build(request["case"], request["params"],
                      allow_any_inertia=request.get("allow_any_inertia", False))
    return model


def _request_rungs(request: dict) -> list[dict]:
    # only the Taylor rungs depend on the run's length (a teaching scene's check names none)
    method = request["method"]
    t_end = float(request["t_end"]) if method in (TAYLOR, "auto") else None
    return rungs(request["case"], _model(request), method, float(request["rtol"]), t_end,
                 project=bool(request["project"]), step=request.get("step"),
                 precision=request.get("precision"))


def _key(request: dict, model, rung: dict) -> tuple:
    """The key of one rung of the request (integrator.is_plain decides small or general)."""
    m = rung["method"]
    if m == TAYLOR:
        return (TAYLOR, *taylor_backend.cache_key(model.model, model.p, rung["precision"],
                                                  rung["tol"]))
    project = bool(request["project"])
    fixed = request.get("step") is not None
    plain = request.get("field", "auto") != "general" and not project and not fixed
    if plain and m in SMALL_METHODS and model.model in generate.GENERATED_MODELS:
        return small_key(model.model, model.p, m)
    if request.get("field") == "generated" and model.model in generate.GENERATED_MODELS \
            and m in tableaux.METHODS:
        return generated_key(model.model, model.p)
    return (GENERAL, model.model, m, project, fixed)


def plan(request: dict) -> list[tuple]:
    """The keys of the kernels a simulate request runs (a dict of SimulateRequest's fields,
    "_model" optional), from the request alone; methods "taylor" and "auto": one per rung.
    Planning "auto" reads the measured front and imports heyoka: not for an event loop."""
    model = _model(request)
    return list(dict.fromkeys(_key(request, model, r) for r in _request_rungs(request)))


def _structure_p(model: int, slots, k_positive: bool = True) -> np.ndarray:
    """A parameter vector of the structure (ones on its slots): the kernels of a structure
    are the same for every value of its parameters (the sign of k aside, for Taylor)."""
    p = np.zeros(L.N_PARAMS)
    p[list(slots)] = 1.0
    if not k_positive and L.CURV in slots:
        p[L.CURV] = -1.0
    return p


def is_compiled(key: tuple) -> bool:
    """Whether the key's kernel is compiled here or in the on-disk caches (numba's index
    for this machine; the Taylor backend's stored integrators)."""
    kind = key[0]
    if kind == SMALL:
        _, model, slots, method = key
        return numba_cache.holds(small_module(model, _structure_p(model, slots), method).run)
    if kind == GENERATED:
        _, model, slots = key
        mod = field_modules.generated_integrator(model, _structure_p(model, slots))
        return numba_cache.holds(mod.rk_integrate)
    if kind == GENERAL:
        method = key[2]
        kern = gauss.gauss_integrate if method in collocation.METHODS else loop_kernel.rk_integrate
        return numba_cache.holds(kern)
    if kind == TAYLOR:
        (model, slots, _), k_positive, precision, tol = key[1:]
        return taylor_backend.ready(model, _structure_p(model, slots, k_positive), precision,
                                    tol)
    raise ValueError(f"unknown kernel key {key!r}")


def _tiny(request: dict, t_end: float, **over):
    """The request run over t_end with 2 samples (what compiles its kernels)."""
    r = {**request, **over}
    return simulate(r["case"], r["params"], r["state"], t_end, method=r["method"],
                    rtol=r["rtol"], atol=r["atol"], samples=2, project=r["project"],
                    max_steps=1000, allow_any_inertia=r.get("allow_any_inertia", False),
                    step=r.get("step"), field=r.get("field", "auto"),
                    precision=r.get("precision"))


def compile(keys, request: dict) -> int:
    """Compile (or load) the kernels `keys` of a simulate request (plan(request) names
    them), each on a tiny run of that request, which also compiles what every run of it
    calls around the kernel (the invariants): a Taylor rung's heyoka integrator, stored on
    disk for whichever process runs the request (a check rung tighter than simulate's
    smallest rtol is compiled directly), a Runge-Kutta rung's kernel on a run of two
    samples (a fixed step fits twice in it). A rung that fails (bad input) is left to the
    request itself to report. Returns how many of the keys are compiled now."""
    wanted = set(keys)
    try:
        model = _model(request)
        todo = [(r, _key(request, model, r)) for r in _request_rungs(request)]
    except Exception:   # the request's own run reports it
        return 0
    done = set()
    for rung, key in todo:
        if key not in wanted or key in done:
            continue
        try:
            if rung["method"] == TAYLOR and rung["tol"] < MIN_RTOL:
                taylor_backend.compiled(model.model, model.p, rung["precision"], rung["tol"])
            elif rung["method"] == TAYLOR:     # rtol = the compiled tol (snap_tol keeps it)
                _tiny(request, 1e-6, method=TAYLOR, precision=rung["precision"], step=None,
                      rtol=rung["tol"], atol=rung["tol"])
            else:
                step = request.get("step")
                _tiny(request, 2.0 * step if step else 1e-6, method=rung["method"],
                      precision=rung["precision"])
            done.add(key)
        except Exception:   # the request's own run reports it
            pass
    return len(done)
