"""Pages rendered on the server, so that their content is in the HTML itself: read with
scripts off, by a search engine or a screen reader before any script runs. The scripts
then redraw the same content with typeset formulas, plots and interaction.

Only text a reader needs goes here: the case's title, and each claim's statement in
words with its verdict; the paper's internal LaTeX labels are not shown.
"""

from __future__ import annotations

from html import escape

from markupsafe import Markup

from app.services.anchors import claim_anchor
from app.services.rubber_tables import rubber_summary, rubber_table
from solvers.verify import marks as vocab


def _info(mark: str):
    return vocab.by_id().get(mark) or vocab.by_id()["not-checkable"]


def _erratum_links(errata: list[str]) -> str:
    # the same links as the page's script (static/js/marks.js erratumLinks)
    return ", ".join(f'<a href="/errata#e-{escape(e)}">erratum</a>' for e in errata)


def badge_html(mark: str) -> str:
    m = _info(mark)
    return f'<strong class="badge {escape(mark)}">{m.shape} {escape(m.name)}</strong>'


def claim_label(c: dict) -> str:
    """A claim as a reader knows it: its kind and printed number (cite.js claimLabel)."""
    return c["kind"].replace("-", " ") + (f' {c["number"]}' if c.get("number") else "")


def permalink_html(c: dict) -> str:
    """The claim's visible permalink, the same as the script draws (cite.js permalinkHtml):
    with scripts off a reader can still link to one claim."""
    a = claim_anchor(c["id"])
    return (f'<a class="permalink" href="#{a}" title="Permalink to this claim" '
            f'aria-label="Permalink to the claim {escape(claim_label(c))}">¶</a>')


def claim_html(c: dict, since: str = "") -> str:
    """A claim as an article, with its 'since 2002' note (`since`, since_html) last."""
    v = c["verdict"]
    residual = (f"; largest normalised residual {v['residual']:.1e}"
                if isinstance(v.get("residual"), float) else "")
    where = f"<p class=\"status\">Printed in the paper: {escape(c['where'])}</p>" \
        if c.get("where") else ""
    links = _erratum_links(v.get("errata") or []) if v.get("mark") == "after-correction" else ""
    note = (f'<p class="marknote">{escape(v["mark_note"].rstrip("."))}'
            f'{f" ({links})" if links else ""}.</p>') if v.get("mark_note") else ""
    msg = (f"<details><summary>How it was checked</summary><p>{escape(v['message'])}</p>"
           f"</details>") if v.get("message") else ""
    return (f'<article class="claim ssr" id="{claim_anchor(c["id"])}">'
            f'<h3>{permalink_html(c)} {escape(claim_label(c))}: {escape(c["plain"])}</h3>'
            f'<p>Mark: {badge_html(v.get("mark") or "not-checkable")}'
            f'{escape(residual)}.</p>{note}{where}{msg}{since}</article>')


ACCESS_WORDS = {"full": "read in full", "abstract": "only abstracts or records read",
                "snippet": "only a first page or a snippet read", "none": "nothing cited"}


def since_html(n: dict) -> str:
    """A 'since 2002' note (catalogue/since_2002.yaml) beside its claim or cell: what later
    work says, cited, with how much of it was read, and where the project's own result
    appears new."""
    refs = "".join(f'<li><a href="{escape(r["href"])}">{escape(r["citation"])}</a></li>'
                   for r in n["references"])
    refs = f'<ul class="since-refs">{refs}</ul>' if refs else ""
    project = (f'<p class="since-project"><strong>The project:</strong> '
               f'{escape(n["project"])}</p>') if n.get("project") else ""
    return (f'<aside class="since-2002" data-record="{escape(n["record"])}" '
            f'data-kind="{escape(n["kind"])}" data-access="{escape(n["access"])}">'
            f'<p><strong>Since 2002</strong> ({escape(n["kind"])}; '
            f'{ACCESS_WORDS[n["access"]]}): {escape(n["note"])}</p>{refs}{project}</aside>')


