"""The explorer as a reference (issue 11, part A) in chromium: printed equation numbers on
case pages, no internal label in any page's visible text (after the scripts ran), search
finding both Chaplygin balls, a glossary tooltip that opens on click/tap."""

import re

from playwright.sync_api import expect

from catalogue.load import load_catalogue

INTERNAL = re.compile(r"(?<![\w/.-])(eq ?[0-9][0-9.]*[-*/0-9]*|eq-[-*d0-9]+|eq\*|ris-\*?\d|"
                      r"ris\d\.eps|an-dp|rem-\*1|2-14\*)(?![\w])")


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


def test_no_internal_label_visible_on_any_page(page, server):
    paths = ["/", "/poincare", "/scenes", "/work-precision", "/how-we-check", "/glossary",
             "/bibliography", "/search?q=Chaplygin", "/errata"]
    paths += [f"/case/{c.id}" for c in load_catalogue().cases()]
    for path in paths:
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
