"""A claim's anchor on its case page: the one rule, which app/static/js/anchor.js repeats for
the pages the browser draws (tests/test_claim_anchor.py checks that both agree)."""

import re


def claim_anchor(claim_id: str) -> str:
    """`claim-` and the claim id with every run of characters other than letters, digits,
    `_` and `-` replaced by one `_` (an id such as plane/round-disk/eq2.4 is not a valid
    fragment as it stands)."""
    return "claim-" + re.sub(r"[^A-Za-z0-9_-]+", "_", claim_id)