def symbol_link(s: dict) -> str:
    """A symbol of a formula as a link to its entry on /notation, its name on hover; the
    same markup as the page's script (static/js/notation.js symbolLink). A click or tap
    shows the definition in place (notation.js); without scripts the link opens it."""
    return (f'<a class="sym" href="{escape(s["href"])}" data-sym="{escape(s["id"])}" '
            f'title="{escape(s["name"])}"><span class="tex" data-tex="{escape(s["tex"])}">'
            f'{escape(s["tex"])}</span><span class="sr-only"> {escape(s["text"])}: '
            f'{escape(s["name"])}</span></a>')


# a rubber case page typesets its cells (beyond the paper): their symbols are the guide's
RUBBER_SYMBOLS = ('<p class="status">The symbols of the rubber tables\' cells are defined on '
                  'the guide\'s page Rubber rolling: Ĩ = I + m (r² E − r rᵀ) with '
                  '<a href="/guide/rubber/#equations">the equations</a>, Q and N with '
                  '<a href="/guide/rubber/#the-rubber-tables">the rubber tables</a>.</p>')


def notation_html(refs: list[dict], rubber: bool = False) -> str:
    """The page's symbols, each linked to its definition (views.page_notation); on a rubber
    case's page, where its cells' symbols are defined instead."""
    if rubber:
        return RUBBER_SYMBOLS
    if not refs:
        return '<p class="status">No typeset formula on this page.</p>'
    return ('<ul class="symbols-page">' + "".join(
        f'<li>{symbol_link(s)} <span class="symname">{escape(s["name"])}</span></li>'
        for s in refs) + "</ul>")


def case_context(detail: dict) -> dict:
    """The server-drawn parts of case.html: the case's title, its counts by mark, its
    claims (each claim and open cell with its 'since 2002' note, if it has one) and the
    symbols of its formulas."""
    notes = {n["record"]: n for n in detail.get("since_2002") or []}
    claims = "".join(claim_html(c, since_html(notes[c["id"]]) if c["id"] in notes else "")
                     for c in detail["claims"])
    cells = [n for n in notes.values() if "/cell/" in n["record"]]
    if cells:
        claims += ('<section class="since-cells ssr" id="since-2002"><h3>Since 2002: the '
                   'table\'s open cells</h3>' +
                   "".join(f'<div id="{claim_anchor(n["record"])}"><p>Cell '
                           f'{escape(n["record"].split("/cell/")[1].replace("_", " "))}:</p>'
                           f'{since_html(n)}</div>' for n in cells) + "</section>")
    return {"title": Markup(escape(detail["title"])),
            "summary": Markup(escape(detail.get("summary") or "")),
            "claims": Markup(claims),
            "notation": Markup(notation_html(detail.get("notation") or [],
                                             rubber=bool(detail.get("rubber"))))}


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


def mark_why(marks: list[dict]) -> str:
    """What goes with a cell's marks (the convention, the misprint and its erratum, what an
    inconclusive check found): a disclosure, the same markup as static/js/marks.js."""
    seen, parts = set(), []
    for m in marks:
        if not m.get("mark_note") and not m.get("errata"):
            continue
        key = (m["mark"], m.get("mark_note") or "")
        if key in seen:
            continue
        seen.add(key)
        who = f"column {m['column']}, " if len(marks) > 1 and m.get("column") else ""
        links = _erratum_links(m.get("errata") or []) if m["mark"] == "after-correction" \
            else ""
        parts.append(f"<p>{who}{escape(_info(m['mark']).name)}: "
                     f"{escape(m.get('mark_note') or '')}{f' ({links})' if links else ''}</p>")
    return (f'<details class="mark-why"><summary>why?</summary>{"".join(parts)}</details>'
            if parts else "")


