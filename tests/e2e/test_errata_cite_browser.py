"""Issue 17, items 4 and 5, in the browser: /errata as a reference table whose index view
fits in about three desktop screens (1500 x 950) with every row behind its own anchor and
both forms typeset; a case page with a Cite box (BibTeX of the paper and of the explorer),
visible claim permalinks and a 'what was checked' box; search results that land on the
claim. The server here verifies on start and finds every case's verdicts in a store of its own,
filled from the session's full verification."""

import re
from datetime import date

import httpx
import pytest
from playwright.sync_api import expect

from tests.e2e.servers import stored_verdicts_server

SCREEN = 950


@pytest.fixture(scope="module")
def verified(catalogue_records, tmp_path_factory):
    """A server that verifies on start and finds every case's verdicts in its store
    (tests/e2e/conftest.py: stored_verdicts_server)."""
    with stored_verdicts_server(catalogue_records, tmp_path_factory.mktemp("verdicts")) as url:
        yield url


def ready(page):
    page.wait_for_function("document.body?.dataset.ready === '1'")


def test_errata_index_fits_three_screens_and_rows_have_anchors(page, verified, artifacts):
    rows = httpx.get(f"{verified}/api/errata").json()
    assert len(rows) > 20                  # the whole paper, not a sample
    page.goto(verified + "/errata")
    ready(page)
    erows = page.locator("#errata-list details.erow")
    expect(erows).to_have_count(len(rows))
    height = page.evaluate("document.documentElement.scrollHeight")
    page.screenshot(path=str(artifacts / "errata-index.png"), full_page=True)
    assert height <= 3 * SCREEN, f"the index view is {height} px, {height / SCREEN:.2f} screens"
    # every row: closed at first, its corrected form typeset (no raw-TeX fallback)
    assert page.locator("#errata-list details.erow[open]").count() == 0
    assert page.locator("#errata-list .corrected .katex").count() == len(rows)
    assert page.locator(".tex-fallback").count() == 0
    # the index by section links every row
    hrefs = page.locator("#index-table a").evaluate_all("els => els.map(a => a.hash)")
    assert {f"#{r['anchor']}" for r in rows} <= set(hrefs)
    # the garbled convention line is gone; the residuals are said in words
    text = page.locator("#conventions-list").text_content()
    assert "read with the project's convention 2" not in text
    assert "Read with the project's convention instead, it fails: residual 2.0" in text
    # Fig. 7's caption, not confirmed, is a finding
    expect(page.locator('#findings-list details.erow[id="f-figure-ris-4"]')).to_contain_text(
        "Fig. 7")


def test_errata_rows_name_claims_not_record_ids(page, verified):
    """Issue 17: every row, opened, names its claim as the case pages do (the case's title,
    the claim's kind and printed number); no record id in what a reader sees (the copyable
    command line aside); the id is the link's target and data-claim."""
    page.goto(verified + "/errata")
    ready(page)
    page.evaluate("document.querySelectorAll('details.erow').forEach((d) => { d.open = true; })")
    text = page.evaluate("""() => {
      const hide = [...document.querySelectorAll('.katex-mathml, annotation, .repro code')];
      hide.forEach((e) => { e.style.display = 'none'; });
      return document.body.innerText; }""")
    ids = re.findall(r"\b(?:plane|sphere)/[a-z0-9-]+(?:/[a-z0-9*-]+)*", text)
    assert not ids, sorted(set(ids))
    rows = [*httpx.get(f"{verified}/api/errata").json(),
            *httpx.get(f"{verified}/api/conventions").json(),
            *httpx.get(f"{verified}/api/findings").json()]
    names = page.locator("a.claimname").evaluate_all(
        "els => els.map((a) => [a.dataset.claim, a.textContent])")
    assert len(names) == len(rows)
    want = {e["claim"]: f"{e['claim_name']} of {e['case_title']}" for e in rows}
    assert {c: t for c, t in names} == want


def test_an_erratum_anchor_opens_its_row(page, verified, artifacts):
    anchor = "e-plane/body-of-revolution/poisson/antigradient"
    page.goto(f"{verified}/errata#{anchor}")
    ready(page)
    row = page.locator(f'details.erow[id="{anchor}"]')
    expect(row).to_have_attribute("open", "")
    expect(row.locator(":scope > summary")).to_contain_text("(2.10)")        # the display corrected
    expect(row.locator(".ebody")).to_be_in_viewport()
    expect(row.locator(".ebody")).to_contain_text("Printed (2.10)")
    assert row.locator(".katex").count() >= 2                      # both forms typeset
    page.screenshot(path=str(artifacts / "errata-row.png"))
    # an index link opens the row it names
    other = page.locator('#index-table a[href^="#e-sphere/"]').first
    target = other.get_attribute("href")[1:]
    other.click()
    expect(page.locator(f'details.erow[id="{target}"]')).to_have_attribute("open", "")


