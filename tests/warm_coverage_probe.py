"""Run in a fresh interpreter by tests/test_warm_covers_requests.py: every task of the
warm-up (solvers/warmup.py parts(only_pending=False), in this process, one after the other),
then what the explorer's default clicks run, each in the code the route and its worker
run: a case page's Run (plain, and with projection), its 3D scene, a Poincare map with the
stream's pilot (every case with the state (M, gamma)), the teaching scenes' checks, and a
worker's warm start. Prints one JSON line: every numba specialization (dispatcher,
signature) the clicks entered from Python that the warm-up's tasks had not.

numba compiles one specialization per signature (argument types, read-only arrays
included) and loads it from the on-disk cache when the warm-up compiled the same one, so
a signature the warm-up never entered is a compile inside a request's deadline once the
warm-up is done (kernel_prepare.needed prepares only the keys the warm-up leaves out)."""

import json
import sys

from numba.core.dispatcher import Dispatcher


def signatures() -> dict[str, set[str]]:
    out: dict[str, set[str]] = {}
    for mod in list(sys.modules.values()):
        path = getattr(mod, "__file__", None) or ""
        if "site-packages" in path:
            continue
        for v in list(vars(mod).values()):
            if isinstance(v, Dispatcher):
                key = f"{v.py_func.__module__}.{v.py_func.__qualname__}"
                out.setdefault(key, set()).update(map(str, v.signatures))
    return out


def clicks() -> None:
    import app.api.routes.poincare as poincare_route
    import app.api.routes.simulate as simulate_route
    from app.schemas.simulate import SceneRequest, SimulateRequest
    from app.services import jobs, poincare_jobs
    from solvers.kernels import layout as L
    from solvers.models.cases import registry
    from solvers.scenes.scene_checks import check_json
    from solvers.scenes.teaching import load_scenes

    jobs.warm()
    steps = 10**6
    for cid in registry():
        run = simulate_route.resolve(SimulateRequest(case=cid, example=True, t_end=1.0,
                                                     samples=11), steps)
        jobs.simulate_json(simulate_route._job(run), steps)
        projected = simulate_route.resolve(SimulateRequest(case=cid, example=True, t_end=1.0,
                                                           samples=11, project=True), steps)
        jobs.simulate_json(simulate_route._job(projected), steps)
        scene = simulate_route.resolve(SceneRequest(case=cid, example=True, t_end=1.0), steps)
        jobs.scene_json(simulate_route._job(scene), 20, steps)
        # no map of the flat-base cases ((M, r1, r2)) nor of the rubber ones (starts off
        # (omega, gamma) = 0): solvers.maps.poincare.map_model refuses them
        if run["_model"].model != L.MODEL_FULL or run["_model"].case.constraint == "rubber":
            continue
        req = poincare_route.PoincareRequest(case=cid, example=True, energy=1.0,
                                             trajectories=2, points=2)
        _, job, starts = poincare_route.resolve(req, steps)
        poincare_jobs.seconds_per_point(job, starts[0], 2)
        poincare_jobs.trajectories(job, starts)
    for sid, s in load_scenes().items():
        for k in range(len(s.checks)):
            check_json(sid, k)


def main() -> None:
    from solvers import warmup

    for what, _ in warmup.parts(only_pending=False):
        warmup._task(what)
    before = signatures()
    clicks()
    after = signatures()
    new = {k: sorted(v - before.get(k, set())) for k, v in after.items()
           if v - before.get(k, set())}
    print(json.dumps({"warmed": sum(map(len, before.values())), "new": new}))


if __name__ == "__main__":
    main()
