"""The rubber tables on the home page, in chromium: after Tables 1 and 2, marked as beyond
the 2002 paper; every cell shows its statement typeset (KaTeX, as Tables 1 and 2's cells),
its sources with their access and a mark of the one vocabulary; the summary gives the
counts by mark, and they match the marks drawn; a mark opens the cell's claims, whose
statements are typeset too. Saves docs/screenshots/rubber-tables-1280.png."""

import re
from pathlib import Path

import pytest
from playwright.sync_api import expect

from app.services.rubber_tables import ACCESS_WORDS, rubber_summary, rubber_table
from catalogue.load import load_rubber
from solvers.verify import marks as vocab

pytestmark = pytest.mark.filterwarnings("ignore::DeprecationWarning")
SHOT = Path(__file__).resolve().parents[2] / "docs" / "screenshots" / "rubber-tables-1280.png"


# per element: its KaTeX formulas, fallbacks, and its text without KaTeX's MathML
TYPESET = """els => els.map(el => {
    const body = el.querySelector('SEL').cloneNode(true);
    const katex = body.querySelectorAll('.katex').length;
    const fallback = body.querySelectorAll('.tex-fallback').length;
    body.querySelectorAll('.katex-mathml').forEach(m => m.remove());
    return {katex, fallback, text: body.textContent}; })"""
# the plain statements' ASCII for what is typeset: Greek by name, x for the cross product
# (not `I~`: KaTeX draws the accent of a typeset tilde as a `~` of its own)
ASCII = re.compile(r"\b(gamma|omega|eps|mu)\b|\sx\s")


def test_rubber_tables_render_with_marks_sources_and_counts(page, server):
    errors = []
    page.on("pageerror", lambda e: errors.append(str(e)))
    page.set_viewport_size({"width": 1280, "height": 900})
    page.goto(server + "/")
    page.locator("body[data-ready='1']").wait_for(state="attached")
    rubber = load_rubber()
    tables = [rubber_table(t.id) for t in rubber.tables()]

    # after Tables 1 and 2, set apart as beyond the paper
    order = page.evaluate("""() => [...document.querySelectorAll(
        '#table-plane, #table-sphere, #rubber')].map(e => e.id)""")
    assert order == ["table-plane", "table-sphere", "rubber"]
    expect(page.locator("#h-rubber")).to_have_text(re.compile("Beyond the 2002 paper"))

    for t, data in zip(rubber.tables(), tables, strict=True):
        tbl = page.locator(f"#tbl-{t.id}")
        expect(tbl.locator("th.case-head")).to_have_count(len(t.cases))
        expect(tbl.locator("tbody tr")).to_have_count(len(t.rows))
        cells = tbl.locator("td.rubber-cell")
        expect(cells).to_have_count(len(t.cases) * len(t.rows))
        # every cell: its mark (shape and word of the vocabulary) and its sources line
        drawn = cells.evaluate_all("""tds => tds.map(td => ({
            mark: td.dataset.mark,
            shape: td.querySelector('.cellmark .mk')?.textContent,
            word: td.querySelector('.cellmark .mkword')?.textContent,
            src: td.querySelector('.cell-src')?.textContent || ''}))""")
        want = [c for row in data["grid"] for c in row["cells"]]
        assert [d["mark"] for d in drawn] == [c["mark"] for c in want]
        for d, c in zip(drawn, want, strict=True):
            info = vocab.by_id()[c["mark"]]
            assert (d["shape"], d["word"]) == (info.shape, info.word)
            for cl in c["claims"]:
                assert cl["short"] in d["src"]
                if cl["access"] != "derived-here":
                    assert f"({ACCESS_WORDS[cl['access']]})" in d["src"]
        # every statement typeset from its LaTeX, as Tables 1 and 2's cells are: one KaTeX
        # formula per $...$, none fallen back to its source, no plain-ASCII formula left in
        # the text a reader sees (KaTeX's MathML, which holds the TeX, set aside)
        typeset = cells.evaluate_all(TYPESET.replace("SEL", ".cell-body"))
        for d, c in zip(typeset, want, strict=True):
            assert d["katex"] == c["tex"].count("$") // 2 and d["fallback"] == 0, c["plain"]
            assert "^(" not in d["text"] and not ASCII.search(d["text"]), d["text"]
        assert sum(d["katex"] for d in typeset) > 20
        # the table's own counts, as drawn
        for mark, n in data["mark_counts"].items():
            expect(tbl.locator(f"td.rubber-cell .mk.{mark}")).to_have_count(n)

    expect(page.locator("#rubber-summary")).to_have_text(rubber_summary(tables))
    assert re.search(r"\d+ cells hold with the project's formula",
                     page.locator("#rubber-summary").text_content())

    # a mark opens its cell's claims: source, place, access and check
    cell = next(c for row in tables[0]["grid"] for c in row["cells"]
                if any(cl["access"] == "abstract-only" for cl in c["claims"])
                and c["mark"] == "project-formula")
    page.locator(f'a.cellmark[href="#{cell["anchor"]}"]').click()
    target = page.locator(f'#{cell["anchor"]}')
    expect(target).to_be_in_viewport()
    expect(target.locator("li.rubber-claim")).to_have_count(len(cell["claims"]))
    # the claims' entries show the statements typeset too
    entries = page.locator("#rubber-claims article.rubber-cell-claims")
    expect(entries).to_have_count(sum(len(t["grid"]) * len(t["columns"]) for t in tables))
    every = [c for t in tables for row in t["grid"] for c in row["cells"]]
    typeset = entries.evaluate_all(TYPESET.replace("SEL", ".cell-statement"))
    for d, c in zip(typeset, every, strict=True):
        assert d["katex"] == c["tex"].count("$") // 2 and d["fallback"] == 0, c["plain"]
        assert "^(" not in d["text"] and not ASCII.search(d["text"]), d["text"]
    expect(target.locator("li.access-abstract-only").first).to_contain_text("(abstract only)")
    derived = target.locator("li.access-derived-here").first
    expect(derived.locator("details.dev")).to_contain_text("tests/")   # the developer's view
    expect(derived.locator("details.dev code").first).not_to_be_visible()

    page.locator("#rubber").scroll_into_view_if_needed()
    page.evaluate("document.getElementById('rubber').scrollIntoView()")
    page.screenshot(path=str(SHOT))
    assert errors == []
