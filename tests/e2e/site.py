"""What "every page" and "every internal label" mean for the browser tests, derived from the
app and the catalogue rather than listed by hand, so that a page or a label added later is
covered without touching the tests.

Pages: every GET route of the app outside /api, /static and the vendored files, a route
with a case id expanded to every case of the catalogue, plus every same-site page the
navigation of those pages links to, plus an unknown address (the HTML 404). A route with any
other parameter is an error here until this module says how to fill it in (the user guide's
/guide/{path} is its front page, which the tests' servers answer as "not built"). /docs (the
vendored Swagger UI) is exempt from the issue's checks and left out.

Labels: every label of the seed (catalogue/printed_numbers.yaml) and every label the
catalogue's data names (claims, cells, models, glossary).
"""

from __future__ import annotations

import re
from html.parser import HTMLParser
from urllib.parse import urljoin, urlsplit

import httpx

from catalogue.glossary import load_glossary
from catalogue.load import load_catalogue
from catalogue.numbering import printed_numbers

NOT_PAGES = ("/api/", "/static/", "/vendor/", "/openapi.json", "/docs")
# the downloads a page offers (the errata as CSV and BibTeX): files, not pages
# (tests/test_errata_export.py checks them)
DOWNLOADS = (".csv", ".bib")
EXEMPT = ("/docs",)      # the vendored Swagger UI (issue 11: exempt)


def _routes(routes, prefix=""):
    """GET paths of an app's routes, through included routers (FastAPI >= 0.16x keeps them
    nested as _IncludedRouter objects with their original router)."""
    for r in routes:
        inner = getattr(r, "original_router", None)
        if inner is not None:
            yield from _routes(inner.routes, prefix + r.include_context.prefix)
        elif "GET" in (getattr(r, "methods", None) or ()):
            yield prefix + r.path


def route_pages() -> list[str]:
    from app.main import create_app
    from app.testing import settings_for_tests

    cases = [c.id for c in load_catalogue().cases()]
    out = []
    for path in _routes(create_app(settings_for_tests()).routes):
        if path.startswith(NOT_PAGES) or path.endswith(DOWNLOADS):
            continue
        params = re.findall(r"\{([^}:]+)(?::[^}]*)?\}", path)
        if params == ["case_id"]:
            out += [re.sub(r"\{case_id(?::[^}]*)?\}", cid, path) for cid in cases]
        elif params == ["path"] and path.startswith("/guide/"):   # the guide: its front page
            out.append("/guide/")
        elif params:
            raise AssertionError(f"tests/e2e/site.py: how to fill in {path!r}?")
        else:
            out.append(path)
    return out


class _Links(HTMLParser):
    def __init__(self):
        super().__init__()
        self.in_header, self.links = 0, []

    def handle_starttag(self, tag, attrs):
        a = dict(attrs)
        if tag in ("header", "nav"):
            self.in_header += 1
        if self.in_header and tag == "a" and a.get("href"):
            self.links.append(a["href"])
        if self.in_header and tag == "form" and a.get("action"):
            self.links.append(a["action"])

    def handle_endtag(self, tag):
        if tag in ("header", "nav"):
            self.in_header -= 1


def nav_links(base: str, html: str) -> set[str]:
    p = _Links()
    p.feed(html)
    out = set()
    for href in p.links:
        u = urlsplit(urljoin(base + "/", href))
        if u.netloc == urlsplit(base).netloc and not u.path.startswith(NOT_PAGES) \
                and not u.path.endswith(DOWNLOADS):
            out.add(u.path + (f"?{u.query}" if u.query else ""))
    return out


def project_pages(base: str) -> list[str]:
    """Every page of the explorer served at `base`, each once, in a stable order; every one
    answers 200 with HTML (checked here), except the unknown address (404 with HTML)."""
    pages = route_pages()
    seen = set(pages)
    with httpx.Client(base_url=base, timeout=60.0) as client:
        for path in list(pages):
            r = client.get(path)
            assert r.status_code == 200 and r.headers["content-type"].startswith("text/html"), \
                (path, r.status_code, r.headers.get("content-type"))
            for link in sorted(nav_links(base, r.text) - seen):
                seen.add(link)
                pages.append(link)
        pages += ["/search?q=Chaplygin", "/no-such-page/at-all"]
        assert client.get(pages[-1]).status_code == 404
    return [p for p in dict.fromkeys(pages) if not p.startswith(EXEMPT)]


# --- internal labels ---------------------------------------------------------------------

def _labels_in(x, out: set[str]) -> None:
    if isinstance(x, dict):
        for k, v in x.items():
            if k in ("label", "labels", "equations", "paper") and v:
                out.update([v] if isinstance(v, str) else [s for s in v if isinstance(s, str)])
            else:
                _labels_in(v, out)
    elif isinstance(x, list):
        for v in x:
            _labels_in(v, out)


def internal_labels() -> set[str]:
    out = set(printed_numbers())
    _labels_in(load_catalogue().model_dump(mode="json"), out)
    _labels_in([e.__dict__ if hasattr(e, "__dict__") else e for e in load_glossary().entries],
               out)
    return out


def internal_label_re() -> re.Pattern:
    """A label where a reader could see it: as a token (not inside a longer word or number),
    alone or after "eq"/"Fig." ("eq an-dp", "eq2b-*1", "ris-*1", "Fig. ris-*1")."""
    labels = sorted(internal_labels(), key=len, reverse=True)
    alt = "|".join(re.escape(x) for x in labels)
    return re.compile(rf"(?<![\w.*/-])(?:eq\s*)?(?:{alt})(?![\w*]|\.\d|/\d)")
