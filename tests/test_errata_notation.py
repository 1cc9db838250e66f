"""/notation defines every symbol of every typeset formula on /errata (misprints, conventions,
findings), and the page links each of them to its definition, as the case pages do
(tests/test_notation.py); the rows of /api/errata, /api/conventions and /api/findings carry
the same lists for the page's script."""

import re

import pytest
from conftest import client_with_verdicts

from app.services.errata_pages import formulas_of
from catalogue.notation import entry_for
from catalogue.symbols import symbols

pytestmark = pytest.mark.filterwarnings("ignore::DeprecationWarning")
ROUTES = ("/api/errata", "/api/conventions", "/api/findings")


@pytest.fixture(scope="module")
def client(catalogue_records):
    with client_with_verdicts(catalogue_records) as c:
        yield c


@pytest.fixture(scope="module")
def rows(client):
    out = {}
    for route in ROUTES:
        r = client.get(route)
        assert r.status_code == 200
        out[route] = r.json()
    assert out["/api/errata"] and out["/api/conventions"], "no rows to check"
    return out


def _ids(e: dict) -> dict[str, set[str]]:
    """role -> the notation entries of that formula's symbols; fails on a symbol that has
    no entry."""
    out = {}
    for role, tex in formulas_of(e):
        ids = set()
        for t in symbols(tex):
            entry = entry_for(t)
            assert entry is not None, f"{e['anchor']}: {t!r} of {tex!r} has no definition"
            ids.add(entry.id)
        out[role] = ids
    return out


def test_every_symbol_of_the_errata_formulas_is_defined(rows):
    n = sum(len(ids) for route in ROUTES for e in rows[route] for ids in _ids(e).values())
    assert n > 0


def test_the_api_lists_each_formulas_symbols_with_links(rows):
    for route in ROUTES:
        for e in rows[route]:
            want = _ids(e)
            got = {role: {s["id"] for s in refs} for role, refs in e["symbols"].items()}
            assert got == want, (route, e["anchor"])
            for refs in e["symbols"].values():
                assert all(s["href"] == f"/notation#sym-{s['id']}" for s in refs)


def test_the_page_links_each_symbol_to_its_definition(client, rows):
    """The page as served (no script run): each row's formulas with their symbols."""
    html = client.get("/errata").text
    notation = client.get("/notation").text
    for route in ROUTES:
        for e in rows[route]:
            m = re.search(rf'<details[^>]*id="{re.escape(e["anchor"])}".*?</details>', html,
                          re.S)
            assert m, e["anchor"]
            for ids in _ids(e).values():
                for sid in ids:
                    assert f'href="/notation#sym-{sid}"' in m[0], (e["anchor"], sid)
                    assert f'id="sym-{sid}"' in notation, sid
