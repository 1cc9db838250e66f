"""The two tables of docs/verdict-levels.md from one `rolling verify --json` output: the table
cells that hold although a formula printed under them fails, and every formula record that
fails as printed, with its kind and its correction.

    rolling verify --json > records.json
    PYTHONPATH=$PWD python scripts/verdict_tables.py records.json

Text a reader sees cites the printed equation numbers (catalogue.numbering).
"""

import json
import sys

from catalogue.numbering import cite, printed


def main(path: str) -> str:
    recs = json.load(open(path))
    by = {r["claim"]: r for r in recs}
    out = ["| cell record | failing formula records under it | verdict | note |",
           "|---|---|---|---|"]
    for r in recs:
        if r.get("level") != "cell":
            continue
        bad = [x for x in r.get("rests_on", []) if by.get(x, {}).get("verdict") == "fails"]
        if bad:
            under = ", ".join(f"`{x}`" for x in bad)
            out.append(f"| `{r['claim']}` | {under} | {r['verdict']} | {cite(r['message'])} |")
    out += ["", "| record | printed number | kind | correction / note |", "|---|---|---|---|"]
    for r in recs:
        if r.get("level", "formula") != "formula" or r["verdict"] != "fails":
            continue
        q = r.get("qualifier")
        note = {"refuted-conjecture": f"found: {r.get('finding')}",
                "refuted": "no correction found: a finding (see /errata)"}.get(q, "")
        if r.get("inherits"):
            note = f"inherits `{r['inherits']}`; "
        corr = by.get(r["claim"] + "/corrected")
        if corr is not None and q in ("misprint", "inherited"):
            res = corr.get("residual")
            note += (f"correction `{r['claim']}/corrected` {corr['verdict']}"
                     + (f" ({res:.1e})" if res is not None else ""))
        number = printed(r.get("label")) or "unnumbered"
        out.append(f"| `{r['claim']}` | {number} | {q} | {cite(note)} |")
    return "\n".join(out) + "\n"


if __name__ == "__main__":
    sys.stdout.write(main(sys.argv[1]))
