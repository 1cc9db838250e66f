"""Counts of the exact layer over `rolling verify` records: proved / certified / neither,
and why each verified formula record that is neither stays so.

    python -m solvers.verify.exact.report records.json    # from `rolling verify --json`
"""

import json
import sys
from collections import Counter

from solvers.verify.exact.certifiers import NUMERIC
from solvers.verify.exact.certify import K_POINTS
from solvers.verify.exact.points import BITS


def kind(rec) -> str:
    """proof | certificate | zeros (no degree known) | witness | none."""
    ex = rec.get("exact")
    if ex is None:
        return "none"
    if ex.get("kind"):
        return ex["kind"]
    return "certificate" if ex.get("holds") and ex.get("bounded", True) else "zeros"


def _verified(records):
    return [r for r in records if r["verdict"] == "verified"
            and r.get("level", "formula") == "formula"]


def exact_counts(records) -> dict:
    ver = _verified(records)
    own = [r for r in ver if not (r.get("exact") or {}).get("negative")]
    kinds = Counter(kind(r) for r in own)
    fails = [r for r in records if r["verdict"] == "fails"]
    return {"verified": len(ver), "proved": kinds["proof"], "certified": kinds["certificate"],
            "neither": len(ver) - kinds["proof"] - kinds["certificate"],
            "witnessed": sum(r.get("exact") is not None for r in fails), "fails": len(fails),
            "bits": BITS, "k": K_POINTS}


def neither_reasons(records) -> dict[str, str]:
    """Why each verified formula record is neither proved nor certified."""
    out = {}
    for r in _verified(records):
        k = kind(r)
        if k in ("proof", "certificate") and not r["exact"].get("negative"):
            continue
        ex = r.get("exact")
        if ex is None:
            why = NUMERIC.get(r["check"]) or "not exactly evaluable at rational points " \
                "(solvers.verify.exact.certifiers.why_not gives the error)"
        elif ex.get("negative"):
            why = "the exact object certifies a negative statement, not this record's formula"
        else:
            why = ex["bound"]
        out[r["claim"]] = why
    return out


def main(path):
    records = json.loads(open(path).read())
    c = exact_counts(records)
    print(json.dumps(c))
    for cid, why in sorted(neither_reasons(records).items()):
        print(f"{cid}: {why}")
    unproved = Counter((r.get("exact") or {}).get("no_proof") for r in _verified(records)
                       if kind(r) == "certificate")
    for why, n in unproved.most_common():
        print(f"certified, not proved ({n}): {why}")


if __name__ == "__main__":
    main(sys.argv[1])
