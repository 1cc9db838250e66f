"""Pages for a reader, rendered on the server (readable without scripts): how a verdict is
reached, the glossary, the bibliography with a Cite box, search; and the navigation and
printed numbers every static page gets when it is served."""

from __future__ import annotations

import re
from html import escape
from pathlib import Path

from app import __version__
from app.services import howcheck
from catalogue.glossary import load_glossary
from catalogue.load import load_catalogue
from catalogue.numbering import cite, printed

PAPER_DOI = "10.1070/RD2002v007n02ABEH000204"   # the seed's \doi{...}

NAV_EXTRA = ('<a href="/how-we-check">How we check</a><a href="/glossary">Glossary</a>'
             '<a href="/bibliography">Bibliography</a><a href="/errata">Errata</a>'
             '<form class="navsearch" role="search" action="/search" method="get">'
             '<label class="sr-only" for="nav-q">Search cases and claims</label>'
             '<input id="nav-q" name="q" type="search" placeholder="Search…" '
             'autocomplete="off"></form>')
_NAV_ANCHOR = '<a href="/docs">API</a>'
_PLACEHOLDER = re.compile(r"\{\{(printed|fig):([^}]+)\}\}")


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
    if _NAV_ANCHOR in html:
        header = html[:html.find(_NAV_ANCHOR)]
        # a link the page's own navigation already has (e.g. Errata) is not added twice
        extra = re.sub(r'<a href="([^"]+)">[^<]*</a>',
                       lambda m: "" if f'href="{m[1]}"' in header else m[0], NAV_EXTRA)
        html = html.replace(_NAV_ANCHOR, extra + _NAV_ANCHOR, 1)
    else:   # a page without the API link (404): give it the whole navigation
        html = html.replace("</a></header>", f"</a><nav aria-label=\"Site\">{_nav()}</nav>"
                            "</header>", 1)
    if name == "index.html":
        html = html.replace("</main>", cite_box() + "</main>", 1)
    tips = '<script type="module" src="/static/js/glossary.js"></script>'
    return html.replace("</head>", tips + "\n</head>", 1)


def _nav() -> str:
    return ('<a href="/#table-plane">Table 1 · plane</a><a href="/#table-sphere">Table 2 · '
            'sphere</a><a href="/poincare">3D point maps</a><a href="/scenes">Scenes</a>'
            '<a href="/work-precision">Speed &amp; accuracy</a>' + NAV_EXTRA + _NAV_ANCHOR)


def layout(title: str, body: str) -> str:
    return f"""<!doctype html>
<html lang="en">
<head>
<meta charset="utf-8">
<meta name="viewport" content="width=device-width, initial-scale=1">
<title>{escape(title)} — Rolling hierarchy</title>
<link rel="icon" href="/static/favicon.svg" type="image/svg+xml">
<link rel="stylesheet" href="/static/vendor/katex/katex.min.css">
<link rel="stylesheet" href="/static/css/app.css">
<script defer src="/static/vendor/katex/katex.min.js"></script>
<script type="module" src="/static/js/glossary.js"></script>
</head>
<body>
<a class="skip" href="#main">Skip to the content</a>
<header class="site">
  <a class="brand" href="/"><span class="logo" aria-hidden="true"></span>Rolling hierarchy</a>
  <nav aria-label="Site">{_nav()}</nav>
</header>
<main id="main" class="reader">
<h1>{escape(title)}</h1>
{body}
</main>
<footer class="site"><p>Rolling hierarchy {escape(__version__)}. Equation and figure numbers
are those of the printed paper (<a href="/how-we-check#numbers">how they are derived</a>).</p>
</footer>
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
        "below are read from the checking code (<code>solvers/verify/checks</code>) when the "
        "page is served.</p>",
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
    parts.append("</tbody></table></div><h2 id=\"verdicts\">What each verdict means</h2><dl>")
    for v, mark, text in howcheck.VERDICTS:
        parts.append(f'<dt><span class="mark {v}">{mark}</span> {v}</dt><dd>{escape(text)}</dd>')
    parts.append("</dl><p>Each verdict on a case page carries the date it was computed and the "
                 "project version that computed it.</p>")
    parts.append(
        '<h2 id="numbers">Equation and figure numbers</h2><p>The pages show the numbers the '
        "printed paper carries, e.g. (2.24) and Fig. 3. They are derived from the paper's LaTeX "
        "by emulating the journal class: equations are numbered per section in order of "
        "appearance (numbered display macros and environments count, starred ones, "
        "<code>$$…$$</code> and lines marked <code>\\notag</code> do not); figures are numbered "
        "through the paper. The LaTeX labels stay in the data (the API's <code>label</code> "
        "fields) only.</p>")
    return layout("How we check", "\n".join(parts))


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
    return layout("Glossary", body)


# --- /bibliography and the Cite box -------------------------------------------------------

def bibtex_paper() -> str:
    return ("@article{BorisovMamaev2002,\n  author  = {Borisov, Alexey V. and Mamaev, Ivan S.},\n"
            "  title   = {The rolling motion of a rigid body on a plane and a sphere. "
            "Hierarchy of dynamics},\n  journal = {Regular and Chaotic Dynamics},\n"
            "  volume  = {7},\n  number  = {2},\n  pages   = {177--200},\n  year    = {2002},\n"
            f"  doi     = {{{PAPER_DOI}}}\n}}")


def bibtex_project() -> str:
    return ("@software{RollingHierarchy,\n  title   = {Rolling hierarchy: a checked knowledge "
            "base of a rigid body rolling on a plane and a sphere},\n"
            f"  version = {{{__version__}}},\n  note    = {{Every claim of Borisov and Mamaev "
            "(2002), Tables 1 and 2, checked by computation}}\n}")


def cite_box() -> str:
    return (f'<section id="cite" class="cite" aria-labelledby="h-cite"><h2 id="h-cite">Cite</h2>'
            f'<p>The paper: <a href="https://doi.org/{PAPER_DOI}">doi:{PAPER_DOI}</a> '
            "(Regular and Chaotic Dynamics 7(2), 2002, pp. 177–200; pages and DOI as the "
            "paper's own LaTeX gives them).</p>"
            f'<pre class="bibtex" tabindex="0">{escape(bibtex_paper())}</pre>'
            f'<p>This project (version {escape(__version__)}):</p>'
            f'<pre class="bibtex" tabindex="0">{escape(bibtex_project())}</pre></section>')


def bibliography() -> str:
    refs = load_catalogue().references
    items = []
    for r in refs:
        who = ", ".join(r.authors) or "authors not named in the paper"
        years = ", ".join(str(y) for y in r.years) or "year not given"
        title = f"<cite>{escape(r.title)}</cite>. " if r.title else ""
        key = f" <code>\\cite{{{escape(r.cite_key)}}}</code>" if r.cite_key else ""
        used = "".join(f"<li>{escape(cite(x))}</li>" for x in r.cited_for)
        remark = f"<p>{escape(cite(r.remarks))}</p>" if r.remarks else ""
        items.append(f'<li id="ref-{escape(r.id)}"><strong>{escape(who)}</strong> ({years}). '
                     f"{title}{key}<ul>{used}</ul>{remark}</li>")
    body = ("<p>Every reference the catalogue cites, resolved from its key. The paper as the "
            "seed holds it has no reference list: authors and years come from its text and "
            "tables, and titles are given only where the paper states them (none is "
            "invented).</p>" + cite_box() +
            f'<h2 id="refs">References ({len(refs)})</h2><ol class="refs">{"".join(items)}</ol>')
    return layout("Bibliography", body)
