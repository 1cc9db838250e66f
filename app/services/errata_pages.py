"""/errata rendered on the server, and its exports.

The page's rows, its index and its counts are in the HTML itself (readable without scripts,
as the home and case pages are: app/services/ssr.py); static/js/errata.js redraws them with
typeset formulas. The counts tell misprints apart from the rows that repeat one: a formula
that fails only through a misprinted one it uses (kind inherited) is a row, not another
misprint, and so is a misprinted display that several cases use (one row per case). The
index names each display once, with a link to each of its rows.

Every typeset formula of a row lists its symbols, each a link to its definition on
/notation, as on the case pages (`with_symbols`: the rows of /api/errata, /api/conventions
and /api/findings carry the lists, the page's script draws them under each formula).

Exports: /errata.csv (one line per row) and /errata.bib (the paper's entry, then one @misc
per misprint: the explorer's erratum, with the printed and the corrected form).
"""

from __future__ import annotations

import csv
import io
import json
import re
from datetime import date
from functools import cache
from html import escape
from pathlib import Path

from markupsafe import Markup

from app import __version__
from app.services import reader_pages
from app.services.anchors import claim_anchor
from app.services.ssr import symbol_link
from app.services.views import symbol_refs

SECTION_TITLES = {"1": "Equations of motion", "2": "Body on a plane", "3": "Body on a sphere"}


def section_of(e: dict) -> str:
    """The section number of a row ("other" when it has none), as errata.js sectionOf."""
    return (e.get("section") or "").removeprefix("section ") or "other"


def misprint_key(e: dict) -> str:
    """What makes two rows one misprint: the display that is corrected."""
    return (e.get("corrected_label") or e.get("corrected_where") or e.get("corrected_formula")
            or e["claim"])


def counts(errata: list[dict]) -> dict:
    """misprints: distinct displays corrected among the rows that are a misprint;
    misprint_rows: those rows (a display that several cases use has a row for each);
    inherited: the rows that fail only through a misprint; rows: all of them."""
    own = [e for e in errata if e.get("kind") != "inherited"]
    return {"rows": len(errata), "misprints": len({misprint_key(e) for e in own}),
            "misprint_rows": len(own), "inherited": len(errata) - len(own)}


def counts_sentence(errata: list[dict]) -> str:
    """'23 misprints, and 5 inherited rows that repeat one' (with the rows of a display
    that several cases use said apart, when there are such)."""
    n = counts(errata)
    words = f"{n['misprints']} misprint{'' if n['misprints'] == 1 else 's'}"
    if n["misprint_rows"] > n["misprints"]:
        extra = n["misprint_rows"] - n["misprints"]
        words += (f" ({extra} more row{'' if extra == 1 else 's'} where several cases "
                  "use the same display)")
    inh = n["inherited"]
    return (f"{words}, and {inh} inherited row{'' if inh == 1 else 's'} that "
            f"repeat{'s' if inh == 1 else ''} one")


# ---- the symbols of a row's formulas, each linked to /notation


def formulas_of(e: dict) -> list[tuple[str, str]]:
    """A row's typeset formulas as (role, TeX): "printed", the display as printed (the
    corrected display's, for a misprint); "claim", the claim as printed where that is
    another display; "corrected", the project's corrected form. A finding about a figure
    quotes its caption, no formula."""
    if e.get("claim", "").startswith("figure/"):
        return []
    shown = e.get("corrected_printed") or e.get("printed")
    out = [("printed", shown)] if shown else []
    if e.get("corrected_printed") and e.get("printed") and e["printed"] != shown:
        out.append(("claim", e["printed"]))
    if e.get("corrected_tex"):
        out.append(("corrected", e["corrected_tex"]))
    return out


def with_symbols(rows: list[dict]) -> list[dict]:
    """The rows, each with `symbols`: role -> the symbols of that formula, each with its
    entry on /notation (views.symbol_refs)."""
    return [{**e, "symbols": {role: symbol_refs(tex) for role, tex in formulas_of(e)}}
            for e in rows]


def _symbols(e: dict, role: str) -> str:
    """The symbols of one of the row's formulas, as the case pages list them."""
    refs = (e.get("symbols") or {}).get(role) or []
    if not refs:
        return ""
    return ('<p class="symbols"><span class="symlabel">Symbols:</span> '
            + " ".join(symbol_link(s) for s in refs) + "</p>")


# ---- the index: each display once, with a link to each of its rows


def _tip(e: dict) -> str:
    name = e.get("claim_name") or ""
    return f"{e.get('case_title') or e['case']}{f', {name}' if name else ''}"


