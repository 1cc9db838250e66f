"""Pages rendered on the server, so that their content is in the HTML itself: read with
scripts off, by a search engine or a screen reader before any script runs. The scripts
then redraw the same content with typeset formulas, plots and interaction.

Only text a reader needs goes here: the case's title, and each claim's statement in
words with its verdict; the paper's internal LaTeX labels are not shown.
"""

from __future__ import annotations

import re
from html import escape

VERDICT_WORDS = {"verified": "verified", "fails": "fails as printed",
                 "evidence": "numerical evidence", "unchecked": "not checkable",
                 "pending": "checking"}


def _anchor(claim_id: str) -> str:
    # the same anchors as the page's script (case.js anchor())
    return "claim-" + re.sub(r"[^A-Za-z0-9_-]+", "_", claim_id)


def claim_html(c: dict) -> str:
    v = c["verdict"]
    word = VERDICT_WORDS.get(v["verdict"], v["verdict"])
    residual = (f"; largest normalised residual {v['residual']:.1e}"
                if isinstance(v.get("residual"), float) else "")
    where = f"<p class=\"status\">Printed in the paper: {escape(c['where'])}</p>" \
        if c.get("where") else ""
    msg = (f"<details><summary>How it was checked</summary><p>{escape(v['message'])}</p>"
           f"</details>") if v.get("message") else ""
    return (f'<article class="claim ssr" id="{_anchor(c["id"])}">'
            f'<h3>{escape(c["kind"])}: {escape(c["plain"])}</h3>'
            f'<p>Verdict: <strong class="badge {escape(v["verdict"])}">{escape(word)}</strong>'
            f'{escape(residual)}.</p>{where}{msg}</article>')


def case_page(template: str, detail: dict) -> str:
    """case.html with the case's title and claims filled in."""
    title = escape(detail["title"])
    claims = "".join(claim_html(c) for c in detail["claims"])
    counts = ", ".join(f"{n} {VERDICT_WORDS[k]}" for k, n in detail["verdicts"].items() if n)
    return (template
            .replace("<title>Case — Rolling hierarchy</title>",
                     f"<title>{title} — Rolling hierarchy</title>", 1)
            .replace('<h1 id="case-title">Loading…</h1>', f'<h1 id="case-title">{title}</h1>', 1)
            .replace('<div id="claimlist"></div>',
                     f'<div id="claimlist"><p class="status ssr">{len(detail["claims"])} '
                     f'claims: {escape(counts)}.</p>{claims}</div>', 1))


MARK_ICONS = {"verified": "✓", "fails": "✗", "evidence": "◐", "unchecked": "?", "pending": "…"}
MARK_WORDS = {"verified": "property holds", "fails": "property fails",
              "evidence": "numerical evidence", "unchecked": "not checkable",
              "pending": "checking"}


def shade_why(c: dict) -> str:
    """Why a cell is shaded: a disclosure (click, tap, Enter), never a hover title; the
    same markup as the page's script (static/js/home.js shadeWhy)."""
    if not c.get("shade_note"):
        return ""
    word = {"partial": "partial", "full": "gray"}.get(c["shade"], "unshaded")
    return (f'<details class="shade-why"><summary>why {word}?</summary>'
            f'<p>{escape(c["shade_note"])}</p></details>')


def _col(m: dict) -> str:
    return f'<sub class="col">{m["column"]}</sub>' if m.get("column") else ""


def mark_html(c: dict) -> str:
    """The cell's verdict marks as text (one per body, column numbers when merged); the
    script redraws them as links (static/js/marks.js)."""
    v = c.get("verdict")
    if not v:
        return ""
    marks = v.get("marks") or [{"mark": v["mark"], "column": None, "notes": []}]
    many = len(marks) > 1
    spans = "".join(f'<span class="mk {escape(m["mark"])}" aria-hidden="true">'
                    f'{MARK_ICONS.get(m["mark"], "?")}{_col(m) if many else ""}</span>'
                    for m in marks)
    said = ", ".join((f"column {m['column']}: " if many else "") + MARK_WORDS.get(
        m["mark"], m["mark"]) for m in marks)
    notes = "".join(f'<span class="cellnote">{escape(n)}</span>' for n in v.get("notes") or [])
    return (f'<span class="cellmark {escape(v["mark"])}">{spans}'
            f'<span class="sr-only">{escape(said)}</span></span>{notes}')


def table_html(t: dict) -> str:
    """A table of the paper (views.table) as plain HTML: the same rows, columns, merged
    cells and shading as the page's script draws, with the cells' words instead of typeset
    formulas; the verdict marks are left to the script (static/js/marks.js)."""
    head = "".join(
        f'<th scope="col" class="case-head"><a href="{escape(c["href"])}" '
        f'data-case="{escape(c["id"])}"><span class="colno">{c["column"]}</span> '
        f'<span class="coltitle">{escape(c["title"])}</span></a></th>' for c in t["columns"])
    labels = {r["key"]: r.get("plain") or r["key"] for r in t["rows"]}
    shade_words = {"full": " (invariant exists)", "partial": " (incomplete set of integrals)"}
    rows = []
    for grow in t["grid"]:
        cells = []
        for c in grow["cells"]:
            span = f' colspan="{c["colspan"]}"' if c["colspan"] > 1 else ""
            sr = shade_words.get(c["shade"], "")
            sub = f'<div>{escape(c["subrow"]["plain"])}</div>' if c.get("subrow") else ""
            cells.append(f'<td{span} class="shade-{escape(c["shade"])}"><div class="cell-body">'
                         f'{escape(c["plain"])}{sub}<span class="sr-only">{sr}</span></div>'
                         f'{shade_why(c)}{mark_html(c)}</td>')
        rows.append(f'<tr class="row-{escape(grow["key"])}"><th scope="row">'
                    f'{escape(labels[grow["key"]])}</th>{"".join(cells)}</tr>')
    return (f'<table class="paper ssr" id="tbl-{escape(t["id"])}" '
            f'aria-describedby="cap-{escape(t["id"])}"><thead><tr><th scope="col" '
            f'class="corner"><span class="sr-only">row</span></th>{head}</tr></thead>'
            f'<tbody>{"".join(rows)}</tbody></table>')


def home_page(template: str, tables: dict[str, dict]) -> str:
    """index.html with Tables 1 and 2 in the HTML itself."""
    for n, t in enumerate(tables.values(), start=1):
        loading = (f'<div class="table-wrap" tabindex="0"><p class="loading">'
                   f'Loading Table {n}…</p></div>')
        template = template.replace(
            loading, f'<div class="table-wrap" tabindex="0">{table_html(t)}</div>', 1)
    return template