def mark_html(c: dict) -> str:
    """The cell's marks as text: each body's shape (column numbers when merged), the word
    once per run of equal marks, the meaning for screen readers, and why; the script
    redraws them as links (static/js/marks.js markHtml)."""
    v = c.get("verdict")
    if not v:
        return ""
    marks = v.get("marks") or [{"mark": v["mark"], "column": None, "case": ""}]
    many = len(marks) > 1
    out = ""
    for i, m in enumerate(marks):
        info = _info(m["mark"])
        out += (f'<span class="mk {escape(m["mark"])}" data-case="{escape(m.get("case", ""))}"'
                f' aria-hidden="true">{info.shape}{_col(m) if many else ""}</span>')
        if i + 1 == len(marks) or marks[i + 1]["mark"] != m["mark"]:
            out += f'<span class="mkword" aria-hidden="true">{escape(info.word)}</span>'
    said = ", ".join((f"column {m['column']}: " if many else "") + _info(m["mark"]).name
                     for m in marks)
    return (f'<span class="cellmark {escape(v["mark"])}">{out}'
            f'<span class="sr-only">{escape(said)}</span></span>{mark_why(marks)}')


def legend_html() -> str:
    """The home page's key to the marks, from the vocabulary (solvers/verify/marks.yaml)."""
    return "".join(f'<span class="key"><span class="mark {escape(m.id)}" aria-hidden="true">'
                   f'{m.shape}</span>{escape(m.name)}</span>' for m in vocab.vocabulary())


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
    return table_shell("paper ssr", t["id"], head, rows)


def table_shell(classes: str, table_id: str, head: str, rows: list[str]) -> str:
    """The markup around a paper-style table's header cells and rows: its id (tbl-...), its
    caption's id, the corner cell."""
    return (f'<table class="{classes}" id="tbl-{escape(table_id)}" '
            f'aria-describedby="cap-{escape(table_id)}"><thead><tr><th scope="col" '
            f'class="corner"><span class="sr-only">row</span></th>{head}</tr></thead>'
            f'<tbody>{"".join(rows)}</tbody></table>')


def rubber_mark_html(c: dict) -> str:
    """A rubber cell's mark as a link to its claims below the table: the shape and word of
    the vocabulary (the same markup as static/js/marks.js markHtml draws for Tables 1 and 2)
    and the level of the check behind it."""
    info = _info(c["mark"])
    level = (f'<span class="mklevel">{escape(c["level_words"])}</span>'
             if c.get("level_words") else "")
    return (f'<a class="cellmark {escape(c["mark"])}" href="#{escape(c["anchor"])}">'
            f'<span class="mk {escape(c["mark"])}" data-case="{escape(c["case"])}" '
            f'aria-hidden="true">{info.shape}</span><span class="mkword" aria-hidden="true">'
            f'{escape(info.word)}</span><span class="sr-only">{escape(info.name)}; its '
            f'sources and checks</span></a>{level}')


def _sources_line(c: dict) -> str:
    """Who a cell's claims come from, each with how much of it was read."""
    seen, parts = set(), []
    for cl in c["claims"]:
        key = (cl["short"], cl["access_words"])
        if key not in seen:
            seen.add(key)
            parts.append(f'<span class="src access-{escape(cl["access"])}">'
                         f'{escape(cl["short"])}</span>'
                         + ("" if cl["access"] == "derived-here"
                            else f' <span class="access">({escape(cl["access_words"])})</span>'))
    if not parts:
        return '<p class="cell-src">no source read or derived here</p>'
    return f'<p class="cell-src">{"; ".join(parts)}</p>'


def rubber_statement_html(c: dict, tag: str, cls: str) -> str:
    """A rubber cell's statement: its plain text, with its LaTeX in `data-tex` for the page's
    script to typeset as it typesets Tables 1 and 2 (static/js/home.js, latex.js textHtml)."""
    return (f'<{tag} class="{cls}" data-tex="{escape(c["tex"])}">{escape(c["plain"])}'
            f'</{tag}>')


