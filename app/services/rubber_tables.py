"""The rubber tables (catalogue/rubber_plane.yaml, rubber_sphere.yaml: beyond the 2002
paper) as the home page shows them: laid out like views.table (columns, rows, a grid of
cells), each cell with its mark from the one vocabulary, the level of the check behind it,
its claims with source, place and access, and the anchor its mark links to; and the counts
by mark. The marks are the catalogue's: no verdict store is consulted."""

from __future__ import annotations

from app.services.anchors import claim_anchor
from catalogue.load import load_rubber
from catalogue.schema import SourcedClaim
from solvers.models.cases import registry
from solvers.verify import marks as vocab

ACCESS_WORDS = {"text-read": "text read", "partial": "part of the text read",
                "abstract-only": "abstract only", "not-reached": "not reached",
                "derived-here": "derived here"}
LEVEL_WORDS = {"exact": "exact (sympy)", "pointwise": "to round-off at random points",
               "numerical": "numerical evidence"}


def rubber_cell_anchor(case_id: str, row: str) -> str:
    """The anchor of a rubber cell's claims on the home page (the claim_anchor rule)."""
    return claim_anchor(f"{case_id}/cell/{row}")


def rubber_claim(c: SourcedClaim, sources: dict) -> dict:
    src = sources.get(c.source)
    return {"source": c.source, "short": src.short if src else "derived here",
            "cite": src.cite if src else None, "place": c.place, "access": c.access.value,
            "access_words": ACCESS_WORDS[c.access.value], "says": c.says,
            "agreement": c.agreement.value, "check": c.check,
            "level": c.level.value if c.level else None}


def rubber_table(table_id: str) -> dict:
    """A rubber table laid out like views.table: columns, rows and a grid of cells, each cell
    with its mark (the vocabulary's), the level of the check behind it, its statement (plain
    text, and the LaTeX the page typesets), its
    claims with source, place and access, and its anchor; the counts by mark."""
    rt = load_rubber()
    t = rt.plane if table_id == "rubber-plane" else rt.sphere
    columns = [{"id": c.id, "column": i + 1, "title": c.title, "model": c.model,
                "href": f"/case/{c.model}" if c.model in registry() else None}
               for i, c in enumerate(t.cases)]
    grid = []
    for row in t.rows:
        cells = []
        for case in t.cases:
            mc = case.cells[row.key]
            cells.append({
                "row": row.key.value, "case": case.id, "plain": mc.statement,
                "tex": mc.statement_tex,
                "mark": mc.mark, "level": mc.level.value if mc.level else None,
                "level_words": LEVEL_WORDS[mc.level.value] if mc.level else None,
                "anchor": rubber_cell_anchor(case.id, row.key.value),
                "claims": [rubber_claim(c, rt.sources) for c in mc.claims]})
        grid.append({"key": row.key.value, "cells": cells})
    counts = vocab.counts(c["mark"] for row in grid for c in row["cells"])
    n = sum(counts.values())
    return {"id": t.id, "title": t.title, "note": t.note,
            "rows": [{"key": r.key.value, "plain": r.plain} for r in t.rows],
            "columns": columns, "grid": grid, "mark_counts": counts,
            "summary": f"Of its {n} cells: {vocab.sentence(counts, 'cell', 'cells')}."}


def rubber_summary(tables: list[dict]) -> str:
    """The counts by mark over the cells of both rubber tables, in words."""
    total: dict[str, int] = {}
    for t in tables:
        for mark, n in t["mark_counts"].items():
            total[mark] = total.get(mark, 0) + n
    counts = {m: total[m] for m in vocab.IDS if m in total}
    n = sum(counts.values())
    return (f"Of the {n} cells of the rubber tables (one per body and row): "
            f"{vocab.sentence(counts, 'cell', 'cells')}.")
