"""Verdicts per table cell: the marks shown in `rolling verify` and in the explorer.

A cell's mark is the verdict of its *cell record* (solvers.verify.levels): the property the
cell states, judged by the best evidence (printed formula, else the project's correction,
else a formula-free test). A misprinted formula under a true property leaves the cell
verified, with a note; the ✗ stays on the formula record.
"""

from solvers.verify.levels import NEUTRAL_CHECKS, aggregate, cell_id  # noqa: F401  (re-exported)


def table_marks(table, records: list[dict]) -> dict[str, dict[str, str]]:
    """{case id: {row key: verdict}} for one catalogue table, from the cell records."""
    by_claim = {r["claim"]: r for r in records}
    return {case.id: {row.value: by_claim.get(cell_id(case.id, row.value), {}).get(
        "verdict", "") for row in case.cells} for case in table.cases}


def cell_notes(table, records: list[dict]) -> dict[str, dict[str, list[str]]]:
    """{case id: {row key: notes}}: "holds; printed formula corrected" and the like."""
    by_claim = {r["claim"]: r for r in records}
    return {case.id: {row.value: list(by_claim.get(cell_id(case.id, row.value), {}).get(
        "notes") or []) for row in case.cells} for case in table.cases}


def cell_verdict(cell_claims: list[str], by_claim: dict[str, dict]) -> str:
    """The aggregation rule of a cell over verdicts as given (levels.aggregate): fails if
    any fails, verified if all checkable ones are (open problems and statements without a
    formula are neutral), evidence if all are evidence or verified, else unchecked."""

    recs = [by_claim[c] for c in cell_claims if c in by_claim]
    return aggregate([(r["verdict"], r) for r in recs]) if recs else ""