def test_case_page_has_a_cite_box_permalinks_and_what_was_checked(page, verified, artifacts):
    cid = "plane/chaplygin-ball"
    page.goto(f"{verified}/case/{cid}")
    page.wait_for_function("document.body?.dataset.cite === '1'")
    today = date.today().isoformat()
    paper = page.locator('#citebox pre[data-cite="paper"]').text_content()
    assert paper.startswith("@article{") and "doi     = {10.1070/RD2002v007n02ABEH000204}" in paper
    sw = page.locator('#citebox pre[data-cite="software"]').text_content()
    assert sw.startswith("@software{")
    for field in ("author", "title", "version", "year", "url", "urldate"):
        assert re.search(rf"^  {field}\s+= \{{.+\}}", sw, re.M), field
    assert f"url     = {{{verified}/case/{cid}}}" in sw and f"urldate = {{{today}}}" in sw
    json_link = page.locator(f'#citebox a[href="/api/cases/{cid}"]')
    expect(json_link).to_be_visible()
    assert httpx.get(verified + json_link.get_attribute("href")).json()["id"] == cid
    # every claim: a visible permalink and a Cite box with both entries and its own URL
    claims = page.locator("#claimlist article.claim")
    n = claims.count()
    assert n == len(httpx.get(f"{verified}/api/cases/{cid}").json()["claims"])
    expect(page.locator("#claimlist article.claim a.permalink")).to_have_count(n)
    first = claims.first
    link = first.locator("a.permalink")
    expect(link).to_be_visible()
    anchor = first.get_attribute("id")
    link.click()
    assert page.evaluate("location.hash") == f"#{anchor}"
    first.locator("details.cite-claim > summary").click()
    box = first.locator("details.cite-claim")
    assert "@article{" in box.locator('pre[data-cite="paper"]').text_content()
    assert f"url     = {{{verified}/case/{cid}#{anchor}}}" in box.locator(
        'pre[data-cite="software"]').text_content()
    # what was checked: one row per kind of check run, the claims not checked listed
    checked = page.locator("#checkedbox")
    expect(checked.locator("table.checked tbody tr").first).to_be_visible()
    expect(checked).to_contain_text("claims on this page")
    page.locator("#checked").screenshot(path=str(artifacts / "case-checked.png"))
    page.locator("#cite").screenshot(path=str(artifacts / "case-cite.png"))


def test_a_search_result_lands_on_its_claim(page, verified):
    page.goto(f"{verified}/search?q=Routh+integral")
    link = page.locator('[data-testid="claim-results"] a').first
    href = link.get_attribute("href")
    m = re.fullmatch(r"/case/([a-z-]+/[a-z0-9-]+)#(claim-[A-Za-z0-9_-]+)", href)
    assert m, href
    link.click()
    page.wait_for_url(re.compile(re.escape(href) + "$"))
    ready(page)
    target = page.locator(f"#{m[2]}")
    expect(target).to_be_in_viewport()


def test_search_results_show_marks(page, verified):
    """Issue 17: a result shows its claim's mark, shape and word, as the case page does."""
    page.goto(f"{verified}/search?q=Chaplygin")
    results = httpx.get(f"{verified}/api/search", params={"q": "Chaplygin"}).json()["claims"]
    marks = {m["id"]: m for m in httpx.get(f"{verified}/api/how-we-check").json()["marks"]}
    badges = page.locator('[data-testid="claim-results"] li .badge')
    expect(badges).to_have_count(min(len(results), 200))
    shown = badges.all_inner_texts()
    for c, text in zip(results[:200], shown, strict=True):
        assert text == f"{marks[c['mark']]['shape']} {marks[c['mark']]['word']}", (c["id"], text)
    assert any(c["mark"] not in ("pending", "not-checkable") for c in results)


def test_bibliography_cite_box_takes_the_pages_address_and_todays_date(page, verified):
    page.goto(f"{verified}/bibliography")
    sw = page.locator('section.cite pre[data-cite="software"]')
    expect(sw).to_contain_text(f"url     = {{{verified}/bibliography}}")
    expect(sw).to_contain_text(f"urldate = {{{date.today().isoformat()}}}")
    assert page.locator('li[data-status="unresolved"]').count() > 30
    expect(page.locator("#ref-this-paper")).to_contain_text("complete")


