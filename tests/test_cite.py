"""Cite and link (issue 17, item 5): every reference complete or marked unresolved, the
BibTeX of the paper (with its DOI) and of the explorer (author, year, version, URL, access
date), search results that link to the claim's anchor."""

import html
import re
from typing import get_args

import pytest
from fastapi.testclient import TestClient

from app import __version__
from app.main import create_app
from app.services import reader_pages
from app.testing import settings_for_tests
from catalogue.load import load_catalogue
from catalogue.schema import Reference, SourceKind

pytestmark = pytest.mark.filterwarnings("ignore::DeprecationWarning")

# entries resolved from a source that was read (catalogue/references.yaml, `checked_in`):
# the API and the page must count what the data holds
COMPLETE = sum(r.status == "complete" for r in load_catalogue().references)
# the kinds of source an entry may be checked in: the catalogue's own list, one definition
KINDS = get_args(SourceKind)


@pytest.fixture(scope="module")
def client():
    with TestClient(create_app(settings_for_tests(warm_workers=False))) as c:
        yield c


def test_every_reference_is_complete_or_marked_unresolved(client):
    refs = client.get("/api/references").json()
    assert len(refs) == len(load_catalogue().references) > 30
    for r in refs:
        assert r["status"] in ("complete", "unresolved"), r["id"]
        full = (r["authors"] and r["title"] and r["journal"] and (r["year"] or r["years"])
                and (r["form"] != "article" or (r["volume"] and r["pages"]))
                and r["checked_in"])
        assert (r["status"] == "complete") == bool(full), r["id"]
        assert (r["missing"] == []) == (r["status"] == "complete"), r["id"]
    paper = next(r for r in refs if r["id"] == "this-paper")
    assert paper["status"] == "complete" and paper["doi"] == reader_pages.PAPER_DOI
    assert paper["journal"] == "Regular and Chaotic Dynamics" and paper["volume"] == "7"
    # complete only from a source that was read, named with its kind, address and access
    complete = [r for r in refs if r["status"] == "complete"]
    assert len(complete) == COMPLETE
    for r in complete:
        assert r["checked_in"], r["id"]
        for c in r["checked_in"]:
            assert c["kind"] in KINDS and c["access"] in ("full", "abstract", "snippet")
            assert c["url"].startswith(("http://", "https://")) and c["source"], r["id"]
        assert r["id"] == "this-paper" or r["identity"], r["id"]
        assert not r["candidate"], r["id"]
    # an unresolved entry says what is missing, and a candidate is never counted
    for r in refs:
        if r["status"] == "unresolved":
            assert r["missing"], r["id"]
    assert not any("suggests" in (r["remarks"] or "") for r in refs)


def test_a_status_that_does_not_match_the_entry_is_refused():
    base = {"id": "x1", "cite_key": "x1", "authors": ["A. Author"], "authors_source": "text",
            "years": [1900], "cited_for": ["a test"], "form": "book"}
    with pytest.raises(ValueError, match="missing"):
        Reference.model_validate({**base, "status": "complete"})     # no title, no journal
    checked = [{"source": "a list", "kind": "the publisher's record",
                "url": "http://example.org/x", "access": "abstract"}]
    with pytest.raises(ValueError, match="checked source"):     # all fields, nothing read
        Reference.model_validate({**base, "title": "T", "journal": "J", "status": "complete"})
    with pytest.raises(ValueError, match="identity"):           # read, but not tied to the key
        Reference.model_validate({**base, "title": "T", "journal": "J",
                                  "checked_in": checked, "status": "complete"})
    with pytest.raises(ValueError, match="missing nothing"):
        Reference.model_validate({**base, "title": "T", "journal": "J", "identity": "why",
                                  "checked_in": checked, "status": "unresolved"})
    with pytest.raises(ValueError, match="http"):
        Reference.model_validate({**base, "status": "unresolved",
                                  "checked_in": [{**checked[0], "url": "somewhere"}]})
    assert Reference.model_validate({**base, "status": "unresolved"}).missing == [
        "title", "journal", "checked source"]


