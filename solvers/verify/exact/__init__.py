"""Exact certificates of the verification layer (issue 10, item 4).

`exact_for(catalogue, case, claim, corrected=False)` returns the `exact` field of a record:
None where no exact test applies, else {"holds", "points", "method", "bound", "witness"}.
"""

from solvers.verify.exact.registry import exact_for, why_not

__all__ = ["exact_for", "why_not"]
