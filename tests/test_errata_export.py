"""/errata on the server (issue 38, item 7), on the verdicts of every case: misprints counted
apart from the inherited rows that repeat one; an index that names each display once with a
link to each of its rows; the whole table in the HTML (readable without scripts); CSV and
BibTeX exports."""

import csv
import io
import re
from html import unescape

import pytest
from conftest import client_with_verdicts
from fastapi.testclient import TestClient

from app.main import create_app
from app.services import errata_pages
from app.testing import settings_for_tests

pytestmark = pytest.mark.filterwarnings("ignore::DeprecationWarning")


@pytest.fixture(scope="module")
def client(catalogue_records):
    with client_with_verdicts(catalogue_records) as c:
        yield c


@pytest.fixture(scope="module")
def rows(client):
    return client.get("/api/errata").json()


def text_of(html: str) -> str:
    html = re.sub(r"<script.*?</script>", "", html, flags=re.S)
    return unescape(re.sub(r"<[^>]+>", "", html))


def test_misprints_are_counted_apart_from_inherited_rows(client, rows):
    inherited = [e for e in rows if e["kind"] == "inherited"]
    own = [e for e in rows if e["kind"] == "misprint"]
    assert inherited and own and len(own) + len(inherited) == len(rows)
    n = errata_pages.counts(rows)
    assert n["inherited"] == len(inherited) and n["rows"] == len(rows)
    assert n["misprints"] == len({errata_pages.misprint_key(e) for e in own}) <= len(own)
    page = client.get("/errata").text
    status = re.search(r'<p class="status" id="errata-status"[^>]*>(.*?)</p>', page, re.S)[1]
    want = f"{n['misprints']} misprints"
    assert unescape(status).startswith(want), status
    assert f"and {len(inherited)} inherited rows that repeat one" in unescape(status)
    # no longer every row counted as a misprinted formula
    assert f"{len(rows)} misprinted formulas" not in page


def test_the_index_names_each_display_once_and_links_every_row(client, rows):
    page = client.get("/errata").text
    index = re.search(r'<div id="index-table">(.*?)</div>\s*</nav>', page, re.S)[1]
    for tr in re.findall(r"<tr id=\"index-[^\"]+\">.*?</tr>", index, re.S):
        cells = re.findall(r"<td>(.*?)</td>", tr, re.S)
        labels = re.findall(r'<span class="idx"><a [^>]*>([^<]+)</a>', cells[0])
        assert len(labels) == len(set(labels)), labels     # each display once
        assert "(3.14) (3.14)" not in text_of(cells[0])
    hrefs = set(re.findall(r'href="#([^"]+)"', index))
    assert {e["anchor"] for e in rows} <= hrefs             # every row still linked
    # a display with several rows links each of them, numbered
    by_display: dict = {}
    for e in rows:
        by_display.setdefault((e["section"], e["corrected_display"]), []).append(e)
    shared = [es for es in by_display.values() if len(es) > 1]
    assert shared
    es = shared[0]
    assert f"({len(es)} rows: " in index


def test_the_page_reads_without_scripts(client, rows):
    page = client.get("/errata").text
    assert "Loading…" not in page
    text = text_of(page)
    for e in rows:
        assert f'id="{e["anchor"]}"' in page
        assert e["corrected_display"] in text and e["change"] in text
    # the formulas as their TeX source, the claim linked as the case pages name it
    e = next(e for e in rows if e["claim"] == "sphere/body-of-revolution/measure")
    row = re.search(rf'<details class="erow ssr" id="{re.escape(e["anchor"])}".*?</details>',
                    page, re.S)[0]
    assert unescape(row).count(e["corrected_tex"]) == 1
    assert f"{e['claim_name']} of {e['case_title']}" in text_of(row)
    for conv in client.get("/api/conventions").json():
        assert f'id="{conv["anchor"]}"' in page
    for f in client.get("/api/findings").json():
        assert f'id="{f["anchor"]}"' in page
    assert 'href="/errata.csv"' in page and 'href="/errata.bib"' in page


