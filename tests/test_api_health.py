"""GET /api/health (app/api/routes/health.py)."""

import pytest
from fastapi.testclient import TestClient

from app.main import create_app
from app.testing import settings_for_tests

pytestmark = pytest.mark.filterwarnings("ignore::DeprecationWarning")


@pytest.fixture(scope="module")
def client():
    with TestClient(create_app(settings_for_tests(warm_workers=False))) as c:
        yield c


def test_health_answers_with_pool_and_limits(client):
    r = client.get("/api/health")
    assert r.status_code == 200
    h = r.json()
    assert h["status"] == "ok"
    assert h["pool"]["workers"] == 2 and h["pool"]["running"] == 0
    assert h["limits"]["deadline_s"] == 20.0
    assert h["verification"]["cases_total"] == 16


def test_openapi_and_docs(client):
    spec = client.get("/openapi.json").json()
    paths = spec["paths"]
    for p in ("/api/cases", "/api/cases/{case_id}", "/api/tables/{table_id}", "/api/simulate",
              "/api/verify/{case_id}", "/api/health", "/api/scene", "/api/validate"):
        assert p in paths, p
    assert "503" in paths["/api/simulate"]["post"]["responses"]
    assert "422" in paths["/api/simulate"]["post"]["responses"]
    assert client.get("/docs").status_code == 200
