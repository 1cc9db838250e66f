"""POST /api/simulate, /api/validate, GET /api/methods (app/api/routes/simulate.py)."""

import csv
import io
import json

import pytest
from fastapi.testclient import TestClient

from app.main import create_app
from app.testing import settings_for_tests
from solvers.models.cases import registry

pytestmark = pytest.mark.filterwarnings("ignore::DeprecationWarning")

BALL = {"case": "plane/chaplygin-ball", "params": {"I1": 1, "I2": 2, "I3": 3, "m": 1, "R": 1},
        "state": [0.5, -0.3, 0.8, 0.3, 0.4, 0.8660254037844386], "t_end": 10.0, "samples": 11}


@pytest.fixture(scope="module")
def client():
    with TestClient(create_app(settings_for_tests(max_steps=20_000))) as c:
        yield c


def raw(client, text):
    return client.post("/api/simulate", content=text.encode(),
                       headers={"Content-Type": "application/json"})


def test_run_returns_state_invariants_stats(client):
    r = client.post("/api/simulate", json=BALL)
    assert r.status_code == 200, r.text
    d = r.json()
    assert d["status"] == "ok" and len(d["t"]) == 11 and d["t"][-1] == 10.0
    assert d["state_labels"] == ["M1", "M2", "M3", "g1", "g2", "g3"]
    assert len(d["state"]) == 11 and len(d["state"][0]) == 6
    assert set(d["invariants"]) == {"energy", "gamma_squared", "area", "M_squared"}
    assert d["stats"]["steps"] > 0 and d["stats"]["drift"]["energy"] < 1e-8
    assert d["stats"]["max_steps"] == 20_000


def test_same_as_the_python_api(client):
    from solvers.simulate import simulate

    d = client.post("/api/simulate", json=BALL).json()
    res = simulate(BALL["case"], BALL["params"], BALL["state"], BALL["t_end"], samples=11)
    assert d["state"] == res.state.tolist()


@pytest.mark.parametrize("cid", list(registry()))
def test_every_case_runs_from_its_example(client, cid):
    r = client.post("/api/simulate", json={"case": cid, "example": True, "t_end": 1.0,
                                           "samples": 5})
    assert r.status_code == 200, r.text
    assert r.json()["status"] in ("ok", "singular")


def test_csv_download(client):
    r = client.post("/api/simulate?format=csv", json=BALL)
    assert r.status_code == 200
    assert r.headers["content-type"].startswith("text/csv")
    assert "attachment" in r.headers["content-disposition"]
    rows = list(csv.reader(line for line in io.StringIO(r.text) if not line.startswith("#")))
    # the JSON's names: the component M2 and the integral M_squared
    assert rows[0] == ["t", "M1", "M2", "M3", "g1", "g2", "g3", "energy", "gamma_squared",
                       "area", "M_squared"]
    assert len(set(rows[0])) == len(rows[0])
    assert len(rows) == 12 and float(rows[-1][0]) == 10.0


def test_step_budget_returns_partial_run(client):
    r = client.post("/api/simulate", json={**BALL, "t_end": 1e6, "samples": 101})
    assert r.status_code == 200
    d = r.json()
    assert d["status"] == "budget" and len(d["t"]) < 101
    assert "step" in d["message"].lower()


@pytest.mark.parametrize("body, field, words", [
    ('{"case": "plane/chaplygin-ball", "example": true, "t_end": NaN}', "t_end", "finite"),
    ('{"case": "plane/chaplygin-ball", "example": true, "t_end": 1e999}', "t_end", "finite"),
    ('{"case": "plane/chaplygin-ball", "example": true, "t_end": -Infinity}', "t_end", "finite"),
    ('{"case": "plane/chaplygin-ball", "example": true, "t_end": 1, "params": {"m": NaN}}',
     "params.m", "finite"),
    ('{"case": "plane/chaplygin-ball", "example": true, "t_end": 1, "state": [1,2,3,4,5,1e999]}',
     "state[5]", "finite"),
    ('{"case": "plane/chaplygin-ball", "example": true, "t_end": 1, "samples": 10000000}',
     "samples", "less than or equal"),
    ('{"case": "plane/chaplygin-ball", "example": true, "t_end": 0}', "t_end", "greater than"),
    ('{"case": "plane/nope", "t_end": 1}', "case", "plane/chaplygin-ball"),
    ('{"case": "plane/chaplygin-ball", "t_end": 1, "state": [1,2,3]}', "state", "at least 5"),
    ('{"case": "plane/chaplygin-ball", "t_end": 1, "colour": "red"}', "colour", "not a field"),
    ('{"case": "plane/chaplygin-ball", "t_end": ', "", "not valid JSON"),
    ('[1, 2, 3]', "", "object"),
])
def test_schema_errors_are_422_with_field_value_and_why(client, body, field, words):
    r = raw(client, body)
    assert r.status_code == 422, r.text
    d = r.json()
    assert words.lower() in d["detail"].lower(), d["detail"]
    assert field in d["detail"]
    json.dumps(d, allow_nan=False)   # the echo of a non-finite input is text, not NaN