def rubber_table_html(t: dict) -> str:
    """A rubber table (rubber_tables.rubber_table): one column per body, one row per invariant;
    every cell its statement, its sources with their access, and its mark linking to its
    claims. The marks are the catalogue's and stay as drawn here; the page's script only
    typesets the statements (rubber_statement_html)."""
    head = "".join(
        '<th scope="col" class="case-head">'
        + (f'<a href="{escape(c["href"])}" data-case="{escape(c["model"])}">' if c["href"]
           else '<span>')
        + f'<span class="colno">{c["column"]}</span> <span class="coltitle">'
        f'{escape(c["title"])}</span>' + ("</a>" if c["href"] else "</span>") + "</th>"
        for c in t["columns"])
    labels = {r["key"]: r["plain"] for r in t["rows"]}
    rows = []
    for grow in t["grid"]:
        cells = "".join(
            f'<td class="shade-none rubber-cell" data-case="{escape(c["case"])}" '
            f'data-mark="{escape(c["mark"])}">{rubber_statement_html(c, "div", "cell-body")}'
            f'{_sources_line(c)}{rubber_mark_html(c)}</td>' for c in grow["cells"])
        rows.append(f'<tr class="inv row-{escape(grow["key"])}"><th scope="row">'
                    f'{escape(labels[grow["key"]])}</th>{cells}</tr>')
    return table_shell("paper rubber", t["id"], head, rows)


def _claim_item(cl: dict) -> str:
    """One claim of a rubber cell: its source (cited in full), the place and how much of it
    was read, what it says and how the project's check relates to it; the module and the
    test behind a derived claim sit behind a Details toggle, the developer's view, as on
    the case pages."""
    derived = cl["access"] == "derived-here"
    src = "<strong>Derived here</strong>" if derived else (
        f'<cite>{escape(cl["cite"])}</cite>, {escape(cl["place"])}')
    agree = "" if cl["agreement"] == "n/a" else f'; our check: {escape(cl["agreement"])}'
    dev = [f'<dt>where</dt><dd><code>{escape(cl["place"])}</code></dd>'] if derived else []
    if cl["check"]:
        dev.append(f'<dt>check</dt><dd><code>{escape(cl["check"])}</code>'
                   f'{" (" + escape(cl["level"]) + ")" if cl["level"] else ""}</dd>')
    details = (f'<details class="dev"><summary>Details</summary><dl>{"".join(dev)}</dl>'
               f'</details>') if dev else ""
    return (f'<li class="rubber-claim access-{escape(cl["access"])}">{src} '
            f'<span class="access">({escape(cl["access_words"])})</span>: '
            f'{escape(cl["says"])}{agree}.{details}</li>')


def rubber_claims_html(t: dict) -> str:
    """Where each cell of a rubber table comes from: one entry per cell, at the anchor its
    mark links to, with its statement (a box that scrolls sideways when a typeset matrix is
    wider than a phone) and every claim's source, place, access and check."""
    labels = {r["key"]: r["plain"] for r in t["rows"]}
    titles = {c["id"]: c["title"] for c in t["columns"]}
    out = []
    for grow in t["grid"]:
        for c in grow["cells"]:
            items = "".join(_claim_item(cl) for cl in c["claims"]) or (
                '<li>No source read says anything of it, and nothing was derived here.</li>')
            out.append(f'<article class="rubber-cell-claims" id="{escape(c["anchor"])}">'
                       f'<h4>{escape(titles[c["case"]])}: {escape(labels[grow["key"]])}</h4>'
                       f'<p>Mark: {badge_html(c["mark"])}'
                       f'{"; check: " + escape(c["level_words"]) if c["level_words"] else ""}'
                       f'.</p>{rubber_statement_html(c, "div", "cell-statement scroll-x")}'
                       f'<ul>{items}</ul></article>')
    return "".join(out)


def home_context(tables: dict[str, dict], summary: str = "") -> dict:
    """The server-drawn parts of index.html: Tables 1 and 2, the key to the marks and the
    counts by mark; the rubber tables beyond the paper, their counts by mark and where
    each of their cells comes from."""
    rubber = [rubber_table(tid) for tid in ("rubber-plane", "rubber-sphere")]
    return {"legend": Markup(legend_html()), "summary": Markup(escape(summary)),
            "tables": [Markup(table_html(t)) for t in tables.values()],
            "rubber_summary": Markup(escape(rubber_summary(rubber))),
            "rubber": [{"id": t["id"], "title": t["title"], "note": t["note"],
                        "summary": t["summary"], "table": Markup(rubber_table_html(t)),
                        "claims": Markup(rubber_claims_html(t))} for t in rubber]}
