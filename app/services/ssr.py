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
                 "evidence": "numerical evidence", "unchecked": "not checked yet"}


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
