"""The explorer's pages and downloads (app/api/routes/pages.py, catalogue.py): everything
a browser needs is served locally (no CDN)."""

import json
import re

import pytest
import yaml
from fastapi.testclient import TestClient

from app.main import create_app
from app.testing import settings_for_tests
from catalogue.load import load_catalogue

pytestmark = pytest.mark.filterwarnings("ignore::DeprecationWarning")


@pytest.fixture(scope="module")
def client():
    with TestClient(create_app(settings_for_tests(warm_workers=False))) as c:
        yield c


def test_home_and_case_pages(client):
    home = client.get("/")
    assert home.status_code == 200 and "text/html" in home.headers["content-type"]
    assert "Table 1" in home.text
    page = client.get("/case/plane/chaplygin-ball")
    assert page.status_code == 200 and 'id="simform"' in page.text
    missing = client.get("/case/plane/no-such-case")
    assert missing.status_code == 404 and "No such case" in missing.text


@pytest.mark.parametrize("page", ["/", "/case/sphere/borisov-fedorov"])
def test_every_asset_is_local_and_served(client, page):
    html = client.get(page).text
    refs = re.findall(r'(?:src|href)="([^"#]+)"', html)
    assert refs
    for ref in refs:
        if ref.startswith("https://doi.org/"):   # the Cite box links the paper's DOI
            continue
        assert ref.startswith("/"), f"{ref} is not served by the app"
        # /errata is the verdicts branch's page, linked from the navigation
        if ref.startswith("/docs") or ref.startswith("/#") or ref == "/errata":
            continue
        assert client.get(ref).status_code == 200, ref


def test_scripts_import_only_local_modules(client):
    for name in ("home", "case", "plots", "scene", "latex", "api", "marks"):
        js = client.get(f"/static/js/{name}.js")
        assert js.status_code == 200
        for target in re.findall(r'from "([^"]+)"', js.text):
            assert target.startswith("./")
            assert client.get(f"/static/js/{target[2:]}").status_code == 200
        assert "http://" not in js.text and "https://" not in js.text


def test_katex_fonts_are_vendored(client):
    css = client.get("/static/vendor/katex/katex.min.css").text
    fonts = set(re.findall(r"url\((fonts/[^)]+\.woff2)\)", css))
    assert fonts
    for f in fonts:
        assert client.get(f"/static/vendor/katex/{f}").status_code == 200


def test_plotly_from_the_installed_package(client):
    r = client.get("/vendor/plotly.min.js")
    assert r.status_code == 200 and "javascript" in r.headers["content-type"]
    assert r.content.lstrip().startswith(b"/**") and len(r.content) > 1_000_000


def test_catalogue_downloads(client):
    j = client.get("/api/catalogue")
    assert j.status_code == 200
    data = json.loads(j.content)
    y = client.get("/api/catalogue.yaml")
    assert y.status_code == 200 and "attachment" in y.headers["content-disposition"]
    assert yaml.safe_load(y.content) == data
    assert len([c for t in ("plane", "sphere") for c in data[t]["cases"]]) == len(
        load_catalogue().cases())


def test_api_docs_are_served_without_a_cdn(client):
    html = client.get("/docs").text
    assert "cdn" not in html.lower()
    for ref in re.findall(r"(?:url|href|src)[:=]\s*['\"]([^'\"]+)['\"]", html):
        if ref.startswith("/"):
            assert client.get(ref).status_code == 200, ref
        else:
            assert not ref.startswith("http"), ref
    assert "/static/vendor/swagger-ui/swagger-ui-bundle.js" in html
