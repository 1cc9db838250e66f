"""The answers of POST /api/simulate over real HTTP (uvicorn): JSON written by orjson from
the arrays, Arrow IPC for clients that ask for it, content negotiation, and non-finite
numbers (app/services/payloads.py)."""

import csv
import json
import math

import httpx
import numpy as np
import pyarrow as pa
import pytest

from app.core.errors import NotAcceptable
from app.services import payloads
from app.testing import live_server, wait_idle
from solvers.simulate import SimulationResult, simulate

pytestmark = pytest.mark.filterwarnings("ignore::DeprecationWarning")
BALL = {"case": "plane/chaplygin-ball", "params": {"I1": 1, "I2": 2, "I3": 3, "m": 1, "R": 1},
        "state": [0.5, -0.3, 0.8, 0.3, 0.4, 0.8660254037844386], "t_end": 50.0,
        "samples": 2000}
BROWSER = "text/html,application/xhtml+xml,application/xml;q=0.9,*/*;q=0.8"


@pytest.fixture(scope="module")
def url():
    with live_server(workers=1) as u:
        wait_idle(u)
        yield u


def post(url, body=BALL, accept=None, query=""):
    headers = {"Accept": accept} if accept is not None else {}
    return httpx.post(f"{url}/api/simulate{query}", json=body, headers=headers, timeout=60)


def arrow_table(content: bytes) -> pa.Table:
    return pa.ipc.open_stream(pa.BufferReader(content)).read_all()


def test_arrow_answer_holds_the_json_answer(url):
    j = post(url)
    a = post(url, accept=payloads.ARROW)
    assert j.status_code == a.status_code == 200, (j.text, a.status_code)
    assert j.headers["content-type"] == "application/json"
    assert a.headers["content-type"] == payloads.ARROW
    assert "Accept" in a.headers["vary"]
    d, tab = j.json(), arrow_table(a.content)
    assert tab.num_rows == 2000 and len(d["t"]) == 2000
    # columns named as the JSON's keys and the CSV: the component M2, the integral M_squared
    assert tab.column_names == ["t", "M1", "M2", "M3", "g1", "g2", "g3", "energy",
                                "gamma_squared", "area", "M_squared"]
    assert all(f.type == pa.float64() for f in tab.schema)
    meta = {k.decode(): json.loads(v) for k, v in tab.schema.metadata.items()}
    assert meta["invariants"] == ["energy", "gamma_squared", "area", "M_squared"]
    for key in ("case", "params", "status", "message", "state_labels"):
        assert meta[key] == d[key]
    for key in ("steps", "rhs_calls", "method", "field", "drift", "max_steps", "samples"):
        assert meta["stats"][key] == d["stats"][key]
    # the same numbers, bit for bit (orjson writes the shortest repr that reads back)
    assert tab.column("t").to_pylist() == d["t"]
    state = np.array(d["state"])
    for j_, lab in enumerate(d["state_labels"]):
        assert tab.column(lab).to_pylist() == state[:, j_].tolist()
    for name in meta["invariants"]:
        assert tab.column(name).to_pylist() == d["invariants"][name]


def test_json_is_the_python_api_run_exactly(url):
    d = post(url).json()
    res = simulate(BALL["case"], BALL["params"], BALL["state"], BALL["t_end"],
                   samples=BALL["samples"])
    assert d["state"] == res.state.tolist() and d["t"] == res.t.tolist()
    assert d["invariants"] == {k: v.tolist() for k, v in res.invariants.items()}
    assert d["stats"]["field"] == res.stats["field"]


@pytest.mark.parametrize("accept", [None, "*/*", BROWSER, "application/*",
                                    "application/json", "application/json, text/csv;q=0.5"])
def test_json_for_browsers_and_plain_clients(url, accept):
    r = post(url, body={**BALL, "samples": 11}, accept=accept)
    assert r.status_code == 200 and r.headers["content-type"] == "application/json"
    assert len(r.json()["t"]) == 11


