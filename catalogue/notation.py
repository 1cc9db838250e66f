"""The notation (catalogue/notation.yaml): every symbol that a typeset formula on a case page
uses, where the paper defines it (printed numbers, section) and what it means in the
project's conventions. `entry_for` maps a symbol token of a formula (catalogue/symbols.py)
to its entry; /notation shows the entries and each formula links its symbols to them."""

from __future__ import annotations

from functools import cache
from pathlib import Path
from typing import Literal

import yaml
from pydantic import BaseModel, ConfigDict, field_validator, model_validator

from catalogue.glossary import load_glossary
from catalogue.numbering import printed
from catalogue.schema import LABEL_RE
from catalogue.symbols import symbols_of_math

PATH = Path(__file__).with_name("notation.yaml")


class Definition(BaseModel):
    model_config = ConfigDict(extra="forbid", frozen=True)
    labels: list[str]                  # the seed's labels; shown as printed numbers
    section: Literal["1", "2", "3"]
    text: str

    @field_validator("labels")
    @classmethod
    def _labels(cls, v: list[str]) -> list[str]:

        for lab in v:
            if not LABEL_RE.match(lab) or printed(lab) is None:
                raise ValueError(f"not a numbered label of the paper: {lab!r}")
        return v


class Symbol(BaseModel):
    model_config = ConfigDict(extra="forbid", frozen=True)
    id: str
    tex: str
    name: str
    forms: list[str]
    defined: list[Definition]
    convention: str | None = None
    glossary: list[str] = []

    @field_validator("id")
    @classmethod
    def _id(cls, v: str) -> str:
        if not v.replace("-", "").isalnum():
            raise ValueError(f"an id is letters, digits and '-': {v!r}")
        return v

    @model_validator(mode="after")
    def _forms(self) -> Symbol:
        if not self.defined:
            raise ValueError(f"{self.id}: says nowhere where the paper defines it")
        for f in self.forms:
            if len(symbols_of_math(f)) != 1:
                raise ValueError(f"{self.id}: the form {f!r} is not one symbol")
        return self

    @property
    def tokens(self) -> list[str]:
        return [symbols_of_math(f)[0] for f in self.forms]


class Notation(BaseModel):
    model_config = ConfigDict(extra="forbid", frozen=True)
    entries: list[Symbol]

    @model_validator(mode="after")
    def _unique(self) -> Notation:
        ids = [e.id for e in self.entries]
        if len(set(ids)) != len(ids):
            twice = sorted({i for i in ids if ids.count(i) > 1})
            raise ValueError(f"notation ids defined twice: {twice}")
        seen: dict[str, str] = {}
        for e in self.entries:
            for t in e.tokens:
                if t in seen:
                    raise ValueError(f"the symbol {t} is in {seen[t]} and {e.id}")
                seen[t] = e.id
        known = {g.symbol for g in load_glossary().entries}
        for e in self.entries:
            for g in e.glossary:
                if g not in known:
                    raise ValueError(f"{e.id}: no glossary entry {g!r}")
        return self

    def by_token(self) -> dict[str, Symbol]:
        return {t: e for e in self.entries for t in e.tokens}

    def get(self, sid: str) -> Symbol | None:
        return next((e for e in self.entries if e.id == sid), None)


@cache
def load_notation() -> Notation:
    return Notation.model_validate(yaml.safe_load(PATH.read_text(encoding="utf-8")))


@cache
def _by_token() -> dict[str, Symbol]:
    return load_notation().by_token()


def entry_for(token: str) -> Symbol | None:
    """The entry that defines a symbol token (catalogue/symbols.py), or None."""
    return _by_token().get(token)
