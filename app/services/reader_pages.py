"""Pages for a reader, rendered on the server (readable without scripts): how a verdict is
reached, the glossary, the bibliography with a Cite box, search; and the navigation and
printed numbers every static page gets when it is served."""

from __future__ import annotations

import re
from datetime import date
from html import escape
from pathlib import Path
from urllib.parse import urlsplit

from app import __version__
from app.services import howcheck, site_shell, ssr
from catalogue.glossary import load_glossary
from catalogue.load import load_catalogue
from catalogue.numbering import cite, printed
from catalogue.since_2002 import load_since_2002, note_json

PAPER_DOI = "10.1070/RD2002v007n02ABEH000204"   # the seed's \doi{...}

_PLACEHOLDER = re.compile(r"\{\{(printed|fig):([^}]+)\}\}")
# the address of each static page, for the navigation's aria-current
_PAGE_PATHS = {"errata.html": "/errata", "poincare.html": "/poincare",
               "scenes.html": "/scenes", "work-precision.html": "/work-precision"}


def _number(kind: str, label: str) -> str:
    num = printed(label)
    if num is None:
        raise KeyError(f"no printed number for {label!r}")
    return num.removeprefix("Fig. ") if kind == "fig" else num


def static_page(path: Path) -> str:
    """A static page as served: printed numbers for {{printed:LABEL}} / {{fig:LABEL}}, the
    reader's links in the site navigation, the glossary tooltips."""
    return render_page(path.read_text(encoding="utf-8"), path.name)


def render_page(text: str, name: str) -> str:
    """`static_page` for a page's text already in hand (`name`: its file name)."""
    html = _PLACEHOLDER.sub(lambda m: _number(m[1], m[2]), text)
    html = site_shell.fill(html, _PAGE_PATHS.get(name))
    if name == "index.html":
        html = html.replace("</main>", cite_box() + "</main>", 1)
    return html


def layout(title: str, body: str, current: str | None = None) -> str:
    return f"""<!doctype html>
<html lang="en">
<head>
{site_shell.HEAD}
<title>{escape(title)} — Rolling hierarchy</title>
</head>
<body>
{site_shell.header("Skip to the content", current)}
<main id="main" class="reader">
<h1>{escape(title)}</h1>
{body}
</main>
{site_shell.FOOTER}
</body>
</html>"""


def tex(s: str) -> str:
    """A formula KaTeX renders in the page (glossary.js); the TeX stays as text without it."""
    return f'<span class="tex" data-tex="{escape(s)}">{escape(s)}</span>'


# --- /how-we-check ------------------------------------------------------------------------

def how_we_check() -> str:
    c = howcheck.constants()
    parts = [
        "<p>Every statement of Tables 1 and 2 and of the text is a <em>claim</em>, and every "
        "claim names the check that decides it. The checks evaluate the printed formulas at "
        "random states with exact derivatives, not by watching a trajectory drift. The numbers "
        "below are read from the checking code itself when the page is served, so they cannot "
        "drift from what the checks do.</p>",
        f'<p class="constants">Tolerance <strong>{c["TOL"]:g}</strong> on relative residuals; '
        f'<strong>{c["N_SETTINGS"]}</strong> parameter draws × <strong>{c["N_POINTS"]}'
        "</strong> random phase points per claim. Round-off gives residuals near 1e-15 to "
        "1e-13; a wrong formula gives 1e-3 to 1. The tolerance is one number for every claim, "
        "never tuned per claim.</p>",
        '<div class="table-wrap"><table class="howcheck"><thead><tr><th scope="col">kind'
        '</th><th scope="col">what is computed</th><th scope="col">at how many points</th>'
        '<th scope="col">tolerance</th></tr></thead><tbody>']
    for k in howcheck.kinds():
        anchors = "".join(f'<span id="{escape(str(n))}"></span>' for n in k["checks"])
        names = ", ".join(f"<code>{escape(str(n))}</code>" for n in k["checks"])
        parts.append(
            f'<tr id="{k["id"]}"><th scope="row">{anchors}{escape(k["title"])}'
            f'{"<details><summary>check names</summary>" + names + "</details>" if names else ""}'
            f'</th><td>{escape(k["computed"])}</td><td>{escape(k["points"])}</td>'
            f'<td>{escape(k["tolerance"])}</td></tr>')
    parts.append("</tbody></table></div><h2 id=\"marks\">What each mark means</h2>"
                 "<p>Every table cell and every claim carries one mark, a shape and a word; "
                 "the tables, the case pages, the JSON API (field <code>mark</code>) and "
                 "<code>rolling verify</code> use these same marks.</p><dl class=\"marks\">")
    for m in howcheck.marks():
        parts.append(f'<dt id="mark-{escape(m["id"])}"><span class="mark {escape(m["id"])}" '
                     f'aria-hidden="true">{m["shape"]}</span> {escape(m["name"])}</dt>'
                     f'<dd>{escape(m["definition"])}</dd>')
    parts.append("</dl><h2 id=\"verdicts\">The coarse verdict</h2><p>Each record also keeps "
                 "its older, coarser <code>verdict</code> field in the JSON API:</p><dl>")
    for v, mark, text in howcheck.VERDICTS:
        parts.append(f'<dt><span class="mark {v}">{mark}</span> {v}</dt><dd>{escape(text)}</dd>')
    parts.append("</dl><p>Each mark on a case page carries the date it was computed and the "
                 "project version that computed it.</p>")
    parts.append(
        '<h2 id="numbers">Equation and figure numbers</h2><p>The pages name equations and '
        "figures by the numbers the paper prints, e.g. (2.24) and Fig. 3. These numbers are "
        "derived from the paper's LaTeX source, not read off a printed copy (we had none). "
        "LaTeX itself numbered them: the source was compiled with TeX Live against a "
        "stand-in for the journal's class, which is not public. The stand-in assumes that "
        "equations are numbered within each section; that each numbered display carries one "
        "number however many lines it has; and that every figure is numbered through the "
        "paper, with or without a caption. The result agrees with the project's own "
        "emulation of the class for every equation and figure. Where the paper cites an "
        "uncaptioned figure, which figure is meant is inferred from where it is cited. "
        "A display without a number is named by where it stands, e.g. the display after "
        "(2.24) in section 2.</p>")
    return layout("How we check", "\n".join(parts), "/how-we-check")


