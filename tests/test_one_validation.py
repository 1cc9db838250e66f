"""One validation, three faces: the command line refuses what the API refuses, in the
API's words and before any work; the OpenAPI schema says the bounds validation holds
(a request valid by the schema is not refused for them); every POST is JSON."""

import json
import subprocess
import sys
import time

import jsonschema_rs
import pytest
from fastapi.testclient import TestClient

from app.main import create_app
from app.schemas.simulate import MAX_SAMPLES, T_END_MIN
from app.testing import settings_for_tests

pytestmark = pytest.mark.filterwarnings("ignore::DeprecationWarning")

RUN = {"case": "plane/chaplygin-ball", "example": True, "t_end": 1.0, "samples": 5}
MAP = {"case": "plane/chaplygin-ball", "example": True, "trajectories": 1, "points": 3}
SIMULATE_OPS = ["/api/simulate", "/api/validate", "/api/scene", "/api/simulate/compiles",
                "/api/scene/compiles"]


@pytest.fixture(scope="module")
def client():
    with TestClient(create_app(settings_for_tests(warm_workers=False))) as c:
        yield c


def _post(client, path, body):
    """JSON as Python writes it: Infinity and NaN too (the API refuses them by name)."""
    return client.post(path, content=json.dumps(body),
                       headers={"content-type": "application/json"})


def rolling(*args, timeout=120):
    t0 = time.monotonic()
    proc = subprocess.run([sys.executable, "-m", "app.cli", *args], capture_output=True,
                          text=True, timeout=timeout)
    return proc, time.monotonic() - t0


def _one_line(proc) -> str:
    assert proc.returncode == 2, (proc.returncode, proc.stderr[-2000:])
    lines = [ln for ln in proc.stderr.splitlines() if ln.strip()]
    assert len(lines) == 1 and lines[0].startswith("error: "), proc.stderr[-2000:]
    assert "Warning" not in proc.stderr and "Traceback" not in proc.stderr
    return lines[0].removeprefix("error: ")


# --- the command line: the API's bounds and words ---------------------------------------

@pytest.mark.parametrize(("flag", "value", "field"), [
    ("--t-end", "1e308", "t_end"),       # before: 19.7 s of CPU, then exit 3
    ("--t-end", "5e-324", "t_end"),
    ("--t-end", "inf", "t_end"),
    ("--samples", "1", "samples"),
    ("--samples", str(MAX_SAMPLES + 1), "samples"),
    ("--rtol", "0.5", "rtol"),
    ("--atol", "0", "atol"),
])
def test_simulate_refuses_as_the_api_does(client, flag, value, field):
    proc, seconds = rolling("simulate", "plane/chaplygin-ball", "--example", flag, value)
    line = _one_line(proc)
    body = {**RUN, field: float(value) if field != "samples" else int(value)}
    api = _post(client, "/api/validate", body)
    assert api.status_code == 422, api.text
    assert line == api.json()["detail"]
    # refused before anything runs (the imports only; a loaded machine is slower)
    assert seconds < 15, seconds


@pytest.mark.parametrize(("flag", "value", "field"), [
    ("--energy", "1e308", "energy"),     # before: numpy warnings and an internal message
    ("--energy", "nan", "energy"),
    ("--rtol", "1e-2", "rtol"),
    ("--direction", "2", "direction"),
])
def test_poincare_refuses_as_the_api_does(client, flag, value, field):
    proc, _ = rolling("poincare", "plane/chaplygin-ball", "--example", "--trajectories", "1",
                      "--points", "3", flag, value)
    line = _one_line(proc)
    api = _post(client, "/api/poincare", {**MAP, field: float(value)
                                         if field != "direction" else int(value)})
    assert api.status_code == 422, api.text
    assert line == api.json()["detail"]


def test_a_bound_is_said_as_a_person_writes_it(client):
    r = client.post("/api/validate", json={**RUN, "t_end": 5e-324})
    assert r.status_code == 422
    assert r.json()["detail"] == "t_end = 5e-324: must be greater than or equal to 1e-300"
    r = client.post("/api/validate", json={**RUN, "t_end": 1e8})
    assert r.json()["detail"] == "t_end = 100000000.0: must be less than or equal to 10000000"


# --- the schema says the bounds -------------------------------------------------------

