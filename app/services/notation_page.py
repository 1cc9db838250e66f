"""/notation: every symbol that a typeset formula on a case page uses, where the paper
defines it (printed number, section) and what it means in the project's conventions; and
which case pages use it. The data is catalogue/notation.yaml; the formulas' symbols are
read by catalogue/symbols.py."""

from __future__ import annotations

from functools import cache
from html import escape

from app.services.reader_pages import layout
from catalogue.load import load_catalogue, load_corrected_forms
from catalogue.notation import entry_for, load_notation
from catalogue.numbering import cite, printed
from catalogue.symbols import plain, symbols, symbols_of_math

SECTIONS = {"1": "section 1, equations of motion", "2": "section 2, body on a plane",
            "3": "section 3, body on a sphere"}


def case_formulas(case) -> list[tuple[str, bool]]:
    """Every formula a case page can typeset, as (TeX, is a table cell's text): the cells
    and their second lines, the claims' printed forms, and the project's corrected form of
    each claim whose check has one (shown when the printed form fails)."""
    forms = load_corrected_forms()
    out: list[tuple[str, bool]] = []
    for c in case.cells.values():
        out.append((c.printed, True))
        if c.subrow:
            out.append((c.subrow.printed, True))
    for cl in case.claims:
        out.append((cl.printed, False))
        a = cl.check_args
        fid = next((f for f in (a.formula, a.system, a.bracket) if f in forms), None)
        if fid:
            out.append((forms[fid].latex, False))
    return out


@cache
def usage() -> dict[str, list[tuple[str, str]]]:
    """entry id -> the case pages whose formulas use it, as (case id, title)."""
    out: dict[str, list[tuple[str, str]]] = {}
    for case in load_catalogue().cases():
        ids: dict[str, None] = {}
        for tex, text in case_formulas(case):
            for t in symbols(tex, text):
                e = entry_for(t)
                if e is not None:
                    ids[e.id] = None
        for sid in ids:
            out.setdefault(sid, []).append((case.id, case.title))
    return out


def _tex(s: str) -> str:
    return f'<span class="tex" data-tex="{escape(s)}">{escape(s)}</span>'


def _numbers(labels: list[str]) -> str:
    return ", ".join(printed(x) or x for x in labels)


def entry_json(e) -> dict:
    # what a reader sees: printed numbers in the texts, the labels stay as data
    return {**e.model_dump(), "name": cite(e.name), "convention": cite(e.convention),
            "defined": [{**d.model_dump(), "text": cite(d.text),
                         "numbers": [printed(x) for x in d.labels],
                         "section_title": SECTIONS[d.section]} for d in e.defined],
            "href": f"/notation#sym-{e.id}",
            "cases": [{"id": cid, "title": t, "href": f"/case/{cid}"}
                      for cid, t in usage().get(e.id, [])]}


def notation_json() -> dict:
    return {"entries": [entry_json(e) for e in load_notation().entries]}


def _entry_html(e) -> str:
    defs = "".join(
        f'<li><span class="where">{escape(_numbers(d.labels))}, {escape(SECTIONS[d.section])}'
        f"</span>: {escape(cite(d.text))}</li>" for d in e.defined)
    many = (f'<p class="hint">One symbol, {len(e.defined)} definitions: which one a formula '
            "means follows its section and case.</p>") if len(e.defined) > 1 else ""
    conv = (f'<p class="convention"><strong>In this project:</strong> '
            f"{escape(cite(e.convention))}</p>") if e.convention else ""
    gl = (" <span class=\"hint\">Glossary: " + ", ".join(
        f'<a href="/glossary#g-{escape(g)}">{escape(g)}</a>' for g in e.glossary) + "</span>"
          if e.glossary else "")
    cases = usage().get(e.id, [])
    used = ('<details class="used"><summary>Used on ' + str(len(cases)) + " case page"
            + ("s" if len(cases) != 1 else "") + "</summary><ul>"
            + "".join(f'<li><a href="/case/{escape(c)}">{escape(t)}</a></li>' for c, t in cases)
            + "</ul></details>") if cases else ""
    forms = " ".join(_tex(f) for f in e.forms)
    return (f'<section class="symbol" id="sym-{escape(e.id)}" data-symbol="{escape(e.id)}">'
            f'<h2>{_tex(e.tex)} <span class="symname">{escape(cite(e.name))}</span></h2>'
            f'<p class="forms">Written {forms}.{gl}</p>'
            f'<p>Where the paper defines it:</p><ul class="defined">{defs}</ul>{many}{conv}'
            f"{used}</section>")


def _plain_forms(e) -> str:
    return ", ".join(plain(symbols_of_math(f)[0]) for f in e.forms[:3])


def page() -> str:

    n = load_notation()
    index = " ".join(
        f'<a href="#sym-{escape(e.id)}">{_tex(e.tex)}<span class="sr-only"> '
        f'{escape(_plain_forms(e))}: {escape(cite(e.name))}</span></a>' for e in n.entries)
    body = ("<p>Every symbol that a typeset formula on a case page uses: where the paper "
            "defines it (the number the paper prints, and its section) and what it means in "
            'the project\'s <a href="/guide/conventions/">conventions</a>. One symbol can '
            "have several definitions, by section (A, k, λ, K): each is listed. The "
            'parameters and state variables you can set are also in the <a href="/glossary">'
            'glossary</a>. Each formula on a case page and on <a href="/errata">the errata'
            "</a> links its symbols here.</p>"
            f'<nav class="symindex" aria-label="Symbols">{index}</nav>'
            + "".join(_entry_html(e) for e in n.entries))
    return layout("Notation", body, "/notation")
