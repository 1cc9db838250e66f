"""GET /api/tables/{plane,sphere} (app/api/routes/tables.py): the paper's layout."""

import pytest
from fastapi.testclient import TestClient

from app.main import create_app
from app.testing import settings_for_tests
from catalogue.load import load_catalogue
from solvers.verify import marks as vocab

pytestmark = pytest.mark.filterwarnings("ignore::DeprecationWarning")


@pytest.fixture(scope="module")
def client():
    with TestClient(create_app(settings_for_tests(warm_workers=False))) as c:
        yield c


@pytest.mark.parametrize("tid", ["plane", "sphere"])
def test_layout_matches_the_catalogue(client, tid):
    r = client.get(f"/api/tables/{tid}")
    assert r.status_code == 200
    t = r.json()
    table = getattr(load_catalogue(), tid)
    assert [c["id"] for c in t["columns"]] == [c.id for c in table.cases]
    assert [r["key"] for r in t["rows"]] == [r.key.value for r in table.rows]
    for row in t["grid"]:
        # every row covers every column exactly once, merged cells with their colspan
        covered = [cid for cell in row["cells"] for cid in cell["merged"]]
        assert covered == [c.id for c in table.cases]
        assert all(cell["colspan"] == len(cell["merged"]) for cell in row["cells"])
        for cell in row["cells"]:
            assert cell["shade"] in ("full", "partial", "none")
            if cell["claims"]:
                assert cell["verdict"]["mark"] in vocab.IDS
                assert cell["verdict"]["verdict"] in ("verified", "fails", "evidence",
                                                      "unchecked", "pending")
            else:
                assert cell["verdict"] is None


def test_merged_header_cells_as_in_table_1(client):
    t = client.get("/api/tables/plane").json()
    inertia = next(r for r in t["grid"] if r["key"] == "tensor_of_inertia")
    assert [c["colspan"] for c in inertia["cells"]] == [3, 3, 1]


def test_second_line_a_equals_2R_under_borisov_fedorov(client):
    t = client.get("/api/tables/sphere").json()
    restr = next(r for r in t["grid"] if r["key"] == "restrictions")
    subs = [c for c in restr["cells"] if c["subrow"]]
    assert len(subs) == 1 and subs[0]["subrow_case"] == "sphere/borisov-fedorov"
    assert subs[0]["subrow"]["plain"] == "a = 2R"


def test_unknown_table_is_422(client):
    r = client.get("/api/tables/torus")
    assert r.status_code == 422
    assert "table_id" in r.json()["detail"]