def test_csv_export_has_a_line_per_row(client, rows):
    r = client.get("/errata.csv")
    assert r.status_code == 200 and r.headers["content-type"].startswith("text/csv")
    lines = list(csv.DictReader(io.StringIO(r.text)))
    assert [x["anchor"] for x in lines] == [e["anchor"] for e in rows]
    base = "http://testserver"
    for x, e in zip(lines, rows, strict=True):
        assert x["url"] == f"{base}/errata#{e['anchor']}"
        assert x["kind"] == e["kind"] and x["corrected_tex"] == e["corrected_tex"]
        assert x["claim"] == e["claim"] and x["change"] == e["change"]


def test_bibtex_export_has_one_entry_per_misprint(client, rows):
    r = client.get("/errata.bib")
    assert r.status_code == 200 and "bibtex" in r.headers["content-type"]
    entries = re.findall(r"^@(\w+)\{([^,]+),", r.text, re.M)
    assert entries[0] == ("article", "BorisovMamaev2002")
    misc = [k for t, k in entries if t == "misc"]
    assert len(misc) == errata_pages.counts(rows)["misprints"] == len(set(misc))
    for k in misc:
        assert re.fullmatch(r"RollingHierarchy:errata:[A-Za-z0-9_.:-]+", k), k
    assert r.text.count("{") == r.text.count("}")          # every entry closes
    assert "related      = {BorisovMamaev2002}" in r.text
    e = next(e for e in rows if e["claim"] == "sphere/body-of-revolution/measure")
    entry = r.text[r.text.index("@misc{RollingHierarchy:errata:sphere:body-of-revolution:measure"):]
    entry = entry[:entry.index("\n}\n")]
    assert f"url          = {{http://testserver/errata#{e['anchor']}}}" in entry
    assert "As printed (fails)" in entry and "Corrected, checked by computation" in entry
    # formulas a citing document can typeset: the paper's own macros expanded
    for name in errata_pages.paper_macros():
        assert not re.search(re.escape(name) + r"(?![A-Za-z])", r.text), name
    assert "\\gamma_3" in entry


def test_the_paper_macros_expand_as_on_the_pages():
    expand = errata_pages.expand
    assert expand(r"\pt{H}{x_j} + \gam_3 \br \bs r \gamma") == \
        r"\frac{\partial H}{\partial x_j} + \gamma_3 \boldsymbol{r} \boldsymbol r \gamma"
    assert errata_pages._inline("a &= b\\\\ c &= d\\\\") == \
        r"$\begin{aligned}a &= b\\ c &= d\end{aligned}$"


def test_a_public_url_is_used_by_the_exports(catalogue_records):
    app = create_app(settings_for_tests(warm_workers=False,
                                        public_url="https://example.org/rolling/"))
    with TestClient(app) as c:
        store = app.state.verdicts
        cid = "sphere/body-of-revolution"
        store.records[cid] = [dict(r) for r in catalogue_records if r["case"] == cid]
        text = c.get("/errata.csv").text
        assert "https://example.org/rolling/errata#e-sphere/body-of-revolution/measure" in text
        assert c.get("/api/cite").json()["public_url"] == "https://example.org/rolling"


def test_the_page_is_kept_until_the_verdicts_change(catalogue_records, tmp_path):
    app = create_app(settings_for_tests(warm_workers=False, cache_dir=tmp_path))
    with TestClient(app) as c:
        pages, store = app.state.pages, app.state.verdicts
        empty = c.get("/errata").text
        assert "No misprint found yet." in empty and "Loading…" not in empty
        n = pages.renders
        assert c.get("/errata").text == empty and pages.renders == n
        cid = "sphere/body-of-revolution"
        store.put(cid, [dict(r) for r in catalogue_records if r["case"] == cid])
        page = c.get("/errata").text
        assert pages.renders == n + 1 and 'id="e-sphere/body-of-revolution/measure"' in page