def _grouped_links(rows: list[tuple[str, dict]]) -> str:
    """rows: (label, entry) in order; one link per label, then numbered links to every row
    that label stands for."""
    groups: dict[str, list[dict]] = {}
    for label, e in rows:
        groups.setdefault(label, []).append(e)
    out = []
    for label, es in groups.items():
        first = (f'<a href="#{escape(es[0]["anchor"])}" title="{escape(_tip(es[0]))}">'
                 f"{escape(label)}</a>")
        if len(es) > 1:
            more = " ".join(f'<a href="#{escape(e["anchor"])}" title="{escape(_tip(e))}">'
                            f"{i}</a>" for i, e in enumerate(es, 1))
            first += f' <span class="rows">({len(es)} rows: {more})</span>'
        out.append(f'<span class="idx">{first}</span>')
    return " ".join(out) or "—"


def index_html(errata: list[dict], conventions: list[dict], findings: list[dict]) -> str:
    secs: dict[str, dict] = {}

    def add(e: dict, what: str, label: str) -> None:
        rec = secs.setdefault(section_of(e), {"title": "", "errata": [], "conventions": [],
                                              "findings": []})
        rec["title"] = e.get("section_title") or rec["title"]
        rec[what].append((label, e))

    for e in errata:
        add(e, "errata", e.get("corrected_display") or e.get("place") or "")
    for e in conventions:
        add(e, "conventions", e.get("place") or "")
    for e in findings:
        add(e, "findings", e.get("place") or e.get("title") or "")
    n = counts(errata)
    body = "".join(
        f'<tr id="index-{escape(s)}"><th scope="row">Section {escape(s)}. '
        f'{escape(r["title"] or SECTION_TITLES.get(s, ""))}</th>'
        f'<td>{_grouped_links(r["errata"])}</td><td>{_grouped_links(r["conventions"])}</td>'
        f'<td>{_grouped_links(r["findings"])}</td></tr>' for s, r in sorted(secs.items()))
    return ('<div class="table-wrap"><table class="eindex"><thead><tr>'
            '<th scope="col">section</th>'
            f'<th scope="col">misprints ({n["misprints"]}, in {n["rows"]} rows): the corrected '
            f'displays</th><th scope="col">conventions ({len(conventions)})</th>'
            f'<th scope="col">findings ({len(findings)})</th></tr></thead>'
            f"<tbody>{body}</tbody></table></div>")


# ---- the rows, as errata.js draws them, formulas as their TeX source


def _res(x) -> str:
    if x is None:
        return "n/a"
    if x == 0:
        return "0"
    return f"{x:.2g}" if abs(x) >= 1e-3 else f"{x:.1e}"


def _claim_href(e: dict) -> str:
    return e.get("href") or f"/case/{e['case']}#{claim_anchor(e['claim'])}"


def _claim_link(e: dict) -> str:
    text = f"{e['claim_name']} of {e.get('case_title')}" if e.get("claim_name") \
        else (e.get("case_title") or "the case")
    return (f'<a class="claimname" href="{escape(_claim_href(e))}" '
            f'data-claim="{escape(e["claim"])}">{escape(text)}</a>')


def _tex(tex: str | None) -> str:
    return f'<pre class="printed tex" tabindex="0"><code>{escape(tex or "")}</code></pre>'


def _row(e: dict, badge: str, disp: str, change: str, res: str, body: str) -> str:
    return (f'<details class="erow ssr" id="{escape(e["anchor"])}" '
            f'data-section="{escape(section_of(e))}"><summary><span class="disp">{badge} '
            f"<strong>{escape(disp)}</strong></span>"
            f'<span class="case">{escape(e.get("case_title") or e["case"])}</span>'
            f'<span class="change">{escape(change)}</span><span class="res">{res}</span>'
            f'</summary><div class="ebody"><a class="permalink" href="#{escape(e["anchor"])}" '
            f'title="Link to this row">¶</a> {body}'
            f'<p class="repro">Reproduce: <code>{escape(e["reproduce"])}</code></p>'
            "</div></details>")


def _claim_form(e: dict) -> str:
    """The claim as printed, where it is another display than the corrected one."""
    if not any(role == "claim" for role, _ in formulas_of(e)):
        return ""
    return (f'<details class="claimform"><summary>the claim as printed at '
            f'{escape(e.get("place") or "")}</summary>{_tex(e.get("printed"))}'
            f'{_symbols(e, "claim")}</details>')


