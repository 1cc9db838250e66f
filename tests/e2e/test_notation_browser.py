"""Symbols and their definitions in chromium: /notation typesets every
entry; each formula on a case page lists its symbols as links to /notation, and a click
opens the definition in place (Escape closes it); a misprinted claim leads with the
corrected formula, the printed one follows labelled "as printed"."""

import json

import httpx
from playwright.sync_api import expect

import solvers.verify.formulas  # noqa: F401  (registers the corrections)
from app.services.views import record
from catalogue.notation import load_notation
from solvers.verify.registry import CORRECTION_NOTES

CASE = "sphere/body-of-revolution"
CLAIM = "sphere/body-of-revolution/measure"


def test_the_notation_page_typesets_every_entry(page, server):
    page.goto(f"{server}/notation")
    entries = page.locator("section.symbol")
    expect(entries).to_have_count(len(load_notation().entries))
    expect(page.locator("#sym-rho0 h2 .katex").first).to_be_visible()
    assert page.locator("section.symbol .tex-fallback").count() == 0
    a = page.locator("#sym-A")
    expect(a).to_contain_text("(1.6), section 1")
    expect(a).to_contain_text("(2.24), section 2")


def _with_correction(detail: dict) -> dict:
    """The case as the API gives it once the check has run: the measure (3.2) misprinted,
    the project's correction holding (the record views.record makes of it)."""
    rec = record({"claim": f"{CLAIM}/corrected", "verdict": "verified", "residual": 1e-15,
                  "origin": "project-correction", "corrects": CLAIM, "mark": "after-correction",
                  "mark_note": "the project's correction holds",
                  "printed": "[project's correction of sphere_revolution_density] "
                             + CORRECTION_NOTES["sphere_revolution_density"]})
    for c in detail["claims"]:
        if c["id"] == CLAIM:
            c["verdict"].update(verdict="fails", mark="after-correction",
                                mark_note="the printed formula has a misprint")
            c["corrections"] = [rec]
    return detail


def test_a_formula_links_its_symbols_and_a_misprint_leads_with_its_correction(page, server):
    detail = _with_correction(httpx.get(f"{server}/api/cases/{CASE}", timeout=30).json())
    page.route(f"{server}/api/cases/{CASE}", lambda route: route.fulfill(
        status=200, content_type="application/json", body=json.dumps(detail)))
    page.goto(f"{server}/case/{CASE}")
    page.wait_for_selector("body[data-ready='1']")
    claim = page.locator(f"#claim-{CLAIM.replace('/', '_')}")
    lead, printed = claim.locator("[data-testid=corrected-lead]"), claim.locator(
        "[data-testid=as-printed]")
    expect(lead).to_contain_text("corrected")
    expect(printed).to_contain_text("as printed")
    # the corrected formula comes first, and is written out (no ellipsis)
    assert lead.bounding_box()["y"] < printed.bounding_box()["y"]
    assert "…" not in lead.inner_text() and "..." not in lead.inner_text()
    # what the correction changes, in words, under the claim
    expect(claim.locator(".correction")).to_contain_text("exponent 1 on (1 − k f₁)")
    # its symbols, each a link to its definition
    sym = claim.locator("p.symbols a.sym[data-sym=rho0]").first
    expect(sym).to_have_attribute("href", "/notation#sym-rho0")
    sym.click()
    box = claim.locator(".symbox")
    expect(box).to_be_visible()
    expect(box).to_contain_text("(3.2), section 3")
    page.keyboard.press("Escape")
    expect(box).to_have_count(0)
    # every symbol of the page, linked in the page's own list
    for s in detail["notation"]:
        expect(page.locator(f'#symbollist a.sym[href="/notation#sym-{s["id"]}"]')).to_have_count(1)


def test_the_new_pages_pass_the_sweeps_rules(page, server):
    """/notation and a case page with its symbol lists and a definition box open: no
    developer words, no internal label, every "(n.m)" a printed number, and axe finds no
    serious or critical violation (the rules of tests/e2e/test_page_sweep_browser.py)."""
    from tests.e2e.test_page_sweep_browser import AXE, AXE_RUN, INTERNAL
    from tests.e2e.test_reader_pages_browser import READER_TEXT, developer_words
    from tests.test_reader_numbers import reader_problems

    for path in ("/notation", f"/case/{CASE}"):
        page.goto(server + path)
        if path.startswith("/case/"):
            page.wait_for_selector("body[data-ready='1']")
            page.locator("p.symbols a.sym").first.click()
            expect(page.locator(".symbox")).to_have_count(1)
        page.wait_for_load_state("networkidle")
        reader = page.evaluate(READER_TEXT)
        assert developer_words(reader) == {}, (path, developer_words(reader))
        assert not INTERNAL.findall(reader) and not reader_problems(reader), path
        page.add_script_tag(path=str(AXE))
        assert page.evaluate(AXE_RUN) == [], path
