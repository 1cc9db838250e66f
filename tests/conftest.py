import copy
import os
from concurrent.futures import ThreadPoolExecutor
from contextlib import contextmanager
from pathlib import Path

import anyio
import numpy as np
import pytest

from catalogue.numbering import SEED_NAME
from catalogue.numbering import find_seed as numbering_find_seed
from solvers.kernels import layout as L
from solvers.models.cases import build, initial_state, registry

# the marble cases: the tests on the `case_id` fixture compare with the marble NumPy field
# (solvers/models/reference.py) and check integrals off the rubber manifold; the rubber cases
# (constraint "rubber") have their own tests against both rubber derivations
# (tests/test_rubber_wire.py)
CASE_IDS = [cid for cid, c in registry().items() if c.constraint == "marble"]


def random_states(model, n, rng, spread=1.0):
    """n random phase points of the model near its demo state (unit gamma, fitting)."""
    from solvers.errors import InputError
    from solvers.models.bodies import check_state

    base = initial_state(model, model.case.state)
    out = []
    while len(out) < n:
        y = base + spread * rng.standard_normal(len(base))
        if model.model == L.MODEL_FULL:
            y[3:] /= np.linalg.norm(y[3:])
        try:
            check_state(model.model, model.p, y, shell=model.case.fixed_k is not None)
        except InputError:
            continue
        out.append(y)
    return out


@pytest.fixture(params=CASE_IDS)
def case_id(request):
    return request.param


@pytest.fixture
def example_model(case_id):
    c = registry()[case_id]
    return build(case_id, c.example)


def revolution_body(kind, k=0.0, g=0.0, s=0.0, a=0.0, brun=0.0, I1=2.0, I3=3.0, m=1.5):
    """A body of revolution in the kernel's parameter vector (the reduced-system tests):
    ellipsoid of revolution, rounded ellipsoid (not a quadric), disk or ball."""
    p = np.zeros(L.N_PARAMS)
    p[L.I1] = p[L.I2] = I1
    p[L.I3] = I3
    p[L.MASS] = m
    p[L.CURV] = k
    p[L.GRAV] = g
    p[L.S3] = s
    p[L.A3] = a
    p[L.BRUN] = brun
    if kind == "ellipsoid":
        p[L.B11] = p[L.B22] = 0.8
        p[L.B33] = 0.3
    elif kind == "rounded":
        p[L.B11] = p[L.B22] = 0.5
        p[L.B33] = 1.2
        p[L.BALL_C] = 0.3
    elif kind == "disk":
        p[L.DISK_D] = 0.9
    elif kind == "ball":
        p[L.BALL_C] = 0.7
    return p


@pytest.fixture(scope="module")
def patient_client():
    """A TestClient of the app without worker warm-up and with a 120 s deadline (the
    Poincare and scene API tests run maps that take seconds)."""
    from fastapi.testclient import TestClient

    from app.main import create_app
    from app.testing import settings_for_tests

    with TestClient(create_app(settings_for_tests(warm_workers=False,
                                                  deadline_s=120.0))) as c:
        yield c


# The paper's text (the LaTeX of Borisov & Mamaev 2002) is found through the setting
# ROLLING_SEED; by default the seed checked out beside the repository (shared/seeds/ in the
# clone's folder or any folder above it, as in CI). The non-test code knows no default
# location (catalogue.numbering.find_seed: an argument or ROLLING_SEED): the search is the
# tests'. Missing, the tests that need it skip and say which setting to set; with
# ROLLING_REQUIRE_SEED=1 (.ci/run) they fail instead.
DEFAULT_SEED = (Path(__file__).resolve().parents[2] / "shared" / "seeds" / SEED_NAME)


def find_seed() -> Path | None:
    """ROLLING_SEED, else shared/seeds/<seed> beside the repository or in any folder above."""
    env = numbering_find_seed()
    if env is not None:
        return env
    repo = Path(__file__).resolve().parents[1]
    for parent in repo.parents:
        p = parent / "shared" / "seeds" / SEED_NAME
        if p.is_file():
            return p
    return None


def seed_path() -> Path:
    return find_seed() or DEFAULT_SEED


@pytest.fixture(scope="session")
def paper_text() -> str:
    path = seed_path()
    if not path.is_file():
        why = (f"the paper's text is not at {path}: set ROLLING_SEED to the seed file "
               "000_c616a4a5e747ad23.txt")
        if os.environ.get("ROLLING_REQUIRE_SEED") == "1":
            pytest.fail(f"{why} (ROLLING_REQUIRE_SEED=1: required here)")
        pytest.skip(why)
    return path.read_text(encoding="utf-8")


@pytest.fixture(scope="session")
def catalogue_records(tmp_path_factory, worker_id):
    """The records of every claim of the catalogue, `verify_parallel(workers=2)`, computed
    once per test session. A full verification costs about a minute of CPU and seven
    modules read it; under pytest-xdist the first worker that asks computes it under a
    file lock and the others read its file. For one case, the records are the same as
    `verify(case=...)`'s (tests/test_verdict_levels.py::test_one_case_is_the_full_run_s)."""
    import fcntl
    import pickle

    from solvers.verify.parallel import verify_parallel

    root = tmp_path_factory.getbasetemp()
    if worker_id != "master":              # xdist: basetemp is per worker, its parent shared
        root = root.parent
    path, lock = root / "catalogue-records.pkl", root / "catalogue-records.lock"
    with open(lock, "w") as fh:
        fcntl.flock(fh, fcntl.LOCK_EX)
        try:
            if path.exists():
                return pickle.loads(path.read_bytes())
            records = verify_parallel(workers=2)
            path.write_bytes(pickle.dumps(records))
            return records
        finally:
            fcntl.flock(fh, fcntl.LOCK_UN)


@contextmanager
def client_with_verdicts(records):
    """A TestClient of the explorer (no warm workers) whose verdict store holds these
    records for every case, as after a finished verification."""
    from fastapi.testclient import TestClient

    from app.main import create_app
    from app.testing import settings_for_tests

    records = copy.deepcopy(records)
    app = create_app(settings_for_tests(warm_workers=False))
    with TestClient(app) as c:
        store = app.state.verdicts
        for cid in store.case_ids:
            store.records[cid] = [r for r in records if r["case"] == cid]
        store.state = "done"
        yield c


def run_async(main):
    """anyio.run(main) in a thread of its own: in one process with the browser tests,
    Playwright's sync API leaves an asyncio loop running in the main thread, and anyio.run
    refuses to nest."""
    with ThreadPoolExecutor(1) as ex:
        return ex.submit(anyio.run, main).result()


def records_of(records, cases):
    """The records of the given cases, in the order of `cases` (as a loop of
    `verify(case=c)` over them would give)."""
    return [r for c in cases for r in records if r["case"] == c]
