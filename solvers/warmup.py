"""Compile every kernel specialization once so later processes load it from numba's cache.

Run by the README's commands (`./dev ...`) after installation: `python -m solvers.warmup`.

The general kernels (one specialization per state dimension and method kind: projection,
sections, scenes, Poincare maps and the reference run on them), and the small kernels of
every case structure (solvers/kernels/small.py: one compile per *structure*, the set of
its nonzero parameter slots, and tableau), which `simulate()` runs for a plain run
(field="auto" or "generated"): dop853's, the default method (WARM_SMALL; compile times
in docs/performance.md); vern9's, which only method="auto" at tight tolerances or an explicit
vern9 run takes, compiles on its first use (the explorer does it before the request's
deadline starts: app/api/routes/simulate.py), or here with --all. They are compiled as tasks of
parallel processes (ROLLING_WARMUP_JOBS, default the number of CPUs, at most 4): the
general kernels are one task, each structure another; a structure whose small kernels are
already in the cache is skipped. The big generated integrators (rk.py on a generated field,
several times a small kernel's compile per structure, and their ensemble twins) are not
compiled here: no default route needs them (`python -m solvers.warmup --generated` still
compiles them).
"""

import multiprocessing as mp
import os
import time
from concurrent.futures import ProcessPoolExecutor, as_completed

import numpy as np

from solvers import compile_state as cs
from solvers.errors import InputError
from solvers.integrate.ensemble import integrate_ensemble
from solvers.integrate.integrator import SMALL_METHODS
from solvers.kernels import generate
from solvers.kernels import layout as L
from solvers.kernels.integrals import ENERGY
from solvers.maps.poincare import (
    MapSpec,
    integral_spread,
    map_model,
    starts_for,
    trace_checked_all,
)
from solvers.models.cases import build, registry
from solvers.models.derivatives import field_jacobian, integral_gradient
from solvers.models.kinematics import scene
from solvers.simulate import compiled_methods, simulate, symmetric_methods


def _general() -> None:
    seen = set()
    for cid, case in registry().items():
        key = (case.body == "flat",)
        if key in seen:
            continue
        seen.add(key)
        for method in compiled_methods():
            r = simulate(cid, case.example, case.state, 0.01, method=method, samples=3,
                         field="general")
            simulate(cid, case.example, case.state, 0.01, method=method, samples=3,
                     project=True, field="general")
        simulate(cid, case.example, case.state, 0.01, method=symmetric_methods()[0],
                 samples=3, step=0.005)
        m = build(cid, case.example)
        y = np.asarray(r.state[0])
        field_jacobian(m.model, m.p, y)
        integral_gradient(ENERGY, m.model, m.p, y)
        # a scene (POST /api/scene, the teaching scenes): the scene model's run and the
        # planner's kinematics on the model's read-only parameters, which no run above
        # calls (without this, the first scene after the warm-up compiled them in its request)
        scene(cid, case.example, case.state, 1e-3, frames=2)


# Structures compiled besides the cases' examples: the work-precision benchmark's
# unbalanced ball runs with gravity (bench/work_precision.py), and method "auto" reads its
# front there (solvers/integrate/auto.py), so it is measured and run on the same field.
EXTRA = (("plane/unbalanced-ball", {"g": 1.0}),)


def warm_targets() -> list[tuple[str, dict]]:
    return [(cid, dict(case.example)) for cid, case in registry().items()] + \
        [(cid, {**registry()[cid].example, **over}) for cid, over in EXTRA]


def pending(generated: bool = False,
            all_structures: bool = False) -> dict[tuple, list[tuple[str, dict]]]:
    """structure -> the (case, parameters) whose small kernels (generated: the big
    generated integrators) are not compiled yet for some method (solvers/compile_state.py
    is_compiled): every case's example parameters and EXTRA (all_structures: every one of
    them, compiled or not)."""
    out: dict[tuple, list] = {}
    for cid, params in warm_targets():
        m = build(cid, params)
        if m.model not in generate.GENERATED_MODELS:
            continue
        if all_structures:
            ready = False
        elif generated:
            ready = cs.is_compiled(cs.generated_key(m.model, m.p))
        else:
            ready = all(cs.is_compiled(cs.small_key(m.model, m.p, meth))
                        for meth in _small_methods())
        if not ready:
            out.setdefault(cs.structure(m.model, m.p), []).append((cid, params))
    return out


WARM_SMALL = ("dop853",)


