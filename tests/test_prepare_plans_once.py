"""A simulate request's prepare job compiles the keys its route planned: the request is
planned once, in the route (app/api/routes/simulate.py _prepare, kernel_prepare.simulate_keys),
and the worker (app/services/jobs.py prepare_kernels) compiles the keys it is given. The keys
travel to the worker through the process pool's pickling, which the pool here repeats."""

import pickle
from concurrent.futures import ThreadPoolExecutor
from types import SimpleNamespace

import anyio
import pytest

from app.api.routes import simulate as route
from app.schemas.simulate import SimulateRequest
from app.services import jobs, kernel_prepare
from app.services.kernel_warmup import KernelWarmup
from solvers import compile_state
from solvers.models.cases import registry

BALL = "plane/chaplygin-ball"


class PicklingPool:
    """Runs a job in this process on its arguments after a pickle round trip (what the
    process pool sends a worker), and records the job."""

    def __init__(self) -> None:
        self.jobs: list[tuple] = []

    async def run(self, fn, *args, deadline=None):
        args = pickle.loads(pickle.dumps(args))
        self.jobs.append((fn, args))
        return fn(*args)


@pytest.fixture
def counted(monkeypatch):
    """plan() counted (the real one answers), compile() recorded instead of compiling."""
    calls = {"plan": [], "compile": []}
    real_plan = compile_state.plan

    def plan(request):
        keys = real_plan(request)
        calls["plan"].append(keys)
        return keys

    def compile_(keys, request):
        calls["compile"].append((list(keys), request))
        return len(keys)

    monkeypatch.setattr(compile_state, "plan", plan)
    monkeypatch.setattr(compile_state, "compile", compile_)
    monkeypatch.setattr(jobs, "lower_priority", lambda: None)   # not this test process
    monkeypatch.setattr(kernel_prepare, "_PREPARED", set())
    return calls


def _prepare(body: dict) -> tuple[PicklingPool, dict]:
    """The simulate route's prepare step on `body`, on a server with nothing warm."""
    pool = PicklingPool()
    request = SimpleNamespace(app=SimpleNamespace(state=SimpleNamespace(kernels=KernelWarmup())))
    settings = SimpleNamespace(kernels_warm=False)
    resolved = route.resolve(SimulateRequest(**body))
    job = route._job(resolved)

    async def main():
        await route._prepare(request, pool, settings, resolved, job)

    # in a thread of its own: a test run that has used Playwright's sync API keeps an event
    # loop running in this thread, where anyio.run would refuse to start another
    with ThreadPoolExecutor(1) as ex:
        ex.submit(anyio.run, main).result()
    return pool, job


@pytest.mark.parametrize("over", [{}, {"method": "rk45"}, {"project": True},
                                  {"method": "taylor", "rtol": 1e-12}],
                         ids=["small", "general", "projected", "taylor"])
def test_a_prepare_of_a_simulate_request_plans_it_once(counted, over):
    pool, job = _prepare({"case": BALL, "example": True, "t_end": 1.0, **over})
    assert len(counted["plan"]) == 1, counted["plan"]
    planned = counted["plan"][0]
    assert planned and all(isinstance(k, tuple) for k in planned), planned
    # one job, the worker's, given the planned keys, which it compiled as they were planned
    assert [(fn, args[1]) for fn, args in pool.jobs] == [(jobs.prepare_kernels, planned)]
    assert counted["compile"] == [(planned, job)]
    # the keys the server records as prepared are the planned ones
    assert kernel_prepare._PREPARED == set(planned)


def test_keys_survive_the_pools_pickling():
    """Every kind of key plan() names hashes and compares equal after a pickle round trip
    (compile_state.compile matches the keys it is given against the ones it plans)."""
    case = registry()[BALL]
    for over in ({}, {"method": "rk45"}, {"field": "generated", "project": True},
                 {"method": "taylor", "rtol": 1e-12}, {"method": "auto", "rtol": 1e-12},
                 {"method": "gauss4", "step": 0.01}):
        keys = compile_state.plan(compile_state.request(BALL, case.example, case.state, **over))
        assert keys, over
        back = pickle.loads(pickle.dumps(keys))
        assert back == keys and set(back) == set(keys), (over, keys, back)


def test_without_keys_the_worker_plans_and_leaves_bad_input_to_the_run(counted, monkeypatch):
    """A teaching scene's check passes no keys: the worker plans them itself (once); a
    request whose planning fails compiles nothing and is left to its own run to report."""
    req = route._job(route.resolve(SimulateRequest(case=BALL, example=True, t_end=1.0)))
    assert jobs.prepare_kernels(req) == 1
    assert len(counted["plan"]) == 1 and counted["compile"] == [(counted["plan"][0], req)]

    def fails(request):
        raise ValueError("bad input")

    monkeypatch.setattr(compile_state, "plan", fails)
    assert jobs.prepare_kernels(req) == 0
    assert len(counted["compile"]) == 1
