"""GET /api/cases gives each parameter's meaning, units and valid range; the range's lower
bound is the one the model's validation checks (solvers/models/bodies.py param_bounds)."""

import pytest
from fastapi.testclient import TestClient

from app.main import create_app
from app.testing import settings_for_tests
from catalogue.glossary import load_glossary
from solvers.errors import InputError
from solvers.models.cases import build, registry

pytestmark = pytest.mark.filterwarnings("ignore::DeprecationWarning")


@pytest.fixture(scope="module")
def client():
    with TestClient(create_app(settings_for_tests(warm_workers=False))) as c:
        yield c


@pytest.fixture(scope="module")
def listed(client):
    r = client.get("/api/cases")
    assert r.status_code == 200
    return {c["id"]: c for c in r.json()}


def test_every_case_lists_every_parameter_with_meaning_units_and_range(listed):
    assert set(listed) == set(registry())
    for cid, spec in registry().items():
        params = listed[cid]["params"]
        assert [p["name"] for p in params] == [*spec.required, *spec.optional], cid
        for p in params:
            assert p["meaning"] and p["units"] and p["range"], (cid, p)
            assert p["required"] == (p["name"] in spec.required)
            if not p["required"]:
                assert p["default"] == spec.optional[p["name"]]


def test_the_case_record_gives_the_same_and_the_units_convention(client, listed):
    for cid in ("plane/chaplygin-ball", "plane/rattleback", "sphere/flat-base"):
        d = client.get(f"/api/cases/{cid}").json()
        assert d["runnable"]["params"] == listed[cid]["params"]
        assert d["runnable"]["units_convention"] == load_glossary().units


def _refused_by_bound(cid, params, name):
    """The InputError build() raises for these parameters, if it names `name`'s bound."""
    try:
        build(cid, params, allow_any_inertia=True)
    except InputError as e:
        msg = str(e)
        return msg.startswith(f"{name} = ") and ("positive" in msg or ">= 0" in msg)
    return False


@pytest.mark.parametrize("cid", list(registry()))
def test_published_bounds_are_the_ones_the_validation_checks(listed, cid):
    spec = registry()[cid]
    for p in listed[cid]["params"]:
        name, b = p["name"], p["bounds"]
        if b is None:
            # no published bound: the validation checks none (a negative value is not
            # refused for its sign)
            assert not _refused_by_bound(cid, {**spec.example, name: -1.0}, name), (cid, name)
            continue
        lo = b["min"]
        outside = lo - 1.0 if b["min_inclusive"] else lo
        assert _refused_by_bound(cid, {**spec.example, name: outside}, name), (cid, name)
        assert not _refused_by_bound(cid, {**spec.example, name: lo + 1e-3}, name), (cid, name)
        if b["min_inclusive"]:
            assert not _refused_by_bound(cid, {**spec.example, name: lo}, name), (cid, name)
        # the glossary's words say the same bound
        assert p["range"].startswith("≥ 0" if b["min_inclusive"] else "> 0"), (cid, p)


def test_a_refused_parameter_changes_nothing(client):
    before = client.get("/api/cases").json()
    r = client.post("/api/validate", json={"case": "plane/chaplygin-ball", "example": True,
                                           "params": {"R": 0.0}, "t_end": 1.0})
    assert r.status_code == 422 and "R = 0.0" in r.text and "positive" in r.text
    assert client.get("/api/cases").json() == before