def _small_methods() -> tuple:
    return SMALL_METHODS if os.environ.get("ROLLING_WARMUP_ALL") else WARM_SMALL


def _compile(target, method: str, kind: str, **over) -> str:
    """Compile the kernel of kind `kind` that a request of the case (an id, with its
    example parameters, or (id, parameters)) with `method` and `over` needs, by
    solvers/compile_state.py, and check that it is compiled."""
    case_id, params = (target, None) if isinstance(target, str) else target
    case = registry()[case_id]
    params = case.example if params is None else params
    req = cs.request(case_id, params, case.state, method=method, **over)
    keys = cs.plan(req)
    cs.compile(keys, req)
    assert [k[0] for k in keys] == [kind] and all(map(cs.is_compiled, keys)), keys
    return case_id


def compile_small(target) -> str:
    """Compile the small kernels of a case (an id, with its example parameters, or (id,
    parameters)) for every warmed method into the on-disk cache."""
    for method in _small_methods():
        case_id = _compile(target, method, "small")
    return case_id


def compile_generated(target) -> str:
    """Compile the generated integrator of a case (an id, with its example parameters, or
    (id, parameters)) and its ensemble twin into the on-disk cache (one compile serves
    every tableau: they are data)."""
    case_id = _compile(target, "dop853", "generated", field="generated", project=True)
    case = registry()[case_id]
    params = case.example if isinstance(target, str) else target[1]
    m = build(case_id, params)
    integrate_ensemble(m.model, m.p, [case.state] * 2, [0.0, 0.01], generated=True,
                       workers=2)
    return case_id


def _jobs() -> int:
    env = os.environ.get("ROLLING_WARMUP_JOBS")
    return max(1, int(env)) if env else max(1, min(4, os.cpu_count() or 1))


def _task(what) -> str:
    """One unit of the parallel warm-up: the general kernels, the compiled ensembles on the
    general field, or a case's structure (("generated", target): its big generated
    integrator and ensemble twin)."""
    if what == GENERAL:
        _general()
        return what
    if what == ENSEMBLES:
        warm_ensembles(generated=False)
        return what
    if isinstance(what, tuple) and what[0] == "generated":
        return compile_generated(what[1])
    return compile_small(what)


GENERAL = "general kernels"
ENSEMBLES = "ensembles"


def part_name(what) -> str:
    """What a task compiles, in words (the progress lines and the explorer's pages)."""
    if what == GENERAL:
        return GENERAL
    if what == ENSEMBLES:
        return "compiled ensembles (Poincare maps)"
    if isinstance(what, tuple) and what[0] == "generated":
        return f"generated integrator of {part_name(what[1])}"
    if isinstance(what, str):
        return what
    # (case, parameters): say what differs from the case's example
    example = registry()[what[0]].example
    differs = ", ".join(f"{k} = {v:g}" for k, v in what[1].items() if example.get(k) != v)
    return f"{what[0]} ({differs})" if differs else what[0]


def parts(generated: bool = False, only_pending: bool = True) -> list[tuple]:
    """The warm-up's tasks, each with the cases it serves: the general kernels, one task
    per structure whose small kernels are not compiled yet (only_pending=False: every
    structure of warm_targets(), compiled or not), and the ensembles (generated: the big
    generated integrators instead, whose ensemble twins come after them)."""
    groups = pending(all_structures=not only_pending)
    # the general kernels first (the longest task), the ensembles next: warm() runs them in
    # the general part's process right after it (they need its rk_integrate: compiled in
    # another process beside it they compiled it a second time; last in the queue they
    # compiled alone at the end, the longest wait of all: see docs/performance.md), while
    # the other processes take the structures
    plan = [(GENERAL, [])]
    if not generated:   # with generated, warm() runs them after all the tasks (their
        plan.append((ENSEMBLES, []))    # generated twins need the generated integrators)
    plan += [(cases[0], sorted({c for c, _ in cases})) for cases in groups.values()]
    if generated:
        plan += [(("generated", cases[0]), sorted({c for c, _ in cases}))
                 for cases in pending(generated=True,
                                      all_structures=not only_pending).values()]
    return plan


