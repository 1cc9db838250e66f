"""Exact certificates and symbolic proofs of the verification layer.

`certifiers.exact_for(catalogue, case, claim, corrected=False)` returns the `exact` field of a
record: None where no exact test applies, else {"holds", "kind", "points", "method",
"bound", "witness"}, kind one of "proof" (symbolic, certain: proofs.py), "certificate"
(k points, Schwartz-Zippel bound: certify.py), "zeros" (exact zeros, degree unknown: no
probability stated), "witness" (a rational point where the residual is nonzero).
"""