def erratum_html(e: dict) -> str:
    badge = ('<span class="ek inherited">↳ inherited</span>' if e.get("kind") == "inherited"
             else '<span class="ek misprint">✗ misprint</span>')
    disp = e.get("corrected_display") or e.get("place") or ""
    inherits = (f'<p>Inherited: this formula uses <a href="#e-{escape(e["inherits"])}">a '
                "misprinted one</a> and fails only through it.</p>"
                if e.get("kind") == "inherited" and e.get("inherits") else "")
    body = (f'<p class="where">Corrected display: <strong>{escape(disp)}</strong>. The claim '
            f"that fails as printed stands at {escape(e.get('number') or e.get('where') or '')}"
            f": {_claim_link(e)}.</p>"
            f"<h4>Printed {escape(disp)} (TeX)</h4>"
            f"{_tex(e.get('corrected_printed') or e.get('printed'))}{_symbols(e, 'printed')}"
            f"<p>residual of the claim as printed {_res(e.get('residual_printed'))} (fails)</p>"
            f"<h4>Corrected (the project, TeX)</h4>{_tex(e.get('corrected_tex'))}"
            f"{_symbols(e, 'corrected')}"
            f"<p>residual {_res(e.get('residual_corrected'))}</p>{_claim_form(e)}"
            f'<p class="note"><strong>What changes:</strong> {escape(e.get("change") or "")}'
            f"</p>{inherits}")
    res = f"{_res(e.get('residual_printed'))} → {_res(e.get('residual_corrected'))}"
    return _row(e, badge, disp, e.get("change") or "", res, body)


def convention_html(e: dict) -> str:
    body = (f'<p class="where">The claim: {_claim_link(e)}.</p>{_tex(e.get("printed"))}'
            f'{_symbols(e, "printed")}<p><strong>Convention:</strong> '
            f'{escape(e.get("convention") or "")}</p>'
            f"<p>Under this convention the printed form holds: residual "
            f"{_res(e.get('residual_under_convention'))}. Read with the project's convention "
            f"instead, it fails: residual {_res(e.get('residual_printed'))}.</p>")
    res = f"{_res(e.get('residual_under_convention'))} · {_res(e.get('residual_printed'))}"
    return _row(e, '<span class="ek convention">◇ convention</span>', e.get("place") or "",
                e.get("convention") or "", res, body)


FINDING_WORDS = {"refuted-conjecture": "✗ refuted conjecture", "refuted": "✗ refuted",
                 "inconclusive": "◌ inconclusive"}


def finding_html(e: dict) -> str:
    word = FINDING_WORDS.get(e.get("kind") or "", e.get("kind") or "")
    body = (f'<p class="where">The paper ({escape(e.get("where") or e.get("place") or "")}), '
            f"{_claim_link(e)}:</p>{_tex(e.get('printed'))}{_symbols(e, 'printed')}"
            f'<p><strong>Found:</strong> {escape(e.get("finding") or "")}</p>')
    return _row(e, f'<span class="ek {escape(e.get("kind") or "")}">{escape(word)}</span>',
                e.get("place") or "", e.get("title") or "", escape(word), body)


def _grouped(rows: list[dict], render) -> str:
    out, last = [], None
    for e in rows:
        s = section_of(e)
        if s != last:
            title = f". {escape(e['section_title'])}" if e.get("section_title") else ""
            out.append(f'<h3 class="esec">Section {escape(s)}{title}</h3>')
            last = s
        out.append(render(e))
    return "".join(out)


def status_sentence(errata: list[dict], conventions: list[dict], findings: list[dict],
                    state: str, done: int, total: int) -> str:
    s = (f"{counts_sentence(errata)}; {len(conventions)} conventions, "
         f"{len(findings)} findings")
    return s + ("." if state == "done" else
                f" — verification {state}: {done} of {total} cases so far.")


def errata_context(errata: list[dict], conventions: list[dict], findings: list[dict],
                   state: str = "done", done: int = 0, total: int = 0) -> dict:
    """The server-drawn parts of errata.html: its status, index, counts and rows, each
    formula with its symbols linked to /notation."""
    errata, conventions, findings = (with_symbols(x) for x in (errata, conventions, findings))
    n = counts(errata)
    status = status_sentence(errata, conventions, findings, state, done, total)
    return {
        "status": Markup(escape(status)),
        "index": Markup(index_html(errata, conventions, findings)),
        "n_errata": Markup(f'({n["misprints"]} misprints in {n["rows"]} rows)'),
        "errata_rows": Markup(_grouped(errata, erratum_html) or "<p>No misprint found yet.</p>"),
        "n_conventions": Markup(f"({len(conventions)})"),
        "convention_rows": Markup("".join(map(convention_html, conventions))
                                  or "<p>None yet.</p>"),
        "n_findings": Markup(f"({len(findings)})"),
        "finding_rows": Markup("".join(map(finding_html, findings)) or "<p>None found yet.</p>"),
    }


# ---- exports

