"""The glossary (catalogue/glossary.yaml): every parameter and state variable of the cases,
with its meaning, units, valid range and where in the paper it appears, and every integral
a run reports under its output name (the JSON's, CSV's and Arrow's)."""

from __future__ import annotations

from functools import cache
from pathlib import Path
from typing import Literal

import yaml
from pydantic import BaseModel, ConfigDict, model_validator

from catalogue.schema import LABEL_RE

PATH = Path(__file__).with_name("glossary.yaml")


class Entry(BaseModel):
    model_config = ConfigDict(extra="forbid", frozen=True)
    symbol: str            # the name the API, the CLI and the forms use
    tex: str               # how the paper writes it (KaTeX)
    kind: Literal["parameter", "state", "integral"]   # integral: an output of a run
    group: Literal["inertia", "shape", "support", "field", "state", "output"]
    units: str             # its dimension in the consistent units of `Glossary.units`
    meaning: str
    range: str
    paper: list[str]       # the seed's labels; shown as printed numbers

    @model_validator(mode="after")
    def _labels(self) -> Entry:
        for lab in self.paper:
            if not LABEL_RE.match(lab):
                raise ValueError(f"{self.symbol}: malformed label {lab!r}")
        return self


class Glossary(BaseModel):
    model_config = ConfigDict(extra="forbid", frozen=True)
    units: str
    entries: list[Entry]

    @model_validator(mode="after")
    def _unique(self) -> Glossary:
        seen = [e.symbol for e in self.entries]
        dup = {s for s in seen if seen.count(s) > 1}
        if dup:
            raise ValueError(f"glossary symbols defined twice: {sorted(dup)}")
        return self

    def get(self, symbol: str) -> Entry | None:
        return next((e for e in self.entries if e.symbol == symbol), None)


@cache
def load_glossary() -> Glossary:
    return Glossary.model_validate(yaml.safe_load(PATH.read_text(encoding="utf-8")))
