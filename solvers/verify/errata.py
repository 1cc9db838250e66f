"""Errata and findings, from the records of
`verify`: the rows of the reference table /errata.

* errata: every printed formula that fails where the project's correction holds -- the
  misprints (qualifier misprint) and the formulas that fail only through one of them
  (inherited) -- with the printed form, the corrected form as TeX and what it changes
  (catalogue/corrected_forms.yaml), the display that is actually corrected (not always
  the one where the failing claim stands: a misprint in u of (2.10) makes (2.9) fail),
  its section, both residuals, the exact witness when the record carries one, the command
  that reproduces it and the row's anchor;
* conventions: printed forms that hold under another convention than the project's;
* findings: what the paper does not have -- a hedged claim answered (refuted-conjecture),
  a printed statement refuted with no correction (refuted), and the checks that ran and
  could not decide while what they found leans against the paper (inconclusive), with
  their evidence; `figure_findings` adds the paper's figures whose caption the recomputed
  figure does not confirm (bench/paper_figures.py).
"""

from __future__ import annotations

import re

from catalogue.load import load_corrected_forms
from catalogue.numbering import cite as _cite
from catalogue.numbering import cite_latex as _cite_latex
from catalogue.numbering import printed
from catalogue.schema import Catalogue

ERRATA_KINDS = ("misprint", "inherited")
FINDING_KINDS = ("refuted-conjecture", "refuted")
# a negative check ("no measure", "no further integral") that ran and found none of what the
# statement predicts (a chaotic layer, a contracting orbit): its message starts so
INCONCLUSIVE = "inconclusive"
NEGATIVE_CHECKS = ("negative_integral", "negative_measure")
# the paper's \section titles (seed, lines 66, 200, 1091)
SECTIONS = {"1": "Equations of rigid body motion on a plane and a sphere without sliding",
            "2": "Body on a plane", "3": "Body on a sphere"}
FIGURES_REPRODUCE = "python bench/paper_figures.py"
FINDING_TITLES = {
    "plane/spherical-inertia/negative/sphere-generalization":
        "An invariant measure of the position alone for a body with spherical inertia on "
        "a sphere (the paper: 'probably, this generalization does not exist')",
    "sphere/borisov-fedorov/reduction/to-chaplygin":
        "The printed map of the Borisov-Fedorov ball (a = 2R) to the Chaplygin ball on a "
        "plane does not hold",
    "plane/ellipsoid/negative/general-measure":
        "No smooth invariant measure for the balanced ellipsoid with I = mu E + lambda m B, "
        "lambda = 1/2 (the paper: 'it is possible, that this measure exists')",
}


def printed_number(label: str | None) -> str | None:
    """What a reader of the printed paper finds: "(2.15)", not the LaTeX label."""

    return printed(label)


def cite(text):
    """Reader's text: every internal label replaced by its printed number (strings inside
    lists and dicts too); labels stay as data in the `label` field only."""

    if isinstance(text, str):
        return _cite(text)
    if isinstance(text, dict):
        return {cite(k): cite(v) for k, v in text.items()}
    if isinstance(text, list):
        return [cite(v) for v in text]
    return text


def cite_latex(tex: str | None) -> str | None:

    return _cite_latex(tex)


def reproduce(claim_id: str) -> str:
    return f"rolling verify --claim {claim_id} --json"


def section_of(label: str | None) -> str | None:
    """The paper's section from an equation label (eq2.15, eq2b-*1, eq3.10 -> 2, 2, 3)."""
    m = re.match(r"^eq(\d)", label or "")
    return f"section {m.group(1)}" if m else None


def section_number(number: str | None, where: str | None) -> str | None:
    """The section a display stands in: from its printed number "(3.16)", else from where
    it is printed ("section 3, ...", or Table 1 / Table 2, which close sections 2 and 3)."""
    m = re.match(r"^\((\d)\.", number or "")
    if m:
        return m[1]
    m = re.match(r"^section (\d)", where or "")
    if m:
        return m[1]
    m = re.match(r"^Table ([12])", where or "")
    return str(int(m[1]) + 1) if m else None


def short_place(number: str | None, where: str | None) -> str:
    """How the index names a display: its number, or, unnumbered, where it stands in a few
    words ("after (2.37)", "Table 2, measure row")."""
    if number:
        return number
    w = where or ""
    m = re.search(r"\b(after|before) (\(\d+\.\d+\)|the [a-z ]+)", w)
    if m:
        return f"unnumbered, {m[1]} {m[2]}"
    m = re.match(r"^(Table \d, [a-z]+ row)", w)
    return m[1] if m else (w.split(",")[0] or "unnumbered")


def corrected_display(fid: str | None, cat: Catalogue) -> dict:
    """The display the correction of formula `fid` changes (corrected_forms.yaml: its
    `display`, else the formula's own), its printed number or place, and its section."""

    cf = load_corrected_forms().get(fid or "")
    if cf is None:
        return {"corrected_tex": None, "change": None, "corrected_label": None,
                "corrected_display": None, "corrected_printed": None}
    f = cat.formula(cf.display or fid)
    number = printed_number(f.label)
    where = cite(f.where)
    return {"corrected_tex": cf.latex, "change": cite(cf.change), "corrected_label": f.label,
            "corrected_printed": cite_latex(f.printed),
            "corrected_display": number or short_place(None, where),
            "corrected_where": where, "corrected_number": number,
            "corrected_section": section_number(number, where)}


def claim_name(kind: str, number: str | None) -> str:
    """A claim as a reader knows it, as case pages name it: its kind and printed number
    ("integral (2.24)"); the record id stays data (the row's anchor, its link)."""
    return kind.replace("-", " ") + (f" {number}" if number else "")


