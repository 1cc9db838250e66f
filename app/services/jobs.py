"""The functions that run inside worker processes (app.core.pool).

Each takes plain data (a dict made from a request schema) and returns bytes ready to send
or plain data, so the event loop only copies bytes: encoding a 20,000-sample run as JSON
takes tens of milliseconds, which would stall every other request if done in the loop.
Domain errors (solvers.errors.InputError) travel back pickled and become 422 answers.
"""

from __future__ import annotations

import csv
import io
import os

from app.services.payloads import arrow_bytes, csv_header, dumps, finite, json_bytes
from app.services.worker_run import lower_priority, run_request
from solvers.verify import verify


def warm() -> int:
    """Import the solvers and load the compiled kernels from numba's cache: one short run
    of every case, so that no request pays for a first call (a noticeable wait on a sphere).
    Only once the kernels are compiled (the warm-up done): before, `warm_imports`."""
    lower_priority()
    # lazy: numba and the kernels, imported at the worker's lower priority, not at its start
    # (unpickling a job of this module)
    from solvers.models.cases import registry
    from solvers.simulate import simulate

    for cid, case in registry().items():   # the generated kernels too (field="auto")
        simulate(cid, case.example, case.state, 0.01, samples=3)
    return warm_imports()


def warm_imports() -> int:
    """A worker started while the kernel warm-up still compiles (app/services/
    kernel_warmup.py): the imports only, no run, so that it compiles nothing the warm-up
    is compiling; the routes prepare what a request needs (kernel_prepare.py)."""
    lower_priority()
    # lazy: pyarrow, in a worker, not at the server's start: the Arrow answer's first use
    # would wait for its imports
    import pyarrow  # noqa: F401

    # lazy: numba, the kernels and the scenes' kinematics, imported at the worker's lower
    # priority, not at its start (unpickling a job of this module)
    import solvers.models.kinematics
    import solvers.simulate  # noqa: F401

    return os.getpid()


def prepare_kernels(req: dict, keys: list[tuple] | None = None) -> int:
    """Compile (or load) the kernels `keys` of a simulate request, each on a tiny run of it
    (solvers/compile_state.py compile; no request pays a compile inside its deadline; the
    route runs this without a deadline: app/services/kernel_prepare.py). The route passes
    the keys it planned (kernel_prepare.simulate_keys), so a request is planned once;
    without them (a teaching scene's check) they are planned here. A request that fails
    (bad input) is left to its own run to report. Returns how many kernels are ready."""
    lower_priority()
    # lazy: solvers.compile_state (with auto's measured front and the Taylor backend), not
    # at the server's start, which imports this module for the jobs' names
    from solvers import compile_state

    if keys is None:
        try:
            keys = compile_state.plan(req)
        except Exception:   # the request's own run reports it
            return 0
    return compile_state.compile(keys, req)


def prepare_scene(req: dict) -> int:
    """The kernels of a scene (the scene model's compiled run), on a tiny run."""
    lower_priority()
    # lazy: the scenes' kinematics (solvers.models.kinematics), not at the server's start,
    # which imports this module for the jobs' names
    from solvers.models.kinematics import scene

    try:
        scene(req["case"], req["params"], req["state"], 1e-3, frames=2,
              rtol=min(req["rtol"], 1e-8), atol=min(req["atol"], 1e-10), max_steps=1000,
              allow_any_inertia=req["allow_any_inertia"])
    except Exception:   # the request's own run reports it
        return 0
    return 1


def prepare_scene_check(scene_id: str) -> int:
    """A teaching scene's checks run its scene and plain runs of its case: their
    kernels, on tiny runs of the scene's own declaration (catalogue/scenes.yaml)."""
    # lazy: the cases' models (numba) and the teaching scenes (the catalogue), not at a
    # worker's start (unpickling a job of this module)
    from solvers.models.cases import registry
    from solvers.scenes.teaching import load_scenes

    preset = load_scenes()[scene_id]
    run = preset.scene
    n = 0
    # a body rolled beside the scene's own (marble against rubber) runs the same declaration
    for cid in (run.case, *((preset.beside.case,) if preset.beside else ())):
        case = registry()[cid]
        req = {"case": cid, "params": {**case.example, **run.params},
               "state": list(run.state or case.state), "rtol": run.rtol, "atol": run.atol,
               "allow_any_inertia": True, "method": "dop853", "project": False,
               "precision": None, "field": "auto"}
        n += prepare_scene(req) + prepare_kernels(req)
    return n


def simulate_json(req: dict, max_steps: int, prov: dict | None = None) -> bytes:
    return json_bytes(run_request(req, max_steps), max_steps, prov)


def simulate_arrow(req: dict, max_steps: int, prov: dict | None = None) -> bytes:
    """The run as an Arrow IPC stream (app/services/payloads.py)."""
    return arrow_bytes(run_request(req, max_steps), max_steps, prov)


def simulate_csv(req: dict, max_steps: int, prov: dict | None = None) -> bytes:
    """The provenance as "# " lines (app/services/provenance.py), then one row per sample:
    t, the state, then every invariant the case carries."""
    # lazy: the provenance's glossary (the catalogue), not at a worker's start
    from app.services.provenance import stamped

    res = run_request(req, max_steps)
    buf = io.StringIO()
    if prov is not None:
        for line in stamped(prov, res)["header"]:
            buf.write(line + "\n")
    w = csv.writer(buf, lineterminator="\n")
    names = list(res.invariants)
    w.writerow(csv_header(list(res.state_labels), names))
    for i, t in enumerate(res.t):
        w.writerow([repr(float(t)), *(repr(float(v)) for v in res.state[i]),
                    *(repr(float(res.invariants[n][i])) for n in names)])
    return buf.getvalue().encode()


def scene_json(req: dict, frames: int, max_steps: int) -> bytes:
    lower_priority()
    # lazy: the scenes' kinematics (solvers.models.kinematics), not at the server's start,
    # which imports this module for the jobs' names
    from solvers.models.kinematics import scene

    return dumps(scene(req["case"], req["params"], req["state"], req["t_end"],
                       frames=frames, rtol=min(req["rtol"], 1e-8),
                       atol=min(req["atol"], 1e-10), max_steps=max_steps,
                       allow_any_inertia=req["allow_any_inertia"]))


def verify_case(case_id: str | None) -> list[dict]:
    lower_priority()
    return [finite(dict(r)) for r in verify(case_id)]
