import numpy as np
import pytest

from solvers.cases import build, initial_state, registry
from solvers.kernels import layout as L

CASE_IDS = list(registry())


def random_states(model, n, rng, spread=1.0):
    """n random phase points of the model near its demo state (unit gamma, fitting)."""
    from solvers.bodies import check_state
    from solvers.errors import InputError

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
