"""POST /api/verify/{id}, GET /api/verdicts (app/api/routes/verify.py) and the verdict
store behind them (app/services/verdicts.py)."""

import pytest
from fastapi.testclient import TestClient

from app.main import create_app
from app.services.verdicts import VerdictStore, summary
from app.testing import settings_for_tests

pytestmark = pytest.mark.filterwarnings("ignore::DeprecationWarning")
CASE = "plane/routh-ball"


@pytest.fixture(scope="module")
def client():
    with TestClient(create_app(settings_for_tests(verify_deadline_s=300))) as c:
        yield c


def test_verify_a_case_and_see_the_verdicts_everywhere(client):
    r = client.post(f"/api/verify/{CASE}", json={})
    assert r.status_code == 200, r.text
    d = r.json()
    assert d["case"] == CASE and d["records"]
    verdicts = {rec["verdict"] for rec in d["records"]}
    assert verdicts <= {"verified", "fails", "evidence", "unchecked"}
    assert "verified" in verdicts
    for rec in d["records"]:
        assert rec["claim"].startswith(CASE + "/") and rec["message"]
    # the case page shows them claim by claim ...
    c = client.get(f"/api/cases/{CASE}").json()
    assert c["verification"] == "done"
    by_id = {rec["claim"]: rec["verdict"] for rec in d["records"]}
    for cl in c["claims"]:
        assert cl["verdict"]["verdict"] == by_id[cl["id"]]
    # ... and the table marks its cells with them
    t = client.get("/api/tables/plane").json()
    marks = [cell["verdict"] for row in t["grid"] for cell in row["cells"]
             if CASE in cell["merged"] and cell["verdict"]]
    assert marks and any(m["verdict"] != "unchecked" for m in marks)
    assert all(m["mark"] != "pending" for m in marks)
    assert {rec["claim"] for rec in client.get("/api/verdicts").json()} == set(by_id)


def test_unknown_case_is_404(client):
    r = client.post("/api/verify/plane/no-such-case", json={})
    assert r.status_code == 404 and "unknown case" in r.json()["detail"]


def test_summary_rules():
    """A cell's mark is the mark of its property per spanned case (the cell records of
    solvers.verify.levels), not of its printed formulas (changed with issue 10); since
    issue 17 `mark` is one of the vocabulary (solvers/verify/marks.yaml) and the coarse
    verdict is kept beside it in `verdict`."""
    a, b, c = "sphere/body-of-revolution", "sphere/round-disk", "sphere/routh-ball"
    V = {"as-printed": "verified", "after-correction": "verified", "fails": "fails",
         "evidence-for": "evidence", "inconclusive": "unchecked"}

    def rec(case, mark, notes=()):
        return {f"{case}/cell/measure": {"claim": f"{case}/cell/measure", "verdict": V[mark],
                                          "mark": mark, "mark_note": None, "errata": [],
                                          "notes": list(notes), "message": "m"}}
    assert summary([], {}, "measure", [a]) is None
    s = summary(["x"], {**rec(a, "after-correction", ["holds; printed formula corrected"]),
                        **rec(b, "as-printed"), **rec(c, "as-printed")}, "measure", [a, b, c])
    assert s["mark"] == "after-correction" and s["verdict"] == "verified"
    assert [m["column"] for m in s["marks"]] == [6, 7, 8]
    assert s["mark_counts"] == {"as-printed": 2, "after-correction": 1}
    assert s["notes"] == ["holds; printed formula corrected"]
    s = summary(["x"], {**rec(a, "as-printed"), **rec(b, "fails")}, "measure", [a, b])
    assert s["mark"] == "fails" and s["verdict"] == "fails"
    s = summary(["x"], {**rec(a, "as-printed"), **rec(b, "evidence-for")}, "measure", [a, b])
    assert s["mark"] == "evidence-for" and s["verdict"] == "evidence"
    s = summary(["x"], {**rec(a, "as-printed"), **rec(b, "inconclusive")}, "measure", [a, b])
    assert s["mark"] == "inconclusive" and s["verdict"] == "unchecked"
    s = summary(["x"], rec(a, "as-printed"), "measure", [a, b])   # b being checked
    assert s["mark"] == "pending" and [m["mark"] for m in s["marks"]] == ["as-printed",
                                                                          "pending"]
    # b has no verdict and is not being checked (its check failed): nothing was run there
    s = summary(["x"], rec(a, "as-printed"), "measure", [a, b], pending=set())
    assert [m["mark"] for m in s["marks"]] == ["as-printed", "not-checkable"]
    assert s["mark"] == "as-printed" and s["verdict"] == "unchecked"


def test_store_cache_round_trip(tmp_path):
    s = VerdictStore(["plane/a", "plane/b"], tmp_path)
    s.put("plane/a", [{"claim": "plane/a/x", "verdict": "verified"}])
    t = VerdictStore(["plane/a", "plane/b"], tmp_path)
    assert t.load_cache() and t.by_claim()["plane/a/x"]["verdict"] == "verified"
    assert t.state != "done"       # plane/b still to verify
    u = VerdictStore(["plane/a"], tmp_path / "elsewhere")
    assert not u.load_cache()
