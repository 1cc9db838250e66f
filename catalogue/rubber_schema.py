"""Schema of the rubber tables (catalogue/rubber_plane.yaml, rubber_sphere.yaml) and of their
sources (catalogue/rubber_sources.yaml).

The rubber tables go beyond the 2002 paper, so they have no printed cells: each cell is a
statement with a mark and its claims, and every claim names its source (a key of
rubber_sources.yaml, or "derived-here"), the place in it and the access level, so that
nothing read only in an abstract passes for a result read in the text. Loaded once by
`load_rubber()`; pydantic models with extra="forbid" reject unknown keys.
"""

from __future__ import annotations

from enum import StrEnum
from functools import lru_cache
from pathlib import Path

import yaml
from pydantic import BaseModel, ConfigDict, model_validator

HERE = Path(__file__).resolve().parent
DERIVED = "derived-here"


class Strict(BaseModel):
    model_config = ConfigDict(extra="forbid", frozen=True)


class Access(StrEnum):
    full_text = "full-text"
    partial = "partial"
    abstract_only = "abstract-only"
    not_reached = "not-reached"
    derived = "derived-here"


class Mark(StrEnum):
    proved_exact = "proved-exact"           # symbolic identity, sympy (rubber_exact.py)
    checked_pointwise = "checked-pointwise"  # complex step at random points, to round-off
    numerical_evidence = "numerical-evidence"  # a run or a numerical search, not a proof
    literature_unchecked = "literature-unchecked"  # stated in a source, not checked here
    open = "open"                           # nothing found: neither read nor derived


class Agreement(StrEnum):
    confirmed = "confirmed"         # our check shows what the source states
    consistent = "consistent"       # agrees under a stated reading or convention
    contradicted = "contradicted"   # our check disagrees, with the evidence
    unchecked = "unchecked"
    not_applicable = "n/a"          # a derived-here claim


class RowKey(StrEnum):
    measure = "measure"
    integrals = "integrals"
    gyrostat = "gyrostat"
    brun = "brun"
    hamiltonian_form = "hamiltonian_form"
    integrability = "integrability"


class Claim(Strict):
    source: str
    place: str
    access: Access
    says: str
    agreement: Agreement
    check: str | None = None        # the test (path::name) or command that checks it

    @model_validator(mode="after")
    def _derived_is_derived(self):
        if (self.source == DERIVED) != (self.access == Access.derived):
            raise ValueError(f"claim from {self.source!r} has access {self.access!r}: "
                             "derived-here and only it has access derived-here")
        if self.source == DERIVED and not self.check:
            raise ValueError("a derived-here claim names the check that backs it")
        if self.agreement in (Agreement.confirmed, Agreement.contradicted) and not self.check:
            raise ValueError("confirming or contradicting a source needs a named check")
        return self


class Cell(Strict):
    mark: Mark
    statement: str
    claims: list[Claim]

    @model_validator(mode="after")
    def _mark_has_backing(self):
        derived = [c for c in self.claims if c.source == DERIVED]
        if self.mark in (Mark.proved_exact, Mark.checked_pointwise, Mark.numerical_evidence):
            if not derived:
                raise ValueError(f"mark {self.mark} needs a derived-here claim with its check")
        if self.mark == Mark.literature_unchecked and (derived or not self.claims):
            raise ValueError("literature-unchecked cells carry source claims only")
        return self


class RubberCase(Strict):
    id: str
    model: str          # key of solvers.models.rubber_bodies.CASES
    title: str
    cells: dict[RowKey, Cell]


class RubberTable(Strict):
    id: str
    title: str
    note: str
    cases: list[RubberCase]


class Source(Strict):
    cite: str
    access: Access
    read: str
    claims: list[dict]
    cited_by: list[dict] | None = None


class RubberSources(Strict):
    sources: dict[str, Source]


def _read(name):
    return yaml.safe_load((HERE / name).read_text(encoding="utf-8"))


@lru_cache(maxsize=1)
def load_rubber() -> tuple[RubberSources, RubberTable, RubberTable]:
    """(sources, plane table, sphere table), validated; every claim's source must resolve."""
    sources = RubberSources(**_read("rubber_sources.yaml"))
    tables = tuple(RubberTable(**_read(f)) for f in ("rubber_plane.yaml", "rubber_sphere.yaml"))
    for t in tables:
        for case in t.cases:
            for row, cell in case.cells.items():
                for c in cell.claims:
                    if c.source != DERIVED and c.source not in sources.sources:
                        raise ValueError(f"{case.id} {row}: unknown source {c.source!r}")
                    if c.source != DERIVED:
                        known = sources.sources[c.source].access
                        if c.access == Access.full_text and known != Access.full_text:
                            raise ValueError(f"{case.id} {row}: {c.source} was not read in "
                                             "full, the claim cannot say full-text")
    return (sources, *tables)
