"""The explorer as a reference (issue 11, part A; issue 17, items 3 and 7) in chromium:
printed equation numbers on case pages, no internal label and no "(n.m)" that names no
display in any glossary pop-up, search finding both Chaplygin balls, a glossary tooltip
that opens on click/tap. The same rules on every page's visible text, and no developer
words on any page: tests/e2e/test_page_sweep_browser.py (which uses the patterns and the
reader's text defined here)."""

import re

import httpx
from playwright.sync_api import expect

from catalogue.numbering import printed
from tests.e2e.site import internal_label_re
from tests.test_reader_numbers import reader_problems

INTERNAL = internal_label_re()     # every label of the seed and of the catalogue's data

# Developer words a page must not show (issue 17, item 7): the pages speak of the physics;
# the CLI keeps its flags, the API and the catalogue their field names.
DEVELOPER_WORDS = {
    # a program's name (mean_logdet, allow_any_inertia, flat_F), not a subscript (b_i, x_n)
    "snake_case identifier": r"\b[a-z]{2,}[a-z0-9]*_[A-Za-z][A-Za-z0-9]*(?:_[A-Za-z0-9]+)*\b",
    "file path": r"\b[\w.-]+/[\w./-]*\.(?:ya?ml|py|js|json|md|html|css|txt)\b"
                 r"|\b(?:catalogue|solvers|app|tests|bench|scripts|docs)/[\w-]",
    "command-line flag": r"(?<![\w-])--[a-z][a-z0-9]+(?:-[a-z0-9]+)*",
    "complex literal": r"\b\d+(?:\.\d+)?(?:e[-+]?\d+)?[-+]\d+(?:\.\d+)?(?:e[-+]?\d+)?j\b",
    "programmer's not-equal": r"!=",
    "citation key": r"\[[a-z][a-z0-9]*(?:[-_][a-z0-9*]+)+\]|\[[a-z]+\d+\]",
    "data key: value": r"\b(?:potential|S|I|a|k|lambda_?|z): (?:any|zero|none|nonzero|brun)\b",
    "record id": r"\b(?:plane|sphere)/[a-z0-9-]+/[a-z0-9*-]+",
    # a statistic's program name (the section map's thickness "median s3/s1")
    "statistic name": r"\bs\d/s\d\b",
}
DEV_RE = {k: re.compile(v) for k, v in DEVELOPER_WORDS.items()}


def developer_words(text: str) -> dict[str, list[str]]:
    out = {}
    for kind, pat in DEV_RE.items():
        found = [m.group(0) for m in pat.finditer(text)]
        if found:
            out[kind] = sorted(set(found))
    return out


# what a reader sees: the text on screen, without the typeset formulas' hidden TeX source
# (KaTeX's MathML annotation), without the "Details" toggles that hold, on purpose and
# labelled as such, the developer's view of a claim (check name, claim id, raw message), and
# without the command lines offered to copy ("Reproduce: rolling verify --claim ...")
READER_TEXT = """() => {
  const hide = [...document.querySelectorAll(
    '.katex-mathml, annotation, details.dev, .repro code')];
  const was = hide.map((e) => e.style.display);
  hide.forEach((e) => { e.style.display = 'none'; });
  const text = document.body.innerText;
  hide.forEach((e, i) => { e.style.display = was[i]; });
  return text;
}"""


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


def test_the_developer_word_patterns_find_the_issues_examples():
    text = ("conditions: potential: any, S: zero, I: I1!=I2!=I3!=I1; mean_logdet; "
            "0.833967+0.521929j; (catalogue/scenes.yaml); pass allow_any_inertia / "
            "--allow-any-inertia; [bm-new]; plane/chaplygin-ball/integral/M2; "
            "max median s3/s1 = 0.00")
    assert set(developer_words(text)) == set(DEVELOPER_WORDS)
    assert not developer_words("I1 ≠ I2 ≠ I3 ≠ I1, no gyrostat (S = 0), any potential U(γ); "
                               "(2.24); Fig. 3; 1.2e-15; e.g. a − b; the Chaplygin ball "
                               "(Borisov, Mamaev 2001); [0, 1]; /case/plane/chaplygin-ball; "
                               "b_i, x_n; 0.833967 + 0.521929i")


