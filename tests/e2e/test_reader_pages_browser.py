"""The explorer as a reference (issue 11, part A) in chromium: printed equation numbers on
case pages, no internal label in any page's visible text (after the scripts ran), search
finding both Chaplygin balls, a glossary tooltip that opens on click/tap."""

import re
from html import unescape

import httpx
from playwright.sync_api import expect

from tests.e2e.site import internal_label_re, project_pages

INTERNAL = internal_label_re()     # every label of the seed and of the catalogue's data


def ready(page):
    page.locator("body[data-ready='1']").wait_for(state="attached")


def test_case_page_shows_printed_equation_numbers(page, server):
    page.goto(server + "/case/plane/chaplygin-ball")
    ready(page)
    claims = page.locator("#claimlist")
    expect(claims).to_contain_text("(2.24)")
    expect(claims).to_contain_text("(2.23)")
    labels = page.locator("#claimlist .claim header .label").all_inner_texts()
    assert labels and all(re.fullmatch(r"\(\d\.\d+\)", x) for x in labels), labels
    # developer text sits behind the Details toggle
    first = page.locator("#claimlist .claim").first
    expect(first.locator("details.dev dd code").first).not_to_be_visible()
    expect(first.locator("p.checked")).to_be_visible()


def test_the_label_pattern_finds_the_issues_examples():
    text = "as eq2b-*1 and eq-** say; see ris-*1, eq an-dp and Fig. ris-*2"
    assert INTERNAL.findall(text) == ["eq2b-*1", "eq-**", "ris-*1", "eq an-dp", "ris-*2"]
    assert not INTERNAL.findall("(2.25), (2.17) and Fig. 3; eq2.171 is no label; 1e-3")


def test_no_internal_label_visible_on_any_page(page, server):
    paths = project_pages(server)      # derived from the app's routes (tests/e2e/site.py)
    for path in paths:
        # the server's HTML, as read with scripts off or by a search engine
        html = httpx.get(server + path, timeout=60).text
        words = unescape(re.sub(r"<[^>]+>", " ", re.sub(
            r"<(script|style)\b.*?</\1>", " ", html, flags=re.S)))
        assert not INTERNAL.findall(words), f"{path} (no scripts): {INTERNAL.findall(words)}"
        page.goto(server + path)
        if path == "/" or path.startswith("/case/"):
            ready(page)
        else:
            page.wait_for_load_state("networkidle")
        # open every details element so hidden text is checked too
        page.evaluate("document.querySelectorAll('details').forEach(d => d.open = true)")
        text = page.locator("body").inner_text()
        found = INTERNAL.findall(text)
        assert not found, f"{path}: {sorted(set(found))}"


def test_search_finds_both_chaplygin_balls(page, server):
    page.goto(server + "/")
    page.fill("#nav-q", "Chaplygin")
    page.press("#nav-q", "Enter")
    page.wait_for_url(re.compile(r"/search\?q=Chaplygin"))
    results = page.get_by_test_id("case-results")
    expect(results.locator('a[href="/case/plane/chaplygin-ball"]')).to_be_visible()
    expect(results.locator('a[href="/case/sphere/chaplygin-ball"]')).to_be_visible()
    expect(results.locator('a[href="/case/sphere/borisov-fedorov"]')).to_be_visible()


def test_glossary_tooltip_opens_on_click(page, server):
    page.goto(server + "/case/plane/chaplygin-ball")
    ready(page)
    tip = page.locator('#params button.tip[data-glossary="I1"]')
    expect(tip).to_have_attribute("aria-expanded", "false")
    tip.click()
    expect(tip).to_have_attribute("aria-expanded", "true")
    box = page.locator("#tip-I1")
    expect(box).to_be_visible()
    expect(box).to_contain_text("moment of inertia")
    tip.click()
    expect(box).to_have_count(0)
    # an empty required field says what to enter
    placeholder = page.locator("#f-p-I1").get_attribute("placeholder")
    assert placeholder.startswith("enter I1") and "> 0" in placeholder
