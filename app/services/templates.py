"""Every HTML page of the explorer is a Jinja2 template rendered here: the static pages
(app/static/*.html, whose server-drawn parts are template variables) and the pages built in
Python (app/templates/*.html).

A page writes the parts every page shares in short forms, which `ShortForms` turns into
the calls below before Jinja reads the page: `{{head}}` inside <head>,
`{{site-header:Skip to the …}}` at the top of <body>, `{{site-footer}}` after </main>, and
the paper's numbers `{{printed:LABEL}}` / `{{fig:LABEL}}` (catalogue/printed_numbers.yaml).
The shared parts themselves are written once, in site_shell.py.
"""

from __future__ import annotations

import re
from functools import cache
from pathlib import Path

from jinja2 import Environment, FileSystemLoader, StrictUndefined
from jinja2.ext import Extension
from markupsafe import Markup

from app.services import site_shell
from catalogue.numbering import printed

TEMPLATES = Path(__file__).resolve().parents[1] / "templates"
_HEADER = re.compile(r"\{\{site-header:([^}]*)\}\}")
_NUMBER = re.compile(r"\{\{(printed|fig):([^}]+)\}\}")
_SHARED = ("{{head}}", "{{site-footer}}")


class ShortForms(Extension):
    """The short forms of the shared parts, as template expressions."""

    def preprocess(self, source: str, name: str | None, filename: str | None = None) -> str:
        source = _HEADER.sub(lambda m: "{{ site_header(" + repr(m[1]) + ") }}", source)
        source = source.replace("{{site-footer}}", "{{ site_footer }}")
        return _NUMBER.sub(lambda m: "{{ " + m[1] + "(" + repr(m[2]) + ") }}", source)


def paper_number(label: str) -> str:
    """The number the paper prints for an equation's label, e.g. (2.24)."""
    num = printed(label)
    if num is None:
        raise KeyError(f"no printed number for {label!r}")
    return num


def figure_number(label: str) -> str:
    """A figure's number without its "Fig. " (the page writes that itself)."""
    return paper_number(label).removeprefix("Fig. ")


@cache
def environment() -> Environment:
    # autoescape: a value is escaped unless it is Markup (the HTML the services build)
    env = Environment(loader=FileSystemLoader(TEMPLATES), autoescape=True,
                      keep_trailing_newline=True, extensions=[ShortForms],
                      undefined=StrictUndefined)
    env.globals.update(head=Markup(site_shell.HEAD), site_footer=Markup(site_shell.FOOTER),
                       printed=paper_number, fig=figure_number,
                       # what a part drawn by the page's script shows until it is drawn
                       loading=Markup('<p class="loading">Loading…</p>'))
    return env


@cache
def _compiled(text: str):
    return environment().from_string(text)


def render(text: str, current: str | None = None, **context) -> str:
    """A page's text rendered: the shared head, header (with `current`, the page's address,
    marked in the navigation) and footer, the paper's numbers, and `context`'s values.
    A page without the shared parts is refused."""
    for form in _SHARED:
        if form not in text:
            raise ValueError(f"a static page lacks {form}")
    if not _HEADER.search(text):
        raise ValueError("a static page lacks {{site-header:…}}")
    return _compiled(text).render(
        site_header=lambda skip: Markup(site_shell.header(skip, current)), **context)


def render_file(name: str, current: str | None = None, **context) -> str:
    """A page of app/templates rendered as `render` renders a static page."""
    return render((TEMPLATES / name).read_text(encoding="utf-8"), current, **context)