def warm(jobs: int | None = None, generated: bool = False, progress=None) -> float:
    """Compile what is not in the caches yet, `jobs` tasks at a time. progress(event): a
    dict, first {"event": "plan", "total": n, "parts": [{"name", "cases"}]}, then
    {"event": "done", "part", "seconds", "done", "total"} as each task finishes (the
    explorer's progress bar and its pages read these: app/services/kernel_warmup.py)."""
    t0 = time.perf_counter()
    plan = parts(generated)
    todo = [what for what, _ in plan]
    report = progress or (lambda event: None)
    report({"event": "plan", "total": len(todo),
            "parts": [{"name": part_name(w), "cases": c} for w, c in plan]})
    done = 0

    def finished(what, seconds):
        nonlocal done
        done += 1
        report({"event": "done", "part": part_name(what), "seconds": round(seconds, 1),
                "done": done, "total": len(todo)})

    # one unit of work per part, but the ensembles in the general part's unit (above)
    units = [[what] for what in todo if what != ENSEMBLES]
    if ENSEMBLES in todo:
        next(u for u in units if u[0] == GENERAL).append(ENSEMBLES)
    jobs = min(jobs or _jobs(), len(units))
    if jobs > 1:
        # spawn: fresh interpreters (a forked numba/LLVM state is not safe to reuse); the
        # general kernels are one more task, so no core waits for them
        with ProcessPoolExecutor(jobs, mp_context=mp.get_context("spawn")) as ex:
            futures = [ex.submit(_timed, unit) for unit in units]
            for f in as_completed(futures):
                for what, seconds in f.result():
                    finished(what, seconds)
    else:
        for unit in units:
            for what, seconds in _timed(unit):
                finished(what, seconds)
    if generated:
        warm_ensembles(generated)
    return time.perf_counter() - t0


def _timed(unit: list) -> list[tuple]:
    """Run the unit's parts one after the other in this process: [(part, seconds)]."""
    out = []
    for what in unit:
        t = time.perf_counter()
        _task(what)
        out.append((what, time.perf_counter() - t))
    return out


def warm_ensembles(generated: bool = False) -> None:
    """The compiled parallel ensemble (solvers/kernels/ensemble.py) on the general field
    (the CLI's Poincare maps and the dask sweeps on several threads) and a tiny map per
    model as the explorer runs it (one thread: the serial kernel per trajectory), so that
    the first Poincare map of a server does not compile in a request; generated: the
    generated twins too (compiled by compile_generated)."""
    seen = set()
    for cid, params in warm_targets():
        case = registry()[cid]
        m = build(cid, params)
        if (m.model,) not in seen:     # the general field: one specialization per model
            seen.add((m.model,))
            # two trajectories on two threads: the parallel loop (the CLI's maps and the
            # sweeps; one thread, as the explorer's map jobs, runs the serial kernel)
            integrate_ensemble(m.model, m.p, [case.state] * 2, [0.0, 0.01], generated=False,
                               workers=2)
            _tiny_map(cid, params)
        if not generated or m.model not in generate.GENERATED_MODELS:
            continue
        key = generate.structure(m.model, m.p)
        if key in seen:
            continue
        seen.add(key)
        integrate_ensemble(m.model, m.p, [case.state] * 2, [0.0, 0.01], generated=True,
                           workers=2)


def _tiny_map(case_id: str, params: dict) -> None:
    """One crossing of a Poincare map of the case, as POST /api/poincare runs it
    (app/services/poincare_jobs.py): besides the ensemble, a map calls the integrals'
    kernels on the model's read-only parameters (integral_series; model_integral, which
    places the starts on the level), each its own numba specialization, which a bare
    ensemble call does not compile (without this, a map after the warm-up compiled them in
    its request)."""
    try:
        model = map_model(case_id, params)
    except InputError:          # the flat-base cases: no map
        return
    if model.model != L.MODEL_FULL:
        return
    spec = MapSpec(energy=1.0, points=1, max_steps=500)
    try:    # sampled on the level, as the route does (on_energy_level: model_integral)
        starts = starts_for(model, spec, trajectories=1)
    except InputError:      # no point of this level: the case's own state
        starts = starts_for(model, spec, states=[registry()[case_id].state])
    for tr in trace_checked_all(model, starts, spec, workers=1):
        integral_spread(model, tr)


if __name__ == "__main__":
    import sys

    if "--all" in sys.argv:     # inherited by the spawned processes
        os.environ["ROLLING_WARMUP_ALL"] = "1"
    # --progress: one JSON line per event on stdout (the explorer starts this in the
    # background and draws its progress bar from them)
    hook = None
    if "--progress" in sys.argv:
        import json

        def hook(event):
            print(json.dumps(event), flush=True)
    print(f"kernels ready in {warm(generated='--generated' in sys.argv, progress=hook):.1f} s",
          flush=True)

