"""GET /api/cases and /api/cases/{id} (app/api/routes/cases.py)."""

import pytest
from fastapi.testclient import TestClient

from app.main import create_app
from app.testing import settings_for_tests
from catalogue.load import load_catalogue
from solvers.models.cases import beyond_table_ids, case_ids, table_case_ids

pytestmark = pytest.mark.filterwarnings("ignore::DeprecationWarning")


@pytest.fixture(scope="module")
def client():
    with TestClient(create_app(settings_for_tests(warm_workers=False))) as c:
        yield c


def test_list_has_every_case_in_the_papers_order(client):
    r = client.get("/api/cases")
    assert r.status_code == 200
    ids = [c["id"] for c in r.json()]
    # the columns of Tables 1 and 2, then the runnable cases beyond them (the rattleback)
    assert ids == [c.id for c in load_catalogue().cases()] + beyond_table_ids()
    assert sorted(ids) == sorted(case_ids())
    assert [c["in_tables"] for c in r.json()] == [cid in table_case_ids() for cid in ids]
    first = r.json()[0]
    assert first["href"] == "/case/plane/chaplygin-ball" and first["table"] == 1


@pytest.mark.parametrize("cid", table_case_ids())
def test_every_case_with_claims_sources_and_verdicts(client, cid):
    r = client.get(f"/api/cases/{cid}")
    assert r.status_code == 200
    c = r.json()
    case = load_catalogue().case(cid)
    assert c["id"] == cid
    assert [cl["id"] for cl in c["claims"]] == [cl.id for cl in case.claims]
    for cl in c["claims"]:
        assert cl["printed"] and cl["plain"]
        assert cl["label"] or cl["where"]
        assert cl["verdict"]["verdict"] in ("verified", "fails", "evidence", "unchecked")
    assert sum(c["verdicts"].values()) == len(case.claims)
    assert len(c["cells"]) == len(case.cells)
    run = c["runnable"]
    assert len(run["state"]) == len(run["state_labels"]) in (5, 6)
    assert {p["name"] for p in run["params"] if p["required"]} <= set(run["example"])


def test_unchecked_until_verified(client):
    c = client.get("/api/cases/plane/routh-ball").json()
    assert c["verification"] == "idle"
    assert all(cl["verdict"]["verdict"] == "unchecked" for cl in c["claims"])


@pytest.mark.parametrize("bad", ["plane/nope", "nope", "plane/chaplygin-ball/extra", "%00"])
def test_unknown_case_is_404_with_a_message(client, bad):
    r = client.get(f"/api/cases/{bad}")
    assert r.status_code == 404
    assert "unknown case" in r.json()["detail"]
