"""For a reader: /how-we-check, /glossary, /bibliography, /search (server-rendered pages)
and their data under /api: printed numbers, glossary, references, search, the check kinds."""

from __future__ import annotations

from html import escape
from typing import Annotated, Literal

from fastapi import APIRouter, Query
from fastapi.responses import HTMLResponse

from app.api.deps import SettingsDep, VerdictsDep
from app.services import howcheck, notation_page, reader_pages
from app.services import search as search_service
from app.services.search import facets, search
from catalogue.glossary import load_glossary
from catalogue.load import load_catalogue
from catalogue.numbering import cite, printed, printed_numbers
from solvers.verify import marks as vocab

router = APIRouter(tags=["reader"])
pages = APIRouter(include_in_schema=False)


@router.get("/printed-numbers")
async def printed_numbers_api() -> dict[str, str]:
    """The seed's label -> the number the printed paper shows, e.g. "eq2.17": "(2.24)"."""
    return printed_numbers()


@router.get("/glossary")
async def glossary_api() -> dict:
    """Every parameter and state variable: meaning, range, where in the paper (numbers)."""
    g = load_glossary()
    return {"units": g.units,
            # the meaning is the reader's text of the "?" pop-up: printed numbers, no labels
            "entries": [{**e.model_dump(), "meaning": cite(e.meaning),
                         "paper_numbers": [printed(x) for x in e.paper]}
                        for e in g.entries]}


@router.get("/notation")
async def notation_api() -> dict:
    """Every symbol of the case pages' typeset formulas: its TeX forms, where the paper
    defines it (labels, printed numbers, section: one item per meaning), its meaning in the
    project's conventions, and the case pages that use it."""
    return notation_page.notation_json()


@router.get("/references")
async def references_api() -> list[dict]:
    """The bibliography: every reference key of the catalogue with its entry; `status`
    complete (authors, title, journal, year and an article's volume and pages, each from a
    named source) or unresolved; `missing` says what no source read gives, and
    `field_sources` names, for each field the entry has, the sources that give it ("seed"
    or a checked source's address)."""
    return [{**r.model_dump(mode="json"), "missing": r.missing,
             "field_sources": r.field_sources()}
            for r in load_catalogue().references]


@router.get("/cite")
async def cite_api(settings: SettingsDep) -> dict:
    """The BibTeX fields of the paper (with its DOI) and of this explorer (author, version);
    a page's Cite box adds its own URL (after `public_url`, when the explorer is published
    at a configured address), the year and the access date, and a claim's box its mark and
    the formula that holds."""
    return reader_pages.cite_data(settings.public_url)


@router.get("/how-we-check")
async def how_we_check_api() -> dict:
    """Each kind of check and the constants the checking code uses."""
    kinds = [{**k, "checks": [str(n) for n in k["checks"]]} for k in howcheck.kinds()]
    return {"constants": howcheck.constants(), "kinds": kinds, "marks": howcheck.marks(),
            "verdicts": [{"verdict": v, "mark": m, "meaning": t}
                         for v, m, t in howcheck.VERDICTS]}


# a filter is one of its facet's values (search.facets()), or empty for any: anything else
# is a 422 that names the field and the values it accepts (app/core/errors.py)
def _facet(values, what: str):
    return Annotated[Literal[("", *values)], Query(description=what)]  # type: ignore[misc]


Body = _facet(search_service.BODIES, "the body: " + ", ".join(search_service.BODIES))
Surface = _facet(search_service.SURFACES, "the surface it rolls on: plane or sphere")
Kind = _facet(search_service.KINDS, "the kind of claim (of an erratum, a convention, "
              "a finding)")
Verdict = _facet(search_service.VERDICTS, "the coarse verdict of a claim")
Mark = _facet(search_service.MARKS, "the mark a claim shows on its case page "
              "(solvers/verify/marks.yaml)")
Type = _facet(search_service.TYPES, "the type of result")


@router.get("/search")
async def search_api(verdicts: VerdictsDep, q: str = Query("", max_length=200),
                     body: Body = "", surface: Surface = "", kind: Kind = "",
                     verdict: Verdict = "", mark: Mark = "", type: Type = "") -> dict:
    """Search the cases (the rattleback included), claims, errata, conventions, findings,
    scenes and the glossary: `results` ranked by a full-text index (word forms and a few
    synonyms match: "density" finds a measure, "disc" a disk), each with its type, title,
    snippet, url, facets and mark; `cases` and `claims` the same results as before. Every
    word must match; when nothing has them all, results with some of them (`match`: any).
    Filtered by body, surface, kind, verdict, mark (the mark each claim shows on its case
    page) and type; an empty filter is any."""
    return search(q, body, surface, kind, verdict, verdicts.by_claim(), verdicts.pending(),
                  mark, type)


@pages.get("/how-we-check", response_class=HTMLResponse)
async def how_we_check_page() -> str:
    return reader_pages.how_we_check()


@pages.get("/glossary", response_class=HTMLResponse)
async def glossary_page() -> str:
    return reader_pages.glossary()


@pages.get("/notation", response_class=HTMLResponse)
async def notation_html() -> str:
    return notation_page.page()


@pages.get("/bibliography", response_class=HTMLResponse)
async def bibliography_page() -> str:
    return reader_pages.bibliography()


