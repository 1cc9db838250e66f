"""One name per quantity in a run's JSON, CSV and Arrow answers (solvers/models/
observables.py), and the provenance every answer carries: the CSV's commented header and
its file name with the hash of the run's inputs (app/services/provenance.py)."""

import csv
import json
import re
from urllib.parse import parse_qs, urlsplit

import pyarrow as pa
import pytest
from fastapi.testclient import TestClient

from app import __version__
from app.main import create_app
from app.services import provenance
from app.testing import settings_for_tests
from catalogue.glossary import load_glossary
from solvers.kernels.integrals import NAMES
from solvers.models.bodies import STATE_LABELS
from solvers.models.observables import public_name
from solvers.simulate import simulate

pytestmark = pytest.mark.filterwarnings("ignore::DeprecationWarning")

BALL = {"case": "plane/chaplygin-ball", "params": {"I1": 1, "I2": 2, "I3": 3, "m": 1, "R": 1},
        "state": [0.5, -0.3, 0.8, 0.3, 0.4, 0.8660254037844386], "t_end": 10.0, "samples": 11}
# a gyrostat on a sphere carries |M + S|^2 instead of |M|^2: each renamed integral is in one
GYRO = {"case": "sphere/chaplygin-ball", "example": True, "t_end": 1.0, "samples": 5,
        "params": {"S1": 0.1, "S2": 0.2, "S3": 0.3}}


@pytest.fixture(scope="module")
def client():
    with TestClient(create_app(settings_for_tests(max_steps=20_000))) as c:
        yield c


def _csv(text: str) -> tuple[list[str], list[list[str]]]:
    lines = text.splitlines()
    comments = [x for x in lines if x.startswith("#")]
    # the comments come first, all of them
    assert lines[:len(comments)] == comments
    return comments, list(csv.reader(lines[len(comments):]))


def _arrow(content: bytes) -> pa.Table:
    return pa.ipc.open_stream(pa.BufferReader(content)).read_all()


def test_no_output_name_reads_as_a_state_component():
    components = {n for labels in STATE_LABELS.values() for n in labels}
    outputs = [public_name(n) for n in NAMES]
    assert len(set(outputs)) == len(outputs)
    assert not components & set(outputs), components & set(outputs)
    assert public_name("M2") == "M_squared" and public_name("gamma2") == "gamma_squared"


def test_every_output_name_is_in_the_glossary():
    g = load_glossary()
    for n in NAMES:
        e = g.get(public_name(n))
        assert e is not None and e.kind == "integral" and e.group == "output", n
        assert e.meaning and e.range
    # and the glossary defines no output that a run cannot report
    outputs = {public_name(n) for n in NAMES}
    assert {e.symbol for e in g.entries if e.kind == "integral"} == outputs


def test_python_result_uses_the_output_names():
    res = simulate(BALL["case"], BALL["params"], BALL["state"], 1.0, samples=3)
    assert list(res.invariants) == ["energy", "gamma_squared", "area", "M_squared"]
    assert set(res.stats["drift"]) == set(res.invariants)
    assert set(res.to_json()["invariants"]) == set(res.invariants)
    # the kernels' code name still finds the same series (code in their vocabulary)
    assert "M2" in res.invariants and res.invariants["M2"] is res.invariants["M_squared"]
    assert res.drift("M2") == res.drift("M_squared")
    assert "M2" not in list(res.invariants) and res.invariants.get("nope") is None
    with pytest.raises(KeyError):
        res.invariants["nope"]


@pytest.mark.parametrize("body", [BALL, GYRO], ids=["ball", "gyrostat"])
def test_json_csv_and_arrow_use_the_same_names(client, body):
    j = client.post("/api/simulate", json=body)
    c = client.post("/api/simulate?format=csv", json=body)
    a = client.post("/api/simulate?format=arrow", json=body)
    assert j.status_code == c.status_code == a.status_code == 200, (j.text, c.text)
    d = j.json()
    _, rows = _csv(c.text)
    tab = _arrow(a.content)
    names = ["t", *d["state_labels"], *d["invariants"]]
    assert rows[0] == names == tab.column_names
    assert len(set(names)) == len(names)
    assert "M2" not in d["invariants"] and "M2" in d["state_labels"]
    assert "gamma_squared" in d["invariants"]
    assert ("M_plus_S_squared" if body is GYRO else "M_squared") in d["invariants"]
    meta = {k.decode(): json.loads(v) for k, v in tab.schema.metadata.items()}
    assert meta["invariants"] == list(d["invariants"])
    assert set(d["stats"]["drift"]) == set(d["invariants"])
    # the same numbers under the same name in all three
    for n in d["invariants"]:
        col = names.index(n)
        assert tab.column(n).to_pylist() == d["invariants"][n]
        assert [float(r[col]) for r in rows[1:]] == d["invariants"][n]