def _base(rec: dict, cat: Catalogue) -> dict:
    claim = cat.claim(rec["claim"])
    return {"claim": rec["claim"], "case": rec["case"], "kind": rec.get("qualifier"),
            "case_title": cat.case(rec["case"]).title,
            "claim_name": claim_name(claim.kind.value, printed_number(claim.label)),
            "label": claim.label, "number": printed_number(claim.label),
            "where": cite(claim.where), "section": section_of(claim.label),
            "printed": cite_latex(claim.printed), "plain": cite(claim.plain),
            "residual_printed": rec.get("residual"), "message": cite(rec.get("message", "")),
            "exact": rec.get("exact"), "reproduce": reproduce(rec["claim"])}


def errata(records: list[dict], cat: Catalogue) -> list[dict]:
    by_claim = {r["claim"]: r for r in records}
    out = []
    for r in records:
        if r.get("level", "formula") != "formula" or r.get("qualifier") not in ERRATA_KINDS:
            continue
        corr = by_claim.get(f"{r['claim']}/corrected", {})
        e = _base(r, cat)
        text = corr.get("printed", "")
        m = re.match(r"^\[project's correction of (\w+)\] (.*)$", text, re.S)
        fid = m.group(1) if m else None
        e.update(corrected=cite(m.group(2) if m else text),
                 corrected_formula=fid, corrected_claim=corr.get("claim"),
                 corrected_verdict=corr.get("verdict"), residual_corrected=corr.get("residual"),
                 corrected_exact=corr.get("exact"), inherits=r.get("inherits"),
                 anchor=f"e-{r['claim']}", **corrected_display(fid, cat))
        sec = e.get("corrected_section") or section_number(e["number"], e["where"])
        e.update(section=f"section {sec}" if sec else e["section"],
                 section_title=SECTIONS.get(sec or ""),
                 place=short_place(e["number"], e["where"]))
        out.append(e)
    # the index reads in the order of the paper: by section, then by display
    return sorted(out, key=lambda e: (e["section"] or "~", _order(e["corrected_display"]),
                                      e["claim"]))


def _section(e: dict) -> None:
    sec = section_number(e["number"], e["where"])
    e.update(section=f"section {sec}" if sec else e["section"],
             section_title=SECTIONS.get(sec or ""))


def _order(display: str | None) -> tuple:
    m = re.search(r"\((\d+)\.(\d+)\)", display or "")
    return (int(m[1]), int(m[2])) if m else (99, 0)


def conventions(records: list[dict], cat: Catalogue) -> list[dict]:
    out = []
    for r in records:
        if r.get("qualifier") == "convention":
            e = _base(r, cat)
            e.update(convention=cite(r.get("convention")), residual_printed=(
                r.get("evidence") or {}).get("residual read with the project's convention"),
                residual_under_convention=r.get("residual"), anchor=f"c-{r['claim']}",
                place=short_place(e["number"], e["where"]))
            _section(e)
            out.append(e)
    return out


def is_inconclusive(r: dict) -> bool:
    """A negative check that ran and could not decide: what it found (no chaotic layer, no
    contraction) is what an integrable or measure-preserving system shows, so it leans
    against the printed negative statement without refuting it."""
    return (r.get("level", "formula") == "formula" and r.get("check") in NEGATIVE_CHECKS
            and (r.get("message") or "").startswith(INCONCLUSIVE))


def findings(records: list[dict], cat: Catalogue) -> list[dict]:
    out = []
    for r in records:
        refuted = r.get("level", "formula") == "formula" and r.get("qualifier") in FINDING_KINDS
        if not (refuted or is_inconclusive(r)):
            continue
        e = _base(r, cat)
        claim = cat.claim(r["claim"])
        title = FINDING_TITLES.get(r["claim"]) or (
            f"{cat.case(r['case']).title}: {claim.plain}")
        # what was found in words: a refutation's finding, else the mark's plain note
        # (solvers/verify/plain_notes.py); the checking code's message stays in `message`
        e.update(title=cite(title), finding=cite(r.get("finding") or r.get("mark_note")
                                                 or r.get("message", "")),
                 evidence=cite(r.get("evidence") or {}), anchor=f"f-{r['claim']}",
                 place=short_place(e["number"], e["where"]),
                 kind=r.get("qualifier") if refuted else INCONCLUSIVE,
                 leans="against the paper")
        _section(e)
        out.append(e)
    return out


def figure_findings(figures: dict, cat: Catalogue) -> list[dict]:
    """The paper's figures whose caption the recomputed figure does not confirm
    (app/static/data/paper_figures.json, written by bench/paper_figures.py: each figure's
    `finding`), as findings; a confirmed caption is not a finding."""
    out = []
    for key, fig in figures.items():
        f = fig.get("finding") or {}
        if not f or f.get("status") == "confirmed":
            continue
        label = key.replace("ris-", "ris-*")          # the seed's label of the figure
        number = printed_number(label)
        out.append({
            "claim": f"figure/{key}", "case": fig["case"], "kind": f["status"],
            "case_title": cat.case(fig["case"]).title, "claim_name": f"the caption of {number}",
            "label": label, "number": number, "where": f"the caption of {number}",
            "section": "section 2", "section_title": SECTIONS["2"],
            "printed": f["statement"], "plain": cite(f["statement"]),
            "residual_printed": None, "message": cite(f["found"]), "exact": None,
            "reproduce": FIGURES_REPRODUCE, "anchor": f"f-figure-{key}",
            "place": number, "leans": f.get("leans"),
            "title": cite(f"{number}: {fig['title']}"), "finding": cite(f["found"]),
            "evidence": f.get("numbers") or {}, "href": f"/poincare#fig-{key}"})
    return out