@pytest.mark.parametrize("change, words", [
    ({"params": {**BALL["params"], "m": -1}}, "m = -1.0: must be positive"),
    ({"params": {**BALL["params"], "I1": 10}}, "triangle inequality"),
    ({"state": [0.5, -0.3, 0.8, 0.3, 0.4, 0.9]}, "|gamma|"),
    ({"params": {**BALL["params"], "Q": 1}}, "unknown parameter Q"),
    ({"params": {"I1": 1}}, "missing parameters"),
    ({"state": None}, "state is required"),
    ({"method": "scipy-rk45", "project": True}, "compiled method"),
    ({"method": "gauss8"}, "give its step"),
    ({"method": "vern9", "step": 0.1}, "only the symmetric fixed-step methods"),
    ({"method": "gauss8", "step": 0.1, "project": True}, "symmetric and holds"),
    ({"method": "gauss6", "step": 1e-5, "t_end": 1000.0}, "more than the budget of 20000"),
    ({"case": "plane/round-disk", "params": {"I1": 0.25, "I3": 0.5, "m": 1, "R": 1},
      "state": [0, 0, 1, 0, 0, 1]}, "lies flat"),
    ({"case": "sphere/chaplygin-ball", "params": {**BALL["params"], "k": 2.0}}, "does not fit"),
    ({"case": "sphere/flat-base", "params": {"I1": 1, "I2": 2, "I3": 3, "m": 1, "k": 0.5,
                                             "z": 0.1}, "state": [0, 0, 1, 0, 0]}, "k = 0.5"),
])
def test_domain_errors_are_422_with_the_solvers_message(client, change, words):
    before = client.get("/api/health").json()["pool"]["completed"]
    r = client.post("/api/simulate", json={**BALL, **change})
    assert r.status_code == 422, r.text
    assert words in r.json()["detail"]
    assert r.json()["errors"][0]["type"] == "input_error"
    # nothing ran: bad input is refused before it reaches a worker
    assert client.get("/api/health").json()["pool"]["completed"] == before


def test_validate_says_what_would_run(client):
    r = client.post("/api/validate", json={"case": "plane/routh-ball", "example": True,
                                           "t_end": 1})
    assert r.status_code == 200
    d = r.json()
    assert d["ok"] and d["params"]["I2"] == d["params"]["I1"]
    assert d["invariants"][:2] == ["energy", "gamma_squared"]
    r = client.post("/api/validate", json={**BALL, "state": [0, 0, 0, 0, 0, 0.5]})
    assert r.status_code == 422 and r.json()["errors"][0]["loc"] == ["body", "state"]


def test_methods(client):
    kinds = {m["name"]: m["kind"] for m in client.get("/api/methods").json()}
    assert kinds["dop853"] == "compiled" and kinds["scipy-radau"] == "scipy reference"
    assert kinds["gauss8"] == "symmetric"


def test_symmetric_method_runs_with_its_step(client):
    r = client.post("/api/simulate", json={**BALL, "method": "gauss8", "step": 0.25})
    assert r.status_code == 200, r.text
    s = r.json()["stats"]
    # samples 1 apart: four equal steps of 0.25 each
    assert s["method"] == "gauss8" and s["steps"] == 40 and s["step"] == 0.25
    assert max(s["drift"].values()) < 1e-14


def test_scipy_reference_method(client):
    r = client.post("/api/simulate", json={**BALL, "method": "scipy-dop853"})
    assert r.status_code == 200
    assert r.json()["stats"]["method"] == "scipy-dop853"
