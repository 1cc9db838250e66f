"""Errata and findings (issue 10, items 5 and 6), from the records of `verify`.

* errata: every printed formula that fails where the project's correction holds -- the
  misprints (qualifier misprint) and the formulas that fail only through one of them
  (inherited) -- with the printed and corrected forms, where they are, both residuals, the
  exact witness when the record carries one, and the command that reproduces it;
* conventions: printed forms that hold under another convention than the project's;
* findings: what the paper does not have -- a hedged claim answered (refuted-conjecture)
  and a printed statement refuted with no correction (refuted), with their evidence.
"""

from __future__ import annotations

import re

from catalogue.schema import Catalogue

ERRATA_KINDS = ("misprint", "inherited")
FINDING_KINDS = ("refuted-conjecture", "refuted")
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
    from catalogue.numbering import printed

    return printed(label)


def cite(text):
    """Reader's text: every internal label replaced by its printed number (strings inside
    lists and dicts too); labels stay as data in the `label` field only."""
    from catalogue.numbering import cite as _cite

    if isinstance(text, str):
        return _cite(text)
    if isinstance(text, dict):
        return {cite(k): cite(v) for k, v in text.items()}
    if isinstance(text, list):
        return [cite(v) for v in text]
    return text


def cite_latex(tex: str | None) -> str | None:
    from catalogue.numbering import cite_latex as _cite_latex

    return _cite_latex(tex)


def reproduce(claim_id: str) -> str:
    return f"rolling verify --claim {claim_id} --json"


def section_of(label: str | None) -> str | None:
    """The paper's section from an equation label (eq2.15, eq2b-*1, eq3.10 -> 2, 2, 3)."""
    m = re.match(r"^eq(\d)", label or "")
    return f"section {m.group(1)}" if m else None


def _base(rec: dict, cat: Catalogue) -> dict:
    claim = cat.claim(rec["claim"])
    return {"claim": rec["claim"], "case": rec["case"], "kind": rec.get("qualifier"),
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
        e.update(corrected=cite(m.group(2) if m else text),
                 corrected_formula=m.group(1) if m else None, corrected_claim=corr.get("claim"),
                 corrected_verdict=corr.get("verdict"), residual_corrected=corr.get("residual"),
                 corrected_exact=corr.get("exact"), inherits=r.get("inherits"))
        out.append(e)
    return out


def conventions(records: list[dict], cat: Catalogue) -> list[dict]:
    out = []
    for r in records:
        if r.get("qualifier") == "convention":
            e = _base(r, cat)
            e.update(convention=cite(r.get("convention")), residual_printed=(
                r.get("evidence") or {}).get("residual read with the project's convention"),
                residual_under_convention=r.get("residual"))
            out.append(e)
    return out


def findings(records: list[dict], cat: Catalogue) -> list[dict]:
    out = []
    for r in records:
        if r.get("level", "formula") == "formula" and r.get("qualifier") in FINDING_KINDS:
            e = _base(r, cat)
            e.update(title=cite(FINDING_TITLES.get(r["claim"], cat.claim(r["claim"]).plain)),
                     finding=cite(r.get("finding") or r.get("message", "")),
                     evidence=cite(r.get("evidence") or {}))
            out.append(e)
    return out
