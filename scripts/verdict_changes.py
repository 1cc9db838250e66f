"""Compare two `rolling verify --json` outputs: the records whose verdict changed, the failing
formula records with their kind, the table cells whose verdict differs from the mark their
claims gave, and the new record ids (docs/verdict-levels.md).

    PYTHONPATH=$PWD python scripts/verdict_changes.py BEFORE.json AFTER.json > changes.md
"""

import json
import sys
from collections import Counter

from catalogue.load import load_catalogue
from solvers.verify.table import cell_verdict

VERDICTS = ("verified", "fails", "evidence", "unchecked")


def main(before: str, after: str) -> str:
    v0, v2 = json.load(open(before)), json.load(open(after))
    b0, b2 = {r["claim"]: r for r in v0}, {r["claim"]: r for r in v2}
    missing = [k for k in b0 if k not in b2]
    assert not missing, f"record ids lost: {missing}"
    c2 = Counter((r.get("level", "formula"), r["verdict"]) for r in v2)

    def cnt(level):
        return ", ".join(f"{v}: {c2[(level, v)]}" for v in VERDICTS)
    nf = sum(1 for r in v2 if r.get("level", "formula") == "formula")
    out = [f"After: {len(v2)} records = {nf} formula records ({cnt('formula')}) + "
           f"{len(v2) - nf} cell records ({cnt('cell')}).\n",
           "### Formula records whose verdict changed\n",
           "| record | old | new | reason |", "|---|---|---|---|"]
    for k, r in b0.items():
        n = b2[k]
        if r["verdict"] != n["verdict"]:
            ours = (n.get("evidence") or {}).get("residual read with the project's convention")
            reason = (f"holds under the convention: {n.get('convention')} (residual "
                      f"{n['residual']:.1e}; with the project's convention {ours:.2g})"
                      if n.get("qualifier") == "convention" else n["message"])
            out.append(f"| `{k}` | {r['verdict']} | {n['verdict']} ({n.get('qualifier')}) "
                       f"| {reason} |")
    out += ["\n### Failing formula records: verdict unchanged (`fails`), kind now recorded\n",
            "| record | label | kind | links / note |", "|---|---|---|---|"]
    for k in b0:
        n = b2[k]
        if n["verdict"] != "fails":
            continue
        q = n.get("qualifier")
        corr = b2.get(k + "/corrected")
        note = {"refuted-conjecture": f"found: {n.get('finding')}",
                "refuted": "no correction found: a finding (see /errata)"}.get(q, "")
        if n.get("inherits"):
            note = f"inherits `{n['inherits']}`; "
        if corr is not None and q in ("misprint", "inherited"):
            note += f"correction `{k}/corrected` {corr['verdict']} ({corr['residual']:.1e})"
        out.append(f"| `{k}` | {n.get('label') or ''} | {q} | {note} |")
    out += ["\n### Table cells: old mark vs new cell record\n",
            "| cell record (new id) | old mark | new verdict | why |", "|---|---|---|---|"]
    same = 0
    for t in load_catalogue().tables():
        for case in t.cases:
            for row, cell in case.cells.items():
                cid = f"{case.id}/cell/{row.value}"
                if cid not in b2:
                    continue
                old, new = cell_verdict(list(cell.claims), b0), b2[cid]
                if old == new["verdict"]:
                    same += 1
                    continue
                rests = ", ".join(f"`{x}`" for x in new["rests_on"])
                out.append(f"| `{cid}` | {old} | {new['verdict']} | {new['message']}; "
                           f"rests on {rests} |")
    out.append(f"\nThe other {same} cell records have the verdict the old mark had.\n")
    new_ids = [k for k in b2 if k not in b0]
    cells = [k for k in new_ids if b2[k].get("level") == "cell"]
    tests = [k for k in new_ids if k not in cells]
    out.append(f"### New record ids\n\n{len(new_ids)} new records: {len(tests)} formula-free "
               f"tests and {len(cells)} cell records.\n")
    out += [f"- `{k}`: {b2[k]['verdict']} — {b2[k]['message']}" for k in tests]
    out += ["\nCell records (`<case>/cell/<row>`):\n", ", ".join(f"`{k}`" for k in cells)]
    return "\n".join(out) + "\n"


if __name__ == "__main__":
    sys.stdout.write(main(*sys.argv[1:3]))