CSV_FIELDS = ("anchor", "url", "kind", "section", "corrected_display", "claim", "claim_name",
              "case", "case_title", "place", "change", "printed", "corrected_printed",
              "corrected_tex", "residual_printed", "residual_corrected", "inherits",
              "reproduce")


def errata_csv(errata: list[dict], base: str) -> str:
    """One line per row of the misprints' table, with the row's address."""
    out = io.StringIO()
    w = csv.DictWriter(out, CSV_FIELDS, extrasaction="ignore", lineterminator="\n")
    w.writeheader()
    for e in errata:
        w.writerow({**{k: e.get(k) for k in CSV_FIELDS},
                    "url": f"{base}/errata#{e['anchor']}",
                    "section": section_of(e)})
    return out.getvalue()


LATEX_JS = Path(__file__).resolve().parents[1] / "static" / "js" / "latex.js"


@cache
def paper_macros() -> dict[str, str]:
    """The paper's own macros, as the pages' KaTeX defines them (latex.js MACROS: one
    definition for the pages and the exports)."""
    block = LATEX_JS.read_text(encoding="utf-8").split("export const MACROS = {", 1)[1]
    block = block.split("};", 1)[0]
    return {json.loads(f'"{k}"'): json.loads(f'"{v}"')
            for k, v in re.findall(r'^\s*"((?:[^"\\]|\\.)+)":\s*"((?:[^"\\]|\\.)*)",',
                                   block, re.M)}


def _fill(body: str, m: re.Match) -> str:
    return re.sub(r"#(\d)", lambda k: m[int(k[1])], body)


def expand(tex: str) -> str:
    """The paper's macros expanded, so that a citing document needs only amsmath: those
    with brace arguments first, then the others (the same as cite.js expandMacros)."""
    for name, body in paper_macros().items():
        n = max((int(k) for k in re.findall(r"#(\d)", body)), default=0)
        if n:
            pat = re.escape(name) + r"(?![A-Za-z])" + r"\s*\{([^{}]*)\}" * n
            tex = re.sub(pat, lambda m, b=body: _fill(b, m), tex)

    def one(m: re.Match) -> str:
        body = paper_macros().get(m[0])
        return body if body is not None and "#" not in body else m[0]

    return re.sub(r"\\[A-Za-z]+(?![A-Za-z])", one, tex)


def _inline(tex: str | None) -> str:
    """A display as one line of inline math for a BibTeX note (as cite.js texInline): the
    paper's macros expanded, an alignment outside any environment put in `aligned`, as the
    pages' KaTeX reads it."""
    t = re.sub(r"(\\\\\s*)+$", "", expand(tex or "").strip())
    if "$" not in t:
        if re.search(r"(^|[^\\])&", t) and "\\begin{" not in t:
            t = f"\\begin{{aligned}}{t}\\end{{aligned}}"
        t = f"${t}$"
    return re.sub(r"\s+", " ", t).strip()


def errata_bibtex(errata: list[dict], base: str, today: date | None = None) -> str:
    """The paper's entry, then one @misc per misprint (the rows of one display together):
    the explorer's erratum, its address, the printed and the corrected form, related to
    the paper's key."""
    today = today or date.today()
    paper = reader_pages.cite_data()["paper"]
    groups: dict[str, list[dict]] = {}
    for e in errata:
        if e.get("kind") != "inherited":
            groups.setdefault(misprint_key(e), []).append(e)
    sw = reader_pages.cite_data()["software"]["fields"]
    out = [reader_pages.bibtex(paper)]
    for es in groups.values():
        e = es[0]
        disp = e.get("corrected_display") or e.get("place") or ""
        cases = ", ".join(dict.fromkeys(x.get("case_title") or x["case"] for x in es))
        note = (f"Erratum to Borisov and Mamaev (2002), {disp} ({e.get('section_title') or ''}"
                f"; {cases}): {e.get('change') or ''}. As printed (fails): "
                f"{_inline(e.get('corrected_printed') or e.get('printed'))}. Corrected, "
                f"checked by computation: {_inline(e.get('corrected_tex'))}")
        entry = {"type": "misc", "key": reader_pages.cite_key(f"errata/{e['claim']}"),
                 "fields": {"author": sw["author"],
                            "title": f"Erratum to Borisov and Mamaev (2002), {disp}",
                            "howpublished": "Rolling hierarchy (the explorer's errata)",
                            "version": __version__, "year": str(today.year),
                            "url": f"{base}/errata#{e['anchor']}",
                            "urldate": today.isoformat(), "related": paper["key"],
                            "note": note}}
        out.append(reader_pages.bibtex(entry))
    return "\n\n".join(out) + "\n"
