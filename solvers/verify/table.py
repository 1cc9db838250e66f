"""Verdicts per table cell: the marks shown in `rolling verify` and in the explorer.

A cell's mark summarises the verdicts of the claims it links to:
  fails      if any of its paper claims fails as printed (a correction may verify),
  verified   if all its checkable claims are verified (claims with nothing to compute:
             open problems, statements without a printed formula, are neutral),
  evidence   if its claims are negative and evidence was gathered,
  unchecked  otherwise (nothing to compute, or not implemented).
"""

MARKS = {"verified": "✓", "fails": "✗", "evidence": "~", "unchecked": "?", "": ""}


NEUTRAL_CHECKS = frozenset({"open_problem", "formula_not_printed", "not_checkable"})


def cell_verdict(cell_claims: list[str], by_claim: dict[str, dict]) -> str:
    recs = [by_claim[c] for c in cell_claims if c in by_claim]
    if not recs:
        return ""
    verdicts = [r["verdict"] for r in recs]
    if "fails" in verdicts:
        return "fails"
    if any(r["verdict"] == "unchecked" and r["check"] not in NEUTRAL_CHECKS for r in recs):
        return "unchecked"
    checked = [v for v in verdicts if v != "unchecked"]
    if not checked:
        return "unchecked"
    if all(v == "verified" for v in checked):
        return "verified"
    return "evidence" if all(v in ("evidence", "verified") for v in checked) else "unchecked"


def table_marks(table, records: list[dict]) -> dict[str, dict[str, str]]:
    """{case id: {row key: verdict}} for one catalogue table."""
    by_claim = {r["claim"]: r for r in records}
    return {case.id: {row.value: cell_verdict(cell.claims, by_claim)
                      for row, cell in case.cells.items()}
            for case in table.cases}