# --- /glossary ----------------------------------------------------------------------------

def _where(labels: list[str]) -> str:
    nums = [printed(x) for x in labels]
    return ", ".join(n for n in nums if n) or "—"


def glossary() -> str:
    g = load_glossary()
    rows = []
    for group in ("inertia", "shape", "support", "field", "state"):
        for e in (e for e in g.entries if e.group == group):
            rows.append(
                f'<tr id="g-{escape(e.symbol)}"><th scope="row">{tex(e.tex)} '
                f'<code>{escape(e.symbol)}</code></th><td>{escape(e.kind)}</td>'
                f"<td>{escape(cite(e.meaning))}</td><td>{escape(e.range)}</td>"
                f"<td>{escape(_where(e.paper))}</td></tr>")
    body = (f"<p><strong>Units.</strong> {escape(g.units)}</p>"
            '<div class="table-wrap"><table class="glossary"><thead><tr>'
            '<th scope="col">symbol</th><th scope="col">kind</th><th scope="col">meaning</th>'
            '<th scope="col">valid range</th><th scope="col">in the paper</th></tr></thead>'
            f"<tbody>{''.join(rows)}</tbody></table></div>")
    return layout("Glossary", body, "/glossary")


# --- /bibliography and the Cite box -------------------------------------------------------

PAPER_ID = "this-paper"
SOFTWARE_AUTHOR = "rolling-hierarchy contributors"   # pyproject.toml names no authors
SOFTWARE_TITLE = ("Rolling hierarchy: a checked knowledge base of a rigid body rolling on a "
                  "plane and a sphere")


SOFTWARE_KEY = "RollingHierarchy"


def cite_key(what: str = "") -> str:
    """The explorer's BibTeX key for a page or a claim, stable and unique: the claim id or
    the page's path after the project's key, in characters every BibTeX reads
    ("sphere/body-of-revolution/measure" -> "RollingHierarchy:sphere:body-of-revolution:measure";
    the same as cite.js citeKey)."""
    rest = re.sub(r"[^A-Za-z0-9_.-]+", ":", what).strip(":")
    return f"{SOFTWARE_KEY}:{rest}" if rest else SOFTWARE_KEY


def public_url() -> str | None:
    from app.core.config import get_settings

    return get_settings().public_url