def test_csv_by_accept_or_by_query(url):
    small = {**BALL, "samples": 5}
    by_accept = post(url, body=small, accept="text/csv")
    by_query = post(url, body=small, accept=payloads.ARROW, query="?format=csv")
    for r in (by_accept, by_query):
        assert r.status_code == 200 and r.headers["content-type"].startswith("text/csv")
        # the provenance's "# " lines first, then the header row and one row per sample
        lines = r.text.splitlines()
        assert lines[0].startswith("# ")
        rows = list(csv.reader(x for x in lines if not x.startswith("#")))
        assert rows[0][:2] == ["t", "M1"] and len(rows) == 6
    assert post(url, body=small, accept="text/csv",
                query="?format=json").headers["content-type"] == "application/json"


def test_unsupported_accept_is_406_and_names_the_types(url):
    r = post(url, body={**BALL, "samples": 5}, accept="image/png")
    assert r.status_code == 406
    assert r.headers["content-type"] == "application/json"
    assert payloads.ARROW in r.json()["detail"] and "application/json" in r.json()["detail"]
    # bad input is still a 422 in JSON, whatever was asked for
    bad = post(url, body={**BALL, "t_end": -1.0}, accept=payloads.ARROW)
    assert bad.status_code == 422 and "t_end" in bad.json()["detail"]


def test_field_general_and_bad_field_over_http(url):
    r = post(url, body={**BALL, "samples": 5, "field": "general"})
    assert r.status_code == 200 and r.json()["stats"]["field"] == "general"
    assert post(url, body={**BALL, "samples": 5}).json()["stats"]["field"] in (
        "generated", "general")
    bad = post(url, body={**BALL, "samples": 5, "field": "generated"})
    assert bad.status_code == 422 and "field" in bad.json()["detail"]
    scene = httpx.post(f"{url}/api/scene", json={**BALL, "samples": 5, "field": "general"},
                       timeout=60)
    assert scene.status_code == 422 and "field" in scene.json()["detail"]


def test_negotiation_rules():
    n = payloads.negotiate
    assert n(None) == n("") == n("*/*") == n(BROWSER) == payloads.JSON
    assert n(f"{payloads.ARROW}, application/json;q=0.5") == payloads.ARROW
    assert n(f"application/json;q=0.5, {payloads.ARROW}") == payloads.ARROW
    assert n("application/json;q=0, */*;q=0.1") == payloads.ARROW   # JSON refused
    assert n("text/*") == payloads.CSV
    assert n("TEXT/CSV; charset=utf-8") == payloads.CSV
    for refused in ("image/png", "application/json;q=0", "*/*;q=0", "text/html"):
        with pytest.raises(NotAcceptable):
            n(refused)


def _result_with(nonfinite):
    t = np.linspace(0.0, 1.0, 4)
    y = np.ones((4, 6))
    y[1, 2], y[2, 0], y[3, 5] = nonfinite
    e = np.array([1.0, math.nan, 2.0, -math.inf])
    return SimulationResult("plane/chaplygin-ball", {"I1": 1.0}, ("M1", "M2", "M3", "g1",
                            "g2", "g3"), t, y, {"energy": e, "M2": e.copy()},
                            {"steps": 3, "drift": {"energy": math.nan}, "wall_s": 1e-3},
                            "singular", "stopped")


def test_non_finite_numbers_are_null_in_json_and_ieee_in_arrow():
    res = _result_with((math.nan, math.inf, -math.inf))
    raw = payloads.json_bytes(res, 100)
    assert b"NaN" not in raw and b"Infinity" not in raw
    d = json.loads(raw)     # strict JSON: parses with any reader
    assert d["state"][1][2] is None and d["state"][2][0] is None and d["state"][3][5] is None
    assert d["invariants"]["energy"] == [1.0, None, 2.0, None]
    assert d["stats"]["drift"]["energy"] is None and d["stats"]["max_steps"] == 100
    # as the former path (ndarray.tolist() + json.dumps, non-finite -> null) wrote it
    from app.services.payloads import finite as _finite
    old = json.loads(json.dumps(_finite(res.to_json()), allow_nan=False))
    assert {k: v for k, v in d.items() if k != "stats"} == \
        {k: v for k, v in old.items() if k != "stats"}
    tab = arrow_table(payloads.arrow_bytes(res, 100))
    assert math.isnan(tab.column("M3")[1].as_py()) and tab.column("M1")[2].as_py() == math.inf
    assert tab.column("M_squared").null_count == 0
    assert tab.column("energy").to_pylist()[3] == -math.inf
