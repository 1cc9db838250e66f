"""/bibliography in a browser: the counts of complete and unresolved entries, a complete
entry with the fields each of its sources gives, an unresolved one with what is missing,
and no script error. Saves 1280x720 screenshots of the first screen and of the start of the
list as artifacts."""

import re

import pytest
from playwright.sync_api import expect

from catalogue.load import load_catalogue

pytestmark = pytest.mark.filterwarnings("ignore::DeprecationWarning")


def test_bibliography_shows_counts_sources_and_what_is_missing(page, server, artifacts):
    refs = load_catalogue().references
    done = [r for r in refs if r.status == "complete"]
    page.set_viewport_size({"width": 1280, "height": 720})
    page.goto(server + "/bibliography")
    expect(page.locator(".refcounts")).to_have_text(
        f"{len(done)} complete, {len(refs) - len(done)} unresolved.")
    # a complete entry: each source it names, with the fields that source gives
    r = next(r for r in done if r.id == "korteweg")
    item = page.locator(f"#ref-{r.id}")
    expect(item).to_have_attribute("data-status", "complete")
    for c in r.checked_in:
        link = page.locator(f'a[href="{c.url}"]')
        src = item.locator("li.checked", has=link)
        expect(src).to_have_count(1)
        expect(src.locator(".gives")).to_have_text("gives: " + ", ".join(c.gives))
    # an unresolved entry says what is missing
    u = next(r for r in refs if r.status == "unresolved")
    hint = page.locator(f"#ref-{u.id} .hint")
    expect(hint).to_have_text(re.compile(r"^missing: " + re.escape(", ".join(u.missing))))
    page.screenshot(path=str(artifacts / "bibliography.png"))
    # the list itself: the heading and the first entries with their sources
    page.locator("#refs").evaluate("h => h.scrollIntoView()")
    page.screenshot(path=str(artifacts / "bibliography-entries.png"))
