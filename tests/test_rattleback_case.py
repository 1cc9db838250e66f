"""The rattleback is a case like the others though no column of the paper's tables: listed
by GET /api/cases and `rolling cases`, with a page /case/plane/rattleback, and runnable."""

import subprocess
import sys

import pytest
from fastapi.testclient import TestClient

from app.main import create_app
from app.testing import settings_for_tests
from solvers.models.cases import registry

pytestmark = pytest.mark.filterwarnings("ignore::DeprecationWarning")
CID = "plane/rattleback"


@pytest.fixture(scope="module")
def client():
    with TestClient(create_app(settings_for_tests(max_steps=20_000))) as c:
        yield c


def test_listed_by_the_api_with_its_parameters(client):
    listed = {c["id"]: c for c in client.get("/api/cases").json()}
    c = listed[CID]
    assert c["in_tables"] is False and c["table"] is None and c["href"] == f"/case/{CID}"
    assert {p["name"] for p in c["params"]} == set(registry()[CID].param_names)
    assert next(p for p in c["params"] if p["name"] == "delta")["units"] == "radians"
    d = client.get(f"/api/cases/{CID}")
    assert d.status_code == 200 and d.json()["id"] == CID


def test_listed_by_the_command_line():
    proc = subprocess.run([sys.executable, "-m", "app.cli", "cases"], capture_output=True,
                          text=True, timeout=120)
    assert proc.returncode == 0, proc.stderr[-2000:]
    line = next(x for x in proc.stdout.splitlines() if x.startswith(CID))
    assert "Rattleback" in line


def test_has_a_page_and_runs(client):
    r = client.get(f"/case/{CID}")
    assert r.status_code == 200 and "Rattleback" in r.text
    run = client.post("/api/simulate", json={"case": CID, "example": True, "t_end": 1.0,
                                             "samples": 5})
    assert run.status_code == 200 and run.json()["status"] == "ok"
    assert run.json()["provenance"]["permalink"].split("?")[0].endswith(f"/case/{CID}")
