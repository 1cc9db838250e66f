"""Write docs/misprint-audit.md from two `rolling verify --json` outputs:
every formula record whose verdict was `misprint` before the audit, read in the notation of
the section where it stands, with its verdict before and after.

    PYTHONPATH=$PWD python scripts/misprint_audit.py BEFORE.json AFTER.json > docs/misprint-audit.md

Text a reader sees cites the printed equation numbers (catalogue.numbering.cite).
"""

import json
import sys
from pathlib import Path

import yaml

from catalogue.numbering import cite, printed

READINGS = {k: (v["reading"], v["evidence"]) for k, v in yaml.safe_load(
    (Path(__file__).with_name("misprint-readings.yaml")).read_text()).items()}


HEAD = """# Misprint audit: each misprint read in its section's notation

Before the project calls a printed formula a misprint, it reads the formula in the notation
of the section where it stands: section 3 writes the second form of ρ0 with r3 = γ3 f2 where
section 2 has r3 = f2; the special-case paragraphs of section 2 name K1 = ω3/ρ where the
general reduction {eq24} names it K2; and the bracket's orientation, the direction of γ, the
sign of k and the section's own parametrisation are all tried. The table lists every formula
record classed `misprint` before these readings were tried, the reading, and what it gave.

Where a reading holds, the claim's `holds_under` in catalogue/*.yaml carries it: the printed
form is then reported `verified` with the qualifier `convention`, and only where the check of
that reading passes (levels.annotate); the residual read with the project's conventions stays
in the record's evidence. The readings themselves are in `scripts/misprint-readings.yaml`.

Regenerate this page with
`PYTHONPATH=$PWD python scripts/misprint_audit.py BEFORE.json AFTER.json > docs/misprint-audit.md`,
where BEFORE.json is `rolling verify --json` without the readings' `holds_under` entries and
AFTER.json with them.
"""


def main(before: str, after: str) -> str:
    b0 = {r["claim"]: r for r in json.load(open(before))}
    b2 = {r["claim"]: r for r in json.load(open(after))}
    rows = [k for k, r in b0.items() if r.get("qualifier") == "misprint"]
    missing = [k for k in rows if k not in READINGS]
    assert not missing, f"no reading written for {missing}"
    changed = [k for k in rows if b2[k].get("qualifier") != "misprint"]
    out = [HEAD.format(eq24=cite("eq2.4")),
           f"{len(rows)} records were classed misprint; {len(changed)} hold in their "
           f"section's notation, {len(rows) - len(changed)} stand as misprints.\n",
           "| record | printed number | reading in the section's notation | as a misprint "
           "| read so | evidence |", "|---|---|---|---|---|---|"]
    for k in rows:
        r0, r2 = b0[k], b2[k]
        num = printed(r0.get("label")) or "unnumbered"
        reading, evidence = READINGS[k]
        after = f"{r2['verdict']} ({r2.get('qualifier')})"
        res = r2.get("residual")
        if r2.get("qualifier") == "convention" and res is not None:
            evidence += f"; residual now {res:.1e}"
        out.append(f"| `{k}` | {num} | {cite(reading)} | {r0['verdict']} (misprint) | {after} "
                   f"| {cite(evidence)} |")
    return "\n".join(out) + "\n"


if __name__ == "__main__":
    sys.stdout.write(main(*sys.argv[1:3]))