def cite_data(base_url: str | None = None) -> dict:
    """What the Cite boxes need (GET /api/cite, cite.js): the paper's entry from
    catalogue/references.yaml and the explorer's; the page's URL, the year and the access
    date are added where the page is shown (in the browser, or `bibtex_project`).
    `base_url` (returned as `public_url`): the configured public address
    (ROLLING_PUBLIC_URL), else None and the page's own address is used; `marks`: each
    mark's shape and name, for a claim's box."""
    from solvers.verify import marks as vocab

    r = load_catalogue().reference(PAPER_ID)
    paper = {"author": " and ".join(_bib_name(a) for a in r.authors), "title": r.title,
             "journal": r.journal, "volume": r.volume, "number": r.number,
             "pages": (r.pages or "").replace("-", "--"), "year": str(r.years[0]),
             "doi": r.doi}
    software = {"author": "{" + SOFTWARE_AUTHOR + "}", "title": SOFTWARE_TITLE,
                "version": __version__,
                "note": "Every claim of Borisov and Mamaev (2002), Tables 1 and 2, checked by "
                        "computation"}
    marks = {m.id: {"shape": m.shape, "name": m.name} for m in vocab.vocabulary()}
    return {"paper": {"type": "article", "key": "BorisovMamaev2002", "fields": paper},
            "software": {"type": "software", "key": SOFTWARE_KEY, "fields": software},
            "public_url": base_url, "version": __version__, "marks": marks}


def _bib_name(name: str) -> str:
    """'A. V. Borisov' -> 'Borisov, A. V.' (BibTeX's last-name-first form)."""
    *first, last = name.split()
    return f"{last}, {' '.join(first)}" if first else last


def bibtex(entry: dict, **extra: str) -> str:
    """One BibTeX entry; the same layout as cite.js's bibtex()."""
    fields = {**entry["fields"], **extra}
    width = max(len(k) for k in fields)
    body = ",\n".join(f"  {k.ljust(width)} = {{{v}}}" for k, v in fields.items() if v)
    return f"@{entry['type']}{{{entry['key']},\n{body}\n}}"


def bibtex_paper() -> str:
    return bibtex(cite_data()["paper"])


def bibtex_project(url: str = "/", today: date | None = None, key: str | None = None) -> str:
    """The explorer's entry for the page at `url`, accessed `today` (the server's date; the
    page's script puts in the reader's own date and the page's full address). `url` is a
    path: with a public address configured it is put after it. The key is the page's."""
    today = today or date.today()
    path = url
    base = public_url()
    if url.startswith("/"):
        url = f"{base}{url}" if base else url
    else:
        path = re.sub(r"^[a-z]+://[^/]+", "", url)
    entry = {**cite_data()["software"], "key": key or cite_key(path.split("#")[0])}
    return bibtex(entry, year=str(today.year), url=url, urldate=today.isoformat())


def _pre(text: str) -> str:
    # braces as character references: the shell's "{{...}}" placeholders never appear in a
    # served page, and a corporate author's double braces are not one
    return escape(text).replace("{{", "&#123;{").replace("}}", "}&#125;")


def cite_box(url: str = "/") -> str:
    return (f'<section id="cite" class="cite" aria-labelledby="h-cite"><h2 id="h-cite">Cite</h2>'
            f'<p>The paper: <a href="https://doi.org/{PAPER_DOI}">doi:{PAPER_DOI}</a> '
            "(Regular and Chaotic Dynamics 7(2), 2002, pp. 177–200).</p>"
            f'<pre class="bibtex" data-cite="paper" tabindex="0">{_pre(bibtex_paper())}</pre>'
            f'<p>This explorer (version {escape(__version__)}), as this page shows it:</p>'
            f'<pre class="bibtex" data-cite="software" data-key="{escape(cite_key(url))}" '
            f'tabindex="0">{_pre(bibtex_project(url))}</pre>'
            '<link rel="stylesheet" href="/static/css/cite.css">'
            '<script type="module" src="/static/js/cite.js"></script></section>')


def _checked_html(c) -> str:
    """One place an entry was read: its kind, what it is, how much was read, its address."""
    access = {"full": "read in full", "abstract": "abstract page read",
              "snippet": "only a snippet of the list read"}[c.access]
    site = urlsplit(c.url).hostname or c.url
    return (f'<li class="checked" data-kind="{escape(c.kind)}" data-access="{c.access}">'
            f"{escape(c.kind)}: {escape(c.source)} ({access}), at "
            f'<a href="{escape(c.url)}" rel="nofollow noopener">{escape(site)}</a></li>')


