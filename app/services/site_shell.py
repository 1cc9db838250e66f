"""The parts every page of the explorer shares, written once: the common <head> links, the
site header (skip link, brand, navigation with the current page marked) and the footer.

A page (app/static/*.html, app/templates/*.html) holds only what is its own and names the
shared parts in short forms that templates.py renders with these.
"""

from __future__ import annotations

from html import escape

from app import __version__

HEAD = """<meta charset="utf-8">
<meta name="viewport" content="width=device-width, initial-scale=1">
<link rel="icon" href="/static/favicon.svg" type="image/svg+xml">
<link rel="stylesheet" href="/static/vendor/katex/katex.min.css">
<link rel="stylesheet" href="/static/css/app.css">
<link rel="stylesheet" href="/static/css/extras.css">
<link rel="stylesheet" href="/static/css/reader.css">
<script defer src="/static/vendor/katex/katex.min.js"></script>
<script type="module" src="/static/js/glossary.js"></script>
<script type="module" src="/static/js/page.js"></script>"""

# (href, text): the site's navigation, in this order on every page
NAV = [("/#table-plane", "Table 1 · plane"), ("/#table-sphere", "Table 2 · sphere"),
       ("/poincare", "3D point maps"), ("/scenes", "Scenes"),
       ("/work-precision", "Speed &amp; accuracy"), ("/how-we-check", "How we check"),
       ("/glossary", "Glossary"), ("/notation", "Notation"), ("/bibliography", "Bibliography"),
       ("/errata", "Errata"), ("/guide/", "Guide")]
SEARCH = ('<form class="navsearch" role="search" action="/search" method="get">'
          '<label class="sr-only" for="nav-q">Search cases and claims</label>'
          '<input id="nav-q" name="q" type="search" placeholder="Search…" '
          'autocomplete="off"></form>')

FOOTER = f"""<footer class="site"><p>Rolling hierarchy {escape(__version__)}. Source:
A.&thinsp;V.&nbsp;Borisov, I.&thinsp;S.&nbsp;Mamaev, <cite>The rolling motion of a rigid body on a
plane and a sphere. Hierarchy of dynamics</cite>, Regular and Chaotic Dynamics 7(2), 2002,
doi:10.1070/RD2002v007n02ABEH000204. Equation and figure numbers are derived from the paper's
LaTeX source by compiling it under stated assumptions about the journal's class; they have not
been checked against a printed copy (<a href="/how-we-check#numbers">how they are derived</a>).
Conventions: &gamma; is the unit normal at the contact point, from the body into the support;
r(&gamma;) runs from the centre of mass to the contact point.</p></footer>"""


# on a phone the links fold behind this button (app/static/js/page.js opens and closes
# them, app/static/css/app.css hides it on a wide screen); the search box stays in view
MENU = ('<button type="button" class="navmenu" aria-expanded="false" aria-controls="site-links">'
        '<span class="bars" aria-hidden="true"></span>Menu</button>')


def nav(current: str | None = None) -> str:
    here = ' aria-current="page"'
    links = "".join(f'<a href="{href}"{here if href == current else ""}>{text}</a>'
                    for href, text in NAV)
    return (SEARCH + '<div class="navlinks" id="site-links">' + links
            + '<a href="/docs">API</a></div>')


def header(skip: str, current: str | None = None) -> str:
    return (f'<a class="skip" href="#main">{escape(skip)}</a>\n<header class="site">\n'
            '  <a class="brand" href="/"><span class="logo" aria-hidden="true"></span>'
            f'Rolling hierarchy</a>\n  {MENU}\n'
            f'  <nav aria-label="Site">{nav(current)}</nav>\n</header>')