def test_bibliography_page_says_complete_or_unresolved(client):
    page = client.get("/bibliography").text
    for r in load_catalogue().references:
        m = re.search(rf'<li id="ref-{re.escape(r.id)}" data-status="(\w+)">(.*?)</li>', page,
                      re.S)
        assert m and m[1] == r.status, r.id
        if r.status == "unresolved":
            assert "unresolved" in m[2] and "missing: " + ", ".join(r.missing) in m[2]
    n = len(load_catalogue().references)
    assert f"{COMPLETE} complete, {n - COMPLETE} unresolved." in page
    for r in load_catalogue().references:
        for c in r.checked_in:      # every complete entry shows where it was checked
            assert f'href="{html.escape(c.url)}"' in page, r.id
    assert "Key suggests" not in page
    assert "authors not named in the paper … Key" not in page


def test_bibtex_of_the_paper_and_of_the_explorer(client):
    paper = reader_pages.bibtex_paper()
    assert paper.startswith("@article{BorisovMamaev2002,")
    for field in ("author", "title", "journal", "volume", "number", "pages", "year", "doi"):
        assert re.search(rf"^  {field}\s+= \{{.+\}},?$", paper, re.M), field
    assert reader_pages.PAPER_DOI in paper and "Regular and Chaotic Dynamics" in paper
    from datetime import date
    sw = reader_pages.bibtex_project("http://example.org/case/plane/chaplygin-ball",
                                     date(2026, 1, 2))
    assert sw.startswith("@software{RollingHierarchy:case:plane:chaplygin-ball,")   # the page's key
    assert "author  = {{rolling-hierarchy contributors}}" in sw
    assert f"version = {{{__version__}}}" in sw and "year    = {2026}" in sw
    assert "url     = {http://example.org/case/plane/chaplygin-ball}" in sw
    assert "urldate = {2026-01-02}" in sw
    d = client.get("/api/cite").json()
    assert d["paper"]["fields"]["doi"] == reader_pages.PAPER_DOI
    assert d["software"]["fields"]["version"] == __version__
    assert d["software"]["fields"]["author"] == "{rolling-hierarchy contributors}"


def test_search_results_link_to_the_claim(client):
    r = client.get("/api/search", params={"q": "Chaplygin"}).json()
    assert r["claims"]
    for c in r["claims"]:
        anchor = "claim-" + re.sub(r"[^A-Za-z0-9_-]+", "_", c["id"])
        assert c["href"] == f"/case/{c['case']}#{anchor}"
    page = client.get("/search", params={"q": "chaplygin"}).text
    first = r["claims"][0]
    assert f'href="{first["href"]}"' in page


def test_keys_are_stable_unique_and_bibtex_legal():
    """Issue 38: one key per page and claim, derived from its id, in characters BibTeX reads;
    the same rule as cite.js citeKey."""
    key = reader_pages.cite_key
    assert key("sphere/body-of-revolution/measure") == \
        "RollingHierarchy:sphere:body-of-revolution:measure"
    assert key("") == key("/") == "RollingHierarchy"
    assert key("/bibliography") == "RollingHierarchy:bibliography"
    ids = [c.id for c in load_catalogue().claims()]
    keys = [key(i) for i in ids]
    assert len(set(keys)) == len(ids)
    for k in keys:
        assert re.fullmatch(r"RollingHierarchy:[A-Za-z0-9_.:-]+", k), k
    js = open("app/static/js/cite.js", encoding="utf-8").read()
    assert 'replace(/[^A-Za-z0-9_.-]+/g, ":")' in js


def test_cite_data_gives_the_public_url_the_version_and_the_marks(monkeypatch):
    with TestClient(create_app(settings_for_tests(
            warm_workers=False, public_url="https://example.org/rh/"))) as c:
        d = c.get("/api/cite").json()
    assert d["public_url"] == "https://example.org/rh" and d["version"] == __version__
    assert d["marks"]["after-correction"] == {"shape": "✎", "name": "holds after correction"}
    # the server-built boxes: the configured address, and the page's own key
    from app.core import config
    monkeypatch.setenv("ROLLING_PUBLIC_URL", "https://example.org/rh")
    config.get_settings.cache_clear()
    try:
        sw = reader_pages.bibtex_project("/bibliography")
    finally:
        config.get_settings.cache_clear()
    assert sw.startswith("@software{RollingHierarchy:bibliography,")
    assert "url     = {https://example.org/rh/bibliography}" in sw