def test_validate_names_the_integrals_as_the_run_will(client):
    v = client.post("/api/validate", json=BALL).json()
    d = client.post("/api/simulate", json=BALL).json()
    assert v["invariants"] == list(d["invariants"])


def test_csv_begins_with_the_runs_provenance(client):
    r = client.post("/api/simulate?format=csv", json=BALL)
    assert r.status_code == 200
    comments, rows = _csv(r.text)
    head = dict(x[2:].split(": ", 1) for x in comments)
    assert head["case"] == "plane/chaplygin-ball"
    # every parameter of the run, the defaults filled in
    assert head["parameters"] == ("I1 = 1.0, I2 = 2.0, I3 = 3.0, m = 1.0, R = 1.0, S1 = 0.0, "
                                  "S2 = 0.0, S3 = 0.0, g = 0.0, eps = 0.0")
    assert head["method"] == "dop853"
    assert head["tolerances"] == "rtol = 1e-10, atol = 1e-12"
    assert head["t_end"] == "10.0; samples: 11"
    assert head["version"] == f"rolling-hierarchy {__version__}"
    assert re.fullmatch(r"\d{4}-\d\d-\d\dT\d\d:\d\d:\d\dZ", head["date"])
    # the address that reproduces the run: the case page with the run's query
    url = urlsplit(head["reproduce"])
    assert url.scheme in ("http", "https") and url.path == "/case/plane/chaplygin-ball"
    q = parse_qs(url.query)
    assert q["run"] == ["1"] and q["p.I2"] == ["2.0"] and q["t_end"] == ["10.0"]
    assert [float(x) for x in q["state"][0].split(",")] == BALL["state"]
    assert q["method"] == ["dop853"] and q["samples"] == ["11"]
    assert rows[0][0] == "t" and len(rows) == 12
    # what each column holds, from the glossary: the component M2, the integral M_squared
    assert [k.removeprefix("column ") for k in head if k.startswith("column ")] == rows[0]
    g = load_glossary()
    for c in rows[0][1:]:
        assert head[f"column {c}"] == g.get(c).meaning, c
    assert head["column M_squared"].startswith("The square of the angular momentum")
    assert head["column M2"].startswith("Component along e2 of the angular momentum")
    # the JSON carries the same header, for the case page's CSV button
    d = client.post("/api/simulate", json=BALL).json()
    assert [x for x in d["provenance"]["header"] if not x.startswith("# date")] == \
        [x for x in comments if not x.startswith("# date")]


def test_csv_file_name_carries_the_hash_of_the_inputs(client):
    r = client.post("/api/simulate?format=csv", json=BALL)
    name = re.search(r'filename="([^"]+)"', r.headers["content-disposition"]).group(1)
    m = re.fullmatch(r"plane_chaplygin-ball_t10_([0-9a-f]{8})\.csv", name)
    assert m, name
    d = client.post("/api/simulate", json=BALL).json()
    assert d["provenance"]["hash"] == m.group(1)
    assert d["provenance"]["file_stem"] + ".csv" == name
    # another parameter, another name; the same run, the same name
    other = client.post("/api/simulate?format=csv", json={
        **BALL, "params": {**BALL["params"], "I3": 2.5}}).headers["content-disposition"]
    assert m.group(1) not in other
    again = client.post("/api/simulate?format=csv", json=BALL).headers["content-disposition"]
    assert name in again


def test_the_hash_is_of_the_inputs_that_decide_the_numbers():
    job = {"case": "plane/chaplygin-ball", "params": {"I1": 1.0, "R": 1.0}, "state": [1, 0],
           "t_end": 100.0, "samples": 201, "method": "dop853", "rtol": 1e-10, "atol": 1e-12,
           "step": None, "project": False, "precision": None, "field": "auto",
           "allow_any_inertia": False}
    h = provenance.run_hash(job)
    assert re.fullmatch(r"[0-9a-f]{8}", h)
    # the order of the parameters does not matter, 1 and 1.0 are the same input
    assert provenance.run_hash({**job, "params": {"R": 1, "I1": 1}}) == h
    for change in ({"rtol": 1e-9}, {"method": "vern9"}, {"samples": 202}, {"t_end": 99.0},
                   {"state": [1, 1e-12]}, {"project": True}, {"case": "plane/routh-ball"}):
        assert provenance.run_hash({**job, **change}) != h, change
    assert provenance.file_stem(job) == f"plane_chaplygin-ball_t100_{h}"


def test_public_url_is_the_address_that_reproduces_the_run():
    settings = settings_for_tests(max_steps=20_000, public_url="https://example.org/rolling/")
    with TestClient(create_app(settings)) as c:
        d = c.post("/api/simulate", json=BALL).json()
    assert d["provenance"]["permalink"].startswith(
        "https://example.org/rolling/case/plane/chaplygin-ball?run=1&")
