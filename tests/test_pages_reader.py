"""Pages a reader can use without scripts (issue 11, part B): HTML 404 with navigation for
people, JSON for /api/*."""

import html

import pytest
from fastapi.testclient import TestClient

from app.main import create_app
from app.testing import settings_for_tests
from catalogue.load import load_catalogue

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


@pytest.mark.parametrize("case_id", ["plane/chaplygin-ball", "sphere/borisov-fedorov"])
def test_case_page_holds_its_claims_without_scripts(client, case_id):
    """The HTML as served (no script run) has the title and every claim in words with
    its verdict; the scripts then redraw them."""
    case = load_catalogue().case(case_id)
    r = client.get(f"/case/{case_id}")
    assert r.status_code == 200
    text = r.text
    assert f'<h1 id="case-title">{html.escape(case.title)}</h1>' in text
    assert f"<title>{html.escape(case.title)} — Rolling hierarchy</title>" in text
    assert text.count('<article class="claim ssr"') == len(case.claims)
    # each claim's statement as the API gives it (printed numbers in place of the paper's
    # internal labels)
    for c in client.get(f"/api/cases/{case_id}").json()["claims"]:
        assert html.escape(c["plain"]) in text
    # issue 17: each claim's mark (shape and name) instead of the coarse verdict
    assert text.count("<p>Mark: <strong class=\"badge ") == len(case.claims)
    assert "Loading…" not in text.split('id="claimlist"')[0][-200:]


@pytest.mark.parametrize("case_id", ["plane/chaplygin-ball", "sphere/borisov-fedorov"])
def test_claims_have_visible_permalinks_without_scripts(client, case_id):
    """Issue 17, item 5, in the HTML as served (no script run): every claim's heading
    starts with a ¶ link to its own anchor, named by the claim's kind and printed number
    as the script names it (cite.js), and the anchor is the claim's article."""
    import re

    text = client.get(f"/case/{case_id}").text
    claims = client.get(f"/api/cases/{case_id}").json()["claims"]
    for c in claims:
        anchor = "claim-" + re.sub(r"[^A-Za-z0-9_-]+", "_", c["id"])
        art = text.split(f'<article class="claim ssr" id="{anchor}">', 1)
        assert len(art) == 2, c["id"]
        head = art[1].split("</h3>", 1)[0]
        label = c["kind"].replace("-", " ") + (f' {c["number"]}' if c["number"] else "")
        assert head.startswith(f'<h3><a class="permalink" href="#{anchor}" '), head
        assert f'aria-label="Permalink to the claim {html.escape(label)}">¶</a>' in head
        assert f"{html.escape(label)}: " in head and c["id"] not in head.split('">¶')[1]
    assert text.count('class="permalink"') >= len(claims)


def test_home_page_holds_both_tables_without_scripts(client):
    """Tables 1 and 2 as served: every case column linked, every row labelled, merged
    cells spanning their columns, the cells' words (the script later typesets them)."""
    text = client.get("/").text
    cat = load_catalogue()
    for table in (cat.plane, cat.sphere):
        tid = table.id.value
        part = text.split(f'id="tbl-{tid}"')[1].split("</table>")[0]
        for c in table.cases:
            assert f'href="/case/{c.id}"' in part and html.escape(c.title) in part
        assert part.count('<th scope="row">') == len(table.rows)
        for row in table.rows:
            first = table.cases[0].cells[row.key]
            assert html.escape(first.plain) in part
    assert "Loading Table" not in text
    assert 'colspan="3"' in text.split('id="tbl-plane"')[1].split("</table>")[0]
