"""Every page of the explorer (tests/e2e/site.py: derived from the app's routes and its
navigation), opened once at a desktop width and once on a 390 px phone, and every per-page
rule of issues 11 and 17 checked on that opening. Before, four tests opened every page
once each (axe, internal labels, developer words, the phone's width): about 30 pages drawn
four times where two suffice (issue 19: CI under 12 minutes).

At the desktop width, after the page's scripts drew it:
  * no developer words in what a reader sees (test_reader_pages_browser.developer_words);
  * no internal label in the visible text, every "details" opened, nor in the server's
    HTML as read with scripts off; every "(n.m)" a number the paper prints;
  * axe-core finds no serious or critical violation;
  * no script error in the page.
On the phone: no page scrolls sideways."""

import re
from html import unescape
from pathlib import Path

import httpx
import pytest

from tests.e2e.site import internal_label_re, project_pages
from tests.e2e.test_reader_pages_browser import READER_TEXT, developer_words
from tests.test_reader_numbers import reader_problems

AXE = Path(__file__).resolve().parents[1] / "vendor" / "axe-core" / "axe.min.js"
INTERNAL = internal_label_re()     # every label of the seed and of the catalogue's data

AXE_RUN = """async () => {
    const r = await axe.run(document, {resultTypes: ['violations']});
    return r.violations.filter(v => ['serious', 'critical'].includes(v.impact))
      .map(v => ({id: v.id, impact: v.impact, n: v.nodes.length,
                  at: v.nodes.slice(0, 3).map(n => n.target.join(' '))}));
}"""

WIDE = """() => [...document.querySelectorAll('body *')]
    .filter(e => e.getBoundingClientRect().right > innerWidth + 1)
    .filter(e => !e.closest('.table-wrap, .scroll-x, .katex-display, pre'))
    .slice(0, 5).map(e => e.tagName + '.' + e.className + '#' + e.id)"""


def settle(page, url: str, path: str, idle: bool = True) -> None:
    """Open a page and wait until its scripts have drawn it (or, for the 404, loaded);
    idle: and until the network is quiet (the text a page's scripts fetch and write)."""
    page.goto(url)
    if path == "/" or path.startswith("/case/"):
        page.locator("body[data-ready='1']").wait_for(state="attached")
    page.wait_for_load_state("networkidle" if idle else "load")
    page.wait_for_timeout(300)


def watched_page(browser, **context_args):
    """A page of a new context, with the script errors it raises collected in a list."""
    ctx = browser.new_context(**context_args)
    page = ctx.new_page()
    page.set_default_timeout(30_000)
    errors: list[str] = []
    page.on("pageerror", lambda e: errors.append(str(e)))
    return ctx, page, errors


@pytest.fixture(scope="module")
def paths(server):
    found = project_pages(server)
    assert len(found) > 25, found
    return found


@pytest.fixture(scope="module")
def desktop(browser, browser_context_args, server, paths):
    """path -> what the desktop opening saw: the reader's text, the visible text with every
    details opened and the reader's text then, axe's findings, the page's script errors."""
    ctx, page, errors = watched_page(browser, **browser_context_args)
    seen = {}
    for path in paths:
        errors.clear()
        settle(page, server + path, path)
        reader = page.evaluate(READER_TEXT)
        page.add_script_tag(path=str(AXE))
        axe = page.evaluate(AXE_RUN)
        # open every details element so hidden text is checked too
        page.evaluate("document.querySelectorAll('details').forEach(d => d.open = true)")
        seen[path] = {"reader": reader, "visible": page.locator("body").inner_text(),
                      "reader_open": page.evaluate(READER_TEXT), "axe": axe,
                      "errors": list(errors)}
    ctx.close()
    return seen


def test_no_script_error_on_any_page(desktop):
    errors = {p: d["errors"] for p, d in desktop.items() if d["errors"]}
    assert not errors, errors


def test_axe_finds_no_serious_or_critical_violation(desktop):
    found = {p: d["axe"] for p, d in desktop.items() if d["axe"]}
    assert not found, f"axe-core violations: {found}"


def test_no_developer_words_on_any_page(desktop):
    """Every page of the derived list, as a reader sees it after the scripts ran."""
    problems = {p: developer_words(d["reader"]) for p, d in desktop.items()}
    problems = {p: f for p, f in problems.items() if f}
    assert not problems, problems


def test_no_internal_label_visible_on_any_page(desktop, server, paths):
    for path in paths:
        # the server's HTML, as read with scripts off or by a search engine
        html = httpx.get(server + path, timeout=60).text
        words = unescape(re.sub(r"<[^>]+>", " ", re.sub(
            r"<(script|style)\b.*?</\1>", " ", html, flags=re.S)))
        assert not INTERNAL.findall(words), f"{path} (no scripts): {INTERNAL.findall(words)}"
        found = INTERNAL.findall(desktop[path]["visible"])
        assert not found, f"{path}: {sorted(set(found))}"
        # and every "(n.m)" on the page is a number the paper prints (issue 17, item 3)
        wrong = [p for p in reader_problems(desktop[path]["reader_open"]) if "label" not in p]
        assert not wrong, f"{path}: {wrong}"


def test_no_page_scrolls_sideways_on_a_phone(browser, server, paths):
    # not is_mobile: a mobile viewport widens itself to fit wide content, hiding the fault
    ctx, phone, errors = watched_page(browser, viewport={"width": 390, "height": 844},
                                      device_scale_factor=1, has_touch=True)
    wide = {}
    for path in paths:
        settle(phone, server + path, path, idle=False)
        w = phone.evaluate("() => [document.scrollingElement.scrollWidth, innerWidth]")
        if w[0] > w[1] or w[1] != 390:
            wide[path] = (w, phone.evaluate(WIDE))
    ctx.close()
    assert not wide, f"pages wider than a 390 px phone: {wide}"
    assert not errors, f"errors in the page: {errors}"
