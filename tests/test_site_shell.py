"""Every page of the explorer gets the shared head, header and footer from one place
(app/services/site_shell.py): once each, no placeholder left, the current page marked in
the navigation; the static page files hold none of it themselves."""

import re
from pathlib import Path

import pytest
from fastapi.testclient import TestClient

from app.main import create_app
from app.services import site_shell, templates
from app.testing import settings_for_tests

pytestmark = pytest.mark.filterwarnings("ignore::DeprecationWarning")
STATIC = Path(__file__).resolve().parents[1] / "app" / "static"
PAGES = {"/": None, "/errata": "/errata", "/poincare": "/poincare", "/scenes": "/scenes",
         "/work-precision": "/work-precision", "/how-we-check": "/how-we-check",
         "/glossary": "/glossary", "/bibliography": "/bibliography", "/search?q=ball": None,
         "/case/plane/routh-ball": None, "/nowhere": None,
         "/guide/": "/guide/"}   # the guide's page when it is not built (app.testing)


@pytest.fixture(scope="module")
def client():
    with TestClient(create_app(settings_for_tests(warm_workers=False))) as c:
        yield c


@pytest.mark.parametrize("path", list(PAGES))
def test_each_page_has_the_shared_parts_once(client, path):
    html = client.get(path).text
    assert "{{" not in html, re.findall(r"\{\{[^}]*\}\}", html)
    for part in ('<header class="site">', '<nav aria-label="Site">', '<footer class="site">',
                 'name="viewport"', 'href="/static/css/app.css"', 'id="nav-q"'):
        assert html.count(part) == 1, (path, part, html.count(part))
    assert html.index('charset="utf-8"') < html.index("<title>")
    current = re.findall(r'<a href="([^"]+)" aria-current="page">', html)
    assert current == ([PAGES[path]] if PAGES[path] else []), current
    assert [h for h, _ in site_shell.NAV] == re.findall(
        r'<a href="([^"]+)"(?: aria-current="page")?>[^<]*</a>',
        html.split('<nav aria-label="Site">')[1].split("</nav>")[0])[:len(site_shell.NAV)]


def test_static_files_hold_no_copy_of_the_shared_parts():
    for f in STATIC.glob("*.html"):
        text = f.read_text()
        assert "{{head}}" in text and "{{site-footer}}" in text and "{{site-header:" in text
        for copy in ('<header class="site">', 'name="viewport"', "favicon.svg", "css/app.css"):
            assert copy not in text, (f.name, copy)


def test_a_page_without_the_placeholders_is_refused():
    with pytest.raises(ValueError, match="head"):
        templates.render("<html><head></head><body></body></html>")
