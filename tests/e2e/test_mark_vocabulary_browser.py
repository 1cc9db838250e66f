"""Issue 17 in chromium: the home table and a case page show each mark as a shape and a
word (told apart without colour), what goes with it behind a tap, and the counts by mark;
readable at 390 px. The marks come from real checks of two cases (POST /api/verify)."""

import httpx
import pytest
from playwright.sync_api import expect

from solvers.verify import marks as vocab

CASES = ["plane/spherical-inertia", "plane/chaplygin-ball"]
SHAPE = {m.id: m.shape for m in vocab.vocabulary()}
WORD = {m.id: m.word for m in vocab.vocabulary()}


def ready(page):
    page.wait_for_function("document.body?.dataset.ready === '1'")


@pytest.fixture(scope="module")
def checked(server):
    for cid in CASES:
        r = httpx.post(f"{server}/api/verify/{cid}", json={}, timeout=600)
        assert r.status_code == 200, r.text
    return server


def _cell(page, table, row, column):
    return page.locator(f'#tbl-{table} tr.row-{row} td[data-columns="{column}"]')


@pytest.mark.parametrize("width", [1500, 390])
def test_home_table_marks_are_shape_and_word(browser, checked, artifacts, width):
    ctx = browser.new_context(viewport={"width": width, "height": 900}, has_touch=width < 500,
                              bypass_csp=True)
    page = ctx.new_page()
    try:
        page.goto(checked + "/")
        ready(page)
        # the spherical-inertia measure cell (column 7): Table 1's formula, as printed
        cell = _cell(page, "plane", "measure", "7")
        mark = cell.locator("a.cellmark")
        expect(mark.locator(".mk")).to_have_text(SHAPE["as-printed"])
        expect(mark.locator(".mkword")).to_have_text(WORD["as-printed"])
        expect(mark.locator(".sr-only")).to_have_text("holds as printed")
        # the Chaplygin ball's Hamiltonian form (column 1): under a convention, named
        cell = _cell(page, "plane", "hamiltonian_form", "1")
        expect(cell.locator(".mk")).to_have_text(SHAPE["under-convention"])
        expect(cell.locator(".mkword")).to_have_text(WORD["under-convention"])
        why = cell.locator("details.mark-why")
        note = why.locator("p")
        expect(note).not_to_be_visible()
        if width < 500:
            why.locator("summary").tap()
        else:
            why.locator("summary").click()
        expect(note).to_be_visible()
        expect(note).to_contain_text("dx/dτ = {H, x}")
        # readable at this width: the word at least 12 px, upright, the target 24 px
        style = mark.locator(".mkword").evaluate(
            "e => [parseFloat(getComputedStyle(e).fontSize), getComputedStyle(e).fontStyle]")
        assert style[0] >= 12 and style[1] == "normal", style
        box = mark.bounding_box()
        assert box["height"] >= 24 and box["width"] >= 24, box
        # every drawn mark has a shape and a word of the vocabulary, none only a colour
        shapes = page.locator("table.paper .mk").evaluate_all(
            "els => els.map(e => [e.className, e.firstChild.textContent])")
        assert shapes and all(s in SHAPE.values() for _, s in shapes)
        assert all(SHAPE[c.split()[1]] == s for c, s in shapes)
        # the summary counts by mark, never "N of N cases verified"
        summary = page.locator("#mark-summary")
        expect(summary).to_contain_text("cells hold as printed")
        expect(summary).to_contain_text("hold under a stated convention")
        assert "verified" not in page.locator("section.intro").inner_text()
        # the key names every mark with its shape
        for m in vocab.vocabulary():
            expect(page.locator(f".legend .mark.{m.id}").first).to_have_text(m.shape)
        page.screenshot(path=str(artifacts / f"home-marks-{width}.png"))
    finally:
        ctx.close()


@pytest.mark.parametrize("width", [1500, 390])
def test_case_page_marks_and_summary(browser, checked, artifacts, width):
    ctx = browser.new_context(viewport={"width": width, "height": 900}, bypass_csp=True)
    page = ctx.new_page()
    try:
        page.goto(checked + "/case/plane/spherical-inertia")
        ready(page)
        expect(page.locator("#tally #mark-summary")).to_contain_text(
            "Of its 4 table cells: 2 cells hold as printed")
        # counts as shape + count + word
        expect(page.locator("#tally .badge.as-printed").first).to_contain_text(
            f"{SHAPE['as-printed']} ")
        row = page.locator("#row-measure")
        expect(row.locator(".cellverdict")).to_contain_text(
            f"{SHAPE['as-printed']} holds as printed")
        expect(row.locator(".mkword")).to_have_text(WORD["as-printed"])
        # the text's display keeps its misprint: holds after correction, linked to its erratum
        claim = page.locator("#claim-plane_spherical-inertia_measure_omega")
        expect(claim.locator("header .badge")).to_have_text(
            f"{SHAPE['after-correction']} holds after correction")
        link = claim.locator(".marknote a", has_text="erratum")
        expect(link).to_have_attribute("href", "/errata#e-plane/spherical-inertia/measure/omega")
        # an open question is its own mark, not "not checkable"
        expect(page.locator("#claim-plane_spherical-inertia_negative_hamiltonian header .badge")
               ).to_have_text(f"{SHAPE['open']} open in the paper")
        size = claim.locator(".marknote").evaluate(
            "e => [parseFloat(getComputedStyle(e).fontSize), getComputedStyle(e).fontStyle]")
        assert size[0] >= 12 and size[1] == "normal", size
        page.screenshot(path=str(artifacts / f"case-marks-{width}.png"))
    finally:
        ctx.close()