def _reference_html(r) -> str:
    who = ", ".join(r.authors) or "authors not named in the paper"
    years = (str(r.year) if r.year else ", ".join(str(y) for y in r.years)) or "year not given"
    title = f"<cite>{escape(r.title)}</cite>. " if r.title else ""
    src = ", ".join(x for x in (r.journal, r.volume and f"vol. {r.volume}",
                                r.number and f"no. {r.number}",
                                r.pages and f"pp. {r.pages.replace('-', '–')}") if x)
    src = f"{escape(src)}. " if src else ""
    doi = (f'<a href="https://doi.org/{escape(r.doi)}">doi:{escape(r.doi)}</a>. '
           if r.doi else "")
    key = f" <code>\\cite{{{escape(r.cite_key)}}}</code>" if r.cite_key else ""
    if r.status == "complete":
        status = '<span class="refstatus complete">complete</span>'
    else:
        status = ('<span class="refstatus unresolved">unresolved</span> '
                  f'<span class="hint">missing: {escape(", ".join(r.missing))}</span>')
    seed_years = ""
    if r.year and r.years and r.years != [r.year]:
        seed_years = (f'<p class="seedyears">The seed dates it '
                      f'{escape(", ".join(str(y) for y in r.years))}.</p>')
    extra = "".join(f'<p class="{cls}">{label}{escape(cite(text))}</p>'
                    for cls, label, text in (
                        ("translation", "", r.translation),
                        ("identity", "Why this work: ", r.identity),
                        ("candidate", "Candidate: ", r.candidate)) if text)
    checked = (f'<p>Checked in:</p><ul class="checkedin">'
               f'{"".join(_checked_html(c) for c in r.checked_in)}</ul>'
               if r.checked_in else '<p class="checkedin none">No source read gives it.</p>')
    used = "".join(f"<li>{escape(cite(x))}</li>" for x in r.cited_for)
    remark = f"<p>{escape(cite(r.remarks))}</p>" if r.remarks else ""
    return (f'<li id="ref-{escape(r.id)}" data-status="{r.status}">{status}<br>'
            f"<strong>{escape(who)}</strong> ({years}). {title}{src}{doi}{key}"
            f"{seed_years}{extra}{checked}<p>Cited for:</p><ul>{used}</ul>{remark}</li>")


def _record_words(record: str) -> str:
    """A claim or cell record as a reader names it: "Balanced ellipsoid: measure (2.30)",
    "Balanced ellipsoid: the Hamiltonian form cell"."""
    parts = record.split("/")
    case_id, rest = "/".join(parts[:2]), "/".join(parts[2:])
    case = next((c for c in load_catalogue().cases() if c.id == case_id), None)
    title = case.title if case else case_id
    if rest.startswith("cell/"):
        row = rest.removeprefix("cell/").replace("_", " ").replace("hamiltonian", "Hamiltonian")
        return f"{title}: the {row} cell"
    claim = next((c for c in case.claims if c.id == record), None) if case else None
    if claim is None:
        return f"{title}: {re.sub(r'[/_*-]+', ' ', rest)}"
    number = printed(claim.label)
    if number is None:
        return f"{title}: {re.sub(r'[/_*-]+', ' ', rest)}"
    return f"{title}: {claim.kind.value.replace('-', ' ')} {number}"


def _since_2002_html() -> str:
    """The later literature and the 'since 2002' notes (catalogue/since_2002.yaml), each
    note linked to its claim or cell on the case page."""
    data = load_since_2002()
    notes = "".join(
        f'<li class="since-note" data-record="{escape(n.record)}">'
        f'<a href="/case/{escape("/".join(n.record.split("/")[:2]))}#'
        f'{escape(ssr._anchor(n.record))}">{escape(_record_words(n.record))}</a>'
        f"{ssr.since_html(note_json(n))}</li>" for n in data.notes)
    return ('<h2 id="since-2002">Since 2002</h2><p>What later work says about every open '
            "cell, open claim, refuted conjecture and non-existence result, with how much of "
            "each work could be read; where nothing later was found the note says so. The "
            f"later works ({len(data.literature)}), each with where it was read:</p>"
            f'<ol class="refs later">{"".join(_reference_html(r) for r in data.literature)}'
            f'</ol><h3 id="since-notes">The notes ({len(data.notes)})</h3>'
            f'<ul class="since-notes">{notes}</ul>')


def bibliography() -> str:
    refs = load_catalogue().references
    unresolved = sum(r.status == "unresolved" for r in refs)
    body = ("<p>Every reference the catalogue cites, resolved from its key. The paper's LaTeX "
            "(the seed) has no reference list. An entry is <em>complete</em> when a source "
            "that was read (another paper's reference list, or the publisher's record; named "
            "under the entry with how much of it was read) gives its authors, title, journal "
            "or book and year, and the seed's own context ties the key to that work; it is "
            "<em>unresolved</em> otherwise, saying what is missing. Nothing is guessed. "
            f'<span class="refcounts">{len(refs) - unresolved} complete, {unresolved} '
            "unresolved.</span></p>" + cite_box("/bibliography") +
            f'<h2 id="refs">References ({len(refs)})</h2><ol class="refs">'
            f'{"".join(_reference_html(r) for r in refs)}</ol>' + _since_2002_html())
    return layout("Bibliography", body, "/bibliography")
