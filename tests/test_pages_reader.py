"""Pages a reader can use without scripts (issue 11, part B): HTML 404 with navigation for
people, JSON for /api/*."""

import pytest
from fastapi.testclient import TestClient

from app.main import create_app
from app.testing import settings_for_tests

pytestmark = pytest.mark.filterwarnings("ignore::DeprecationWarning")


@pytest.fixture(scope="module")
def client():
    with TestClient(create_app(settings_for_tests(warm_workers=False))) as c:
        yield c


@pytest.mark.parametrize("path", ["/no-such-page", "/case", "/static/nope.css",
                                  "/poincare/extra"])
def test_unknown_addresses_get_an_html_page_with_navigation(client, path):
    r = client.get(path)
    assert r.status_code == 404 and r.headers["content-type"].startswith("text/html")
    assert '<nav aria-label="Site">' in r.text and 'href="/poincare"' in r.text
    assert "Page not found" in r.text or "No such case" in r.text


def test_the_message_is_escaped(client):
    r = client.get("/<script>alert(1)</script>")
    assert r.status_code == 404 and "<script>alert" not in r.text


@pytest.mark.parametrize("path", ["/api/nope", "/api/cases/plane/nope", "/api"])
def test_unknown_api_addresses_stay_json(client, path):
    r = client.get(path)
    assert r.status_code == 404 and r.headers["content-type"] == "application/json"
    assert r.json()["detail"]