def _validator(client, name):
    doc = client.get("/openapi.json").json()
    schema = {**doc["components"]["schemas"][name], "components": doc["components"]}
    return jsonschema_rs.Draft202012Validator(schema)


@pytest.mark.parametrize("path", SIMULATE_OPS)
def test_t_end_at_the_schemas_minimum_is_served(client, path):
    """5e-324 was valid by the schema and refused by 6 operations; the schema's minimum
    now holds MAX_SAMPLES distinct sample times."""
    doc = client.get("/openapi.json").json()
    for name in ("SimulateRequest", "SceneRequest"):
        assert doc["components"]["schemas"][name]["properties"]["t_end"]["minimum"] == T_END_MIN
    body = {**RUN, "t_end": T_END_MIN, "samples": MAX_SAMPLES}
    if "scene" in path:     # a scene's samples are bounded by the server (max_samples)
        body["samples"] = 2
    if path in ("/api/validate", "/api/simulate/compiles", "/api/scene/compiles"):
        r = client.post(path, json=body)
        assert r.status_code == 200, r.text
    r = client.post(path, json={**body, "t_end": 5e-324})
    assert r.status_code == 422 and ["body", "t_end"] in [e["loc"] for e in r.json()["errors"]]


@pytest.mark.parametrize(("name", "body"), [
    ("PoincareRequest", {"case": "plane/ellipsoid"}),
    ("PoincareRequest", {"case": "sphere/flat-base", "example": True}),
    ("PoincareRequest", {"case": "plane/chaplygin-ball", "params": {"q": 1}, "example": True}),
    ("SimulateRequest", {"case": "plane/ellipsoid", "params": {}, "state": [0, 0, 1, 0, 0, 1],
                         "t_end": 1}),
    ("SimulateRequest", {"case": "sphere/flat-base", "example": True, "t_end": 1,
                         "state": [0, 0, 1, 0, 0, 1]}),
    ("SimulateRequest", {"case": "plane/chaplygin-ball", "example": True, "t_end": 5e-324}),
])
def test_the_schema_refuses_what_validation_refuses(client, name, body):
    v = _validator(client, name)
    assert not v.is_valid(body), body
    path = "/api/poincare" if name == "PoincareRequest" else "/api/validate"
    r = client.post(path, json=body)
    assert r.status_code == 422, r.text


@pytest.mark.parametrize(("name", "body"), [
    ("PoincareRequest", {"case": "plane/ellipsoid", "example": True, "trajectories": 1,
                         "points": 2}),
    ("PoincareRequest", {"case": "plane/chaplygin-ball", "trajectories": 1, "points": 2,
                         "params": {"I1": 1, "I2": 2, "I3": 3, "m": 1, "R": 1}}),
    ("SimulateRequest", {**RUN, "case": "sphere/flat-base"}),
    ("SimulateRequest", {"case": "plane/chaplygin-ball", "t_end": 1,
                         "params": {"I1": 1, "I2": 2, "I3": 3, "m": 1, "R": 1, "eps": 0},
                         "state": [0.5, -0.3, 0.8, 0.3, 0.4, 0.8660254037844386]}),
])
def test_the_schema_still_takes_what_validation_takes(client, name, body):
    assert _validator(client, name).is_valid(body), body
    if name == "SimulateRequest":
        r = client.post("/api/validate", json=body)
        assert r.status_code == 200, r.text


@pytest.mark.parametrize(("path", "body"), [
    ("/api/validate", {**RUN, "samples": 7.0}),
    ("/api/scene/compiles", {**RUN, "frames": 5.0}),
    ("/api/poincare", {**MAP, "points": 3.0, "trajectories": 1.0, "seed": 2.0,
                       "direction": -1.0}),
])
def test_an_integer_written_with_a_point_is_an_integer(client, path, body):
    """JSON Schema's integer includes 7.0 (schemathesis sent samples: 19999.0 and got
    422 "must be an integer": a schema-valid request refused); 7.5, "7" and true stay
    refused."""
    assert _post(client, path, body).status_code == 200, _post(client, path, body).text
    for bad in (7.5, "7", True):
        r = _post(client, "/api/validate", {**RUN, "samples": bad})
        assert r.status_code == 422 and "samples" in r.json()["detail"], r.text
