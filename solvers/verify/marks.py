"""The vocabulary of marks (marks.yaml): loaded once, validated, and the summary sentences
("12 cells hold as printed, 3 hold after correction, ...") every view builds from it.

Which record gets which mark is decided in solvers/verify/levels.py; this module only
holds what the marks are and how they are said."""

from __future__ import annotations

from functools import cache
from pathlib import Path

import yaml
from pydantic import BaseModel, ConfigDict


class Mark(BaseModel):
    model_config = ConfigDict(extra="forbid", frozen=True)

    id: str
    shape: str
    word: str
    name: str
    counted: str
    counted_one: str
    definition: str


class Verdict(BaseModel):
    """A coarse verdict (the API's `verdict` field), its sign and what it means."""

    model_config = ConfigDict(extra="forbid", frozen=True)

    id: str
    shape: str
    meaning: str


@cache
def _raw() -> dict:
    return yaml.safe_load(Path(__file__).with_name("marks.yaml").read_text(encoding="utf-8"))


@cache
def vocabulary() -> tuple[Mark, ...]:
    marks = tuple(Mark(**m) for m in _raw()["marks"])
    for attr in ("id", "shape", "word", "name"):
        values = [getattr(m, attr) for m in marks]
        if len(set(values)) != len(values):
            raise ValueError(f"marks.yaml: two marks share a {attr}")
    return marks


@cache
def verdicts() -> tuple[Verdict, ...]:
    """The coarse verdicts, in the order /how-we-check lists them."""
    out = tuple(Verdict(**v) for v in _raw()["verdicts"])
    if len({v.id for v in out}) != len(out):
        raise ValueError("marks.yaml: two verdicts share an id")
    return out


def by_id() -> dict[str, Mark]:
    return {m.id: m for m in vocabulary()}


# every mark a record can carry; `pending` is what a view shows while a check runs
IDS = tuple(m.id for m in vocabulary())
VERDICT_MARKS = tuple(i for i in IDS if i != "pending")


def counts(marks) -> dict[str, int]:
    """{mark id: how many}, in the vocabulary's order, marks that occur only."""
    marks = list(marks)
    return {i: marks.count(i) for i in IDS if i in marks}


def sentence(n_by_mark: dict[str, int], unit: str, units: str) -> str:
    """'12 cells hold as printed, 3 hold after correction and 1 is open in the paper'
    (unit / units: the noun, singular and plural). Empty counts: ''."""
    parts = []
    for i in IDS:
        n = n_by_mark.get(i, 0)
        if not n:
            continue
        m = by_id()[i]
        verb = m.counted_one if n == 1 else m.counted
        noun = (unit if n == 1 else units) if not parts else ""
        parts.append(f"{n} {noun + ' ' if noun else ''}{verb}")
    if len(parts) > 1:
        return ", ".join(parts[:-1]) + " and " + parts[-1]
    return parts[0] if parts else ""