def test_claim_numbers_and_glossary_popups_name_the_right_display(page, server):
    """A claim's number on its case page is its label's printed number, and every "?"
    pop-up on the page shows printed numbers only (no label, no number of no display)."""
    for case in ("plane/chaplygin-ball", "plane/unbalanced-ball", "sphere/flat-base",
                 "sphere/chaplygin-ball"):
        page.goto(f"{server}/case/{case}")
        ready(page)
        data = httpx.get(f"{server}/api/cases/{case}", timeout=60).json()
        for c in data["claims"]:
            assert c["number"] == printed(c["label"]), c["id"]
        # the page shows those numbers, claim by claim, in order
        labels = page.locator("#claimlist .claim header .label").all_inner_texts()
        expected = [c["number"] for c in data["claims"] if c["number"]]
        assert labels == expected, case
        tips = page.locator("button.tip[data-glossary]")
        assert tips.count() > 0
        for i in range(tips.count()):
            btn = tips.nth(i)
            sym = btn.get_attribute("data-glossary")
            btn.click()
            box = page.locator(f'[id="tip-{sym}"]')
            expect(box).to_be_visible()
            text = box.inner_text()
            assert not reader_problems(text), (case, sym, text)
            btn.click()


def test_search_finds_both_chaplygin_balls(page, server):
    page.goto(server + "/")
    page.fill("#nav-q", "Chaplygin")
    page.press("#nav-q", "Enter")
    page.wait_for_url(re.compile(r"/search\?q=Chaplygin"))
    results = page.get_by_test_id("case-results")
    expect(results.locator('a[href="/case/plane/chaplygin-ball"]')).to_be_visible()
    expect(results.locator('a[href="/case/sphere/chaplygin-ball"]')).to_be_visible()
    expect(results.locator('a[href="/case/sphere/borisov-fedorov"]')).to_be_visible()


def test_the_rattleback_has_a_case_page_beyond_the_tables(page, server):
    """Before: /case/plane/rattleback was a 404 though the case runs. Its page says it is
    no case of the paper's tables, has no cells and claims to check, and runs."""
    errors = []
    page.on("pageerror", lambda e: errors.append(str(e)))
    page.goto(server + "/case/plane/rattleback")
    ready(page)
    expect(page.locator("#case-title")).to_contain_text("Rattleback (Celtic stone)")
    expect(page.locator("#crumb-table")).to_have_text("beyond the tables")
    expect(page.locator("#facts")).to_contain_text("beyond Tables 1 and 2")
    expect(page.locator("#mark-summary")).to_contain_text(
        "Not a case of the paper's Tables 1 and 2")
    expect(page.get_by_test_id("beyond-tables")).to_contain_text("No column of Tables 1 and 2")
    expect(page.locator("#facts")).to_contain_text("state (M, γ)")
    expect(page.locator("#reverify")).to_be_hidden()
    expect(page.locator("#checkedbox")).to_contain_text("nothing is checked")
    expect(page.locator("#cite")).to_contain_text("a case beyond the tables")
    assert not developer_words(page.evaluate(READER_TEXT))
    assert not errors, errors


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


def test_since_2002_notes_stay_beside_their_claims_after_the_scripts_ran(page, server):
    """The notes come rendered by the server; the case page's scripts redraw the claims and
    must put every note back (beside its claim, or in the open cells' section)."""
    notes = httpx.get(server + "/api/cases/plane/ellipsoid", timeout=30).json()["since_2002"]
    assert notes
    page.goto(server + "/case/plane/ellipsoid")
    ready(page)
    shown = page.locator("#claimlist aside.since-2002")
    expect(shown).to_have_count(len(notes))
    for n in notes:
        if "/cell/" not in n["record"]:
            anchor = "claim-" + re.sub(r"[^A-Za-z0-9_-]+", "_", n["record"])
            expect(page.locator(f"#{anchor} > aside.since-2002")).to_have_count(1)