def test_a_corrected_claims_cite_box_says_what_was_shown(page, verified):
    """Issue 38: the Cite box of a misprinted claim (the measure (3.2) of a body of
    revolution on a sphere) gives its mark, the corrected formula that holds, the printed
    one labelled as printed, the erratum's address and a key of its own; no claim of the
    case has a note that cites a misprinted formula as checked."""
    import os

    cid = "sphere/body-of-revolution"
    claim = f"{cid}/measure"
    data = httpx.get(f"{verified}/api/cases/{cid}").json()
    rec = next(c for c in data["claims"] if c["id"] == claim)
    assert rec["verdict"]["mark"] == "after-correction"
    corrected = next(r["printed_tex"] for r in rec["corrections"] if r.get("printed_tex"))
    page.goto(f"{verified}/case/{cid}")
    page.wait_for_function("document.body?.dataset.cite === '1'")
    anchor = "claim-" + re.sub(r"[^A-Za-z0-9_-]+", "_", claim)
    art = page.locator(f"#{anchor}")
    box = art.locator("details.cite-claim")
    box.locator(":scope > summary").click()
    expect(box.locator(".cite-mark")).to_contain_text("✎ holds after correction")
    assert box.locator(".cite-holds .katex").count() == 1          # the corrected form, typeset
    expect(box.locator(".cite-shown")).to_contain_text("as printed (fails; misprint)")
    expect(box.locator(f'.cite-erratum a[href="/errata#e-{claim}"]')).to_be_visible()
    sw = box.locator('pre[data-cite="software"]').text_content()
    key = "RollingHierarchy:sphere:body-of-revolution:measure"
    assert sw.startswith(f"@software{{{key},"), sw
    note = re.search(r"^  note\s+= \{(.*)\},?$", sw, re.M)[1]
    assert "Mark: holds after correction" in note
    assert not re.search(r"\\gam(?![a-z])", note) and "\\gamma_3" in note   # macros expanded
    assert "the project's correction: $" in note and "As printed (fails): $" in note
    assert re.sub(r"\s+", " ", corrected).strip()[:40] in note, (corrected, note)
    assert f"{verified}/errata#e-{claim}" in note
    assert "checked by computation" not in note
    assert f"url     = {{{verified}/case/{cid}#{anchor}}}" in sw
    os.makedirs("/tmp/cite-shots", exist_ok=True)
    # the whole claim with its box open, from the full page (the sticky bars at its top)
    r = art.bounding_box()
    y = page.evaluate("window.scrollY")
    page.screenshot(path="/tmp/cite-shots/measure-3.2-cite.png", full_page=True,
                    clip={"x": r["x"], "y": r["y"] + y, "width": r["width"], "height": r["height"]})
    # CSL-JSON and RIS beside the BibTeX, with the same key
    box.locator("details.cite-formats summary").click()
    csl = box.locator('pre[data-cite="csl"]').text_content()
    assert f'"id": "{key}"' in csl and '"type": "software"' in csl
    ris = box.locator('pre[data-cite="ris"]').text_content()
    assert "TY  - COMP" in ris and f"ID  - {key}" in ris and "DO  - 10.1070/" in ris
    # every claim of the case: a key of its own; a misprinted one cited with its mark and
    # correction, never its printed form as checked
    entries = page.locator('details.cite-claim pre[data-cite="software"]').evaluate_all(
        "els => els.map((e) => e.textContent)")
    assert len(entries) == len(data["claims"])
    keys = [re.match(r"@software\{([^,]+),", e)[1] for e in entries]
    assert len(set(keys)) == len(keys)
    errata = {e["claim"] for e in httpx.get(f"{verified}/api/errata").json()
              if e["case"] == cid}
    assert claim in errata
    for c, entry in zip(data["claims"], entries, strict=True):
        note = re.search(r"^  note\s+= \{(.*)\},?$", entry, re.M)[1]
        assert "checked by computation" not in note, (c["id"], note)
        assert note.startswith(f"{data['title']}: the claim ") and " Mark: " in note, note
        if c["id"] in errata:
            assert c["verdict"]["mark"] == "after-correction", c["id"]
            assert "Mark: holds after correction" in note and "As printed (fails): " in note
            assert f"{verified}/errata#e-" in note, (c["id"], note)
