"""What is known since the paper: catalogue/since_2002.yaml, validated and cross-checked.

    from catalogue.since_2002 import load_since_2002, notes_for
    data = load_since_2002()          # cached: parsed, validated and resolved once
    notes_for("plane/ellipsoid")      # the notes on that case's claims and cells

Every note's record is a claim id of the catalogue or a cell record id `<case>/cell/<row>`
of a cell that lists claims, and every reference it cites is a complete entry of
references.yaml or of the file's own `literature` (schema: Since2002, SinceNote).
"""

from __future__ import annotations

from functools import cache

import yaml

from catalogue.load import DATA_DIR, UniqueKeyLoader, load_catalogue
from catalogue.numbering import cite
from catalogue.schema import Reference, Since2002, SinceNote

FILE = DATA_DIR / "since_2002.yaml"


def _records(cat) -> set[str]:
    """The record ids a note may name: every claim, and every cell that lists claims."""
    ids = {cl.id for cl in cat.claims()}
    for case in cat.cases():
        ids |= {f"{case.id}/cell/{row.value}" for row, cell in case.cells.items()
                if cell.claims}
    return ids


def build(raw: dict) -> Since2002:
    data = Since2002.model_validate(raw)
    cat = load_catalogue()
    refs = {r.id: r for r in cat.references}
    clash = sorted(set(refs) & {r.id for r in data.literature})
    if clash:
        raise ValueError(f"since_2002.yaml: literature ids already in references.yaml: {clash}")
    refs.update({r.id: r for r in data.literature})
    records = _records(cat)
    seen: set[str] = set()
    for n in data.notes:
        if n.record not in records:
            raise ValueError(f"since-2002 note: unknown claim or cell record {n.record!r}")
        if n.record in seen:
            raise ValueError(f"since-2002 note: two notes for {n.record!r}")
        seen.add(n.record)
        for rid in n.references:
            if rid not in refs:
                raise ValueError(f"since-2002 note {n.record}: unknown reference {rid!r}")
            if refs[rid].status != "complete":
                raise ValueError(f"since-2002 note {n.record}: reference {rid!r} is "
                                 "unresolved; a note cites complete entries only")
    return data


@cache
def load_since_2002() -> Since2002:
    with FILE.open(encoding="utf-8") as f:
        return build(yaml.load(f, Loader=UniqueKeyLoader))


def reference(ref_id: str) -> Reference:
    """A note's reference: an entry of references.yaml or of the later literature."""
    for r in (*load_since_2002().literature, *load_catalogue().references):
        if r.id == ref_id:
            return r
    raise KeyError(ref_id)


def notes_for(case_id: str) -> list[SinceNote]:
    """The notes on one case's claims and cells, in the file's order."""
    return [n for n in load_since_2002().notes if n.record.startswith(case_id + "/")]


def note_json(n: SinceNote) -> dict:
    """A note as the case JSON and the pages show it: the paper's equations by their printed
    numbers (catalogue.numbering.cite), its references resolved."""
    return {**n.model_dump(mode="json"), "note": cite(n.note),
            "project": cite(n.project) if n.project else None,
            "references": [{"id": rid, "citation": short_citation(reference(rid)),
                            "href": f"/bibliography#ref-{rid}"} for rid in n.references]}


def short_citation(r: Reference) -> str:
    """'García-Naranjo, Marrero (2013), <title>, arXiv preprint 1306.4237': the form a note
    shows beside its text (the full entry is on /bibliography)."""
    last = ", ".join(a.split()[-1] for a in r.authors)
    year = r.year or (r.years[0] if r.years else "")
    where = " ".join(x for x in (r.journal, r.volume, r.number and f"({r.number})"
                                 if r.volume else r.number) if x)
    pages = f", pp. {r.pages.replace('-', '–')}" if r.pages else ""
    doi = f", doi:{r.doi}" if r.doi else ""
    return f"{last} ({year}), {r.title}, {where}{pages}{doi}"