def _select(name: str, options: list[str], value: str) -> str:
    opts = "".join(f'<option value="{escape(o)}"{" selected" * (o == value)}>{escape(o)}'
                   "</option>" for o in options)
    return (f'<label><span>{name}</span><select name="{name}"><option value="">any</option>'
            f"{opts}</select></label>")


def _mark_html(m) -> str:
    """A claim's mark as its case page draws it (marks.js badgeHtml): shape and word, told
    apart without colour; the full name for a screen reader and on hover."""
    return (f'<span class="badge {escape(m.id)}" title="{escape(m.name)}" '
            f'data-mark="{escape(m.id)}">{escape(m.shape)} {escape(m.word)}</span>')


TYPE_NAMES = {"case": "case", "claim": "claim", "erratum": "misprint",
              "convention": "convention", "finding": "finding", "scene": "scene",
              "glossary": "glossary"}


def _hit_html(x: dict, marks: dict) -> str:
    """One ranked result: its type, its title as a link, its snippet, its mark."""
    mark = _mark_html(marks[x["mark"]]) if x.get("mark") in marks else ""
    return (f'<li data-type="{escape(x["type"])}"><span class="chip">'
            f'{escape(TYPE_NAMES[x["type"]])}</span> <a href="{escape(x["url"])}">'
            f'{escape(x["title"])}</a> {mark}<br><span class="hint">{escape(x["snippet"])}'
            "</span></li>")


@pages.get("/search", response_class=HTMLResponse)
async def search_page(verdicts: VerdictsDep, q: str = Query("", max_length=200),
                      body: Body = "", surface: Surface = "", kind: Kind = "",
                      verdict: Verdict = "", mark: Mark = "", type: Type = "") -> str:
    r = search(q, body, surface, kind, verdict, verdicts.by_claim(), verdicts.pending(), mark,
               type)
    f = facets()
    marks = vocab.by_id()
    # the marks by their names (the value is the API's `mark` id); a verdict in the query
    # (an old link) still filters, kept as a hidden field so the form does not drop it
    mark_opts = "".join(f'<option value="{escape(i)}"{" selected" * (i == mark)}>'
                        f'{escape(marks[i].shape)} {escape(marks[i].name)}</option>'
                        for i in f["mark"])
    old_verdict = (f'<input type="hidden" name="verdict" value="{escape(verdict)}">'
                   if verdict else "")
    form = (f'<form class="searchform" role="search" action="/search" method="get">'
            f'<label><span>text</span><input type="search" name="q" value="{escape(q)}" '
            'placeholder="e.g. invariant measure sphere"></label>'
            + "".join(_select(n, f[n], v) for n, v in (("body", body), ("surface", surface),
                                                       ("kind", kind)))
            + f'<label><span>mark</span><select name="mark"><option value="">any</option>'
            f'{mark_opts}</select></label>{old_verdict}'
            + _select("type", f["type"], type)
            + '<button type="submit">Search</button></form>')
    said = []
    if r["match"] == "any":
        said.append("No result has every word; these have some of them, best first.")
    if r["ignored"]:
        said.append("Not found anywhere, left out: " + ", ".join(r["ignored"]) + ".")
    note = f'<p class="status" data-testid="match-note">{escape(" ".join(said))}</p>' \
        if said else ""
    best = "".join(_hit_html(x, marks) for x in r["results"][:10]) if q.strip() else ""
    best_html = (f'<h2 id="best">Best matches</h2><ol class="results" '
                 f'data-testid="ranked-results">{best}</ol>' if best else "")
    cases = "".join(f'<li><a href="{escape(c["href"])}">{escape(c["title"])}</a> '
                    f'<span class="hint">{_place(c)}, {escape(c["surface"])}, '
                    f'{escape(c["body"])}</span></li>' for c in r["cases"])
    claims = "".join(
        f'<li><a href="{escape(c["href"])}">{escape(c["case_title"])}</a>: '
        f'{escape(c["number"] + " " if c["number"] else "")}{escape(c["plain"] or "")} '
        f'{_mark_html(marks[c["mark"]])}</li>'
        for c in r["claims"][:200])
    more = (f"<p>First 200 of {len(r['claims'])} claims.</p>" if len(r["claims"]) > 200 else "")
    sections = ""
    for title, anchor, types in (("Errata, conventions and findings", "errata",
                                  ("erratum", "convention", "finding")),
                                 ("Scenes", "scenes", ("scene",)),
                                 ("Glossary", "glossary", ("glossary",))):
        hits = [x for x in r["results"] if x["type"] in types]
        if hits:
            sections += (f'<h2 id="{anchor}">{title} ({len(hits)})</h2>'
                         f'<ul class="results" data-testid="{anchor}-results">'
                         + "".join(_hit_html(x, marks) for x in hits[:200]) + "</ul>")
    body_html = (form + note + best_html + f'<h2 id="cases">Cases ({len(r["cases"])})</h2>'
                 f'<ul class="results" data-testid="case-results">{cases}</ul>'
                 f'<h2 id="claims">Claims ({len(r["claims"])})</h2>{more}'
                 f'<ul class="results" data-testid="claim-results">{claims}</ul>' + sections)
    return reader_pages.layout("Search cases and claims", body_html, "/search")


def _place(c: dict) -> str:
    return f"Table {c['table']}" if c.get("table") else "beyond the tables"
