"""Schema of the bibliography: the paper's reference keys (references.yaml), where each
entry's data was read and which fields each source gives, and the notes of what is known
since 2002 (since_2002.yaml). Importable from catalogue.schema like every model."""

from __future__ import annotations

import re
from typing import Literal

from pydantic import field_validator, model_validator

from catalogue.claims import REF_ID_RE
from catalogue.kinds import Access, Strict

SourceKind = Literal["the paper's published reference list", "another paper's reference list",
                     "the publisher's record", "the preprint's record",
                     "a bibliographic database's record", "the article itself"]


# the bibliographic fields of an entry, each of which a complete entry takes from a source
BibField = Literal["authors", "title", "journal", "volume", "number", "pages", "year", "doi"]
BIB_FIELDS: tuple[str, ...] = ("authors", "title", "journal", "volume", "number", "pages",
                               "year", "doi")


class CheckedIn(Strict):
    """Where an entry's bibliographic data was read: the page's address, what kind of source
    it is, how much of it could be read (full: the whole list or record; abstract: the
    record's abstract page; snippet: only the part of a reference list that holds the entry)
    and which of the entry's fields it gives (`gives`)."""

    source: str  # what the page is, e.g. "the reference list of <paper>"
    kind: SourceKind
    url: str
    access: Literal["full", "abstract", "snippet"]
    gives: list[BibField] = []  # the fields of the entry this source prints

    @field_validator("url")
    @classmethod
    def _url(cls, v: str) -> str:
        if not re.match(r"^https?://\S+$", v):
            raise ValueError(f"checked_in url must be an http(s) address, got {v!r}")
        return v


class Reference(Strict):
    id: str  # the \cite key when there is one
    cite_key: str | None  # None: a name the paper mentions without \cite
    # complete entries: the authors as the checked source prints them (authors_source
    # "checked"); otherwise as the seed prints them, empty if the seed never names them
    authors: list[str]
    authors_source: Literal["text", "table", "key", "seed", "checked"]
    years: list[int] = []  # every year the seed gives (more than one: the seed disagrees)
    year_note: str | None = None
    year: int | None = None  # the year of the publication as the checked source gives it
    title: str | None = None
    title_source: str | None = None
    journal: str | None = None  # journal, or book with its publisher, as the source gives it
    volume: str | None = None
    number: str | None = None
    pages: str | None = None
    doi: str | None = None
    translation: str | None = None  # a translation or reprint the source names beside it
    checked_in: list[CheckedIn] = []  # where the entry was read; none: nothing was checked
    # fields read in the seed itself (the paper's own LaTeX), for the paper's own entry
    seed_gives: list[BibField] = []
    # article: a complete entry also needs volume and pages; a book or a preprint does not
    form: Literal["article", "book", "preprint"] = "article"
    identity: str | None = None  # why the \cite key is this work (the seed's context)
    candidate: str | None = None  # unresolved: a work a source lists and why it is not taken
    # complete: authors, title, journal and year (and an article's volume and pages) are
    # known, each from a named source, and the key is tied to the work; unresolved
    # otherwise, and `missing` says what is lacking
    status: Literal["complete", "unresolved"]
    cited_for: list[str]
    remarks: str | None = None

    @property
    def missing(self) -> list[str]:
        """What a full bibliographic entry needs and no checked source gave: authors, title,
        journal (or book), year, and for an article its volume and pages; and a source."""
        have = {"authors": bool(self.authors), "title": bool(self.title),
                "journal": bool(self.journal), "year": bool(self.year or self.years)}
        if self.form == "article":
            have |= {"volume": bool(self.volume), "pages": bool(self.pages)}
        have["checked source"] = bool(self.checked_in)
        return [k for k, ok in have.items() if not ok]

    def field_sources(self) -> dict[str, list[str]]:
        """Each bibliographic field the entry has, with the sources that give it: the seed,
        or the address of a checked source."""
        out: dict[str, list[str]] = {}
        for f in BIB_FIELDS:
            value = getattr(self, f)
            if not value:
                continue
            out[f] = (["seed"] if f in self.seed_gives else []) + [
                c.url for c in self.checked_in if f in c.gives]
        return out

    @property
    def unsourced(self) -> list[str]:
        """The fields of a complete entry that no named source gives (must be empty)."""
        if self.status != "complete":
            return []
        return [f for f, srcs in self.field_sources().items() if not srcs]

    @model_validator(mode="after")
    def _key(self) -> Reference:
        if not REF_ID_RE.match(self.id):
            raise ValueError(f"malformed reference id {self.id!r}")
        if self.cite_key is not None and self.cite_key != self.id:
            raise ValueError(f"reference {self.id}: id must equal the cite key {self.cite_key}")
        if (self.status == "complete") != (not self.missing):
            raise ValueError(f"reference {self.id}: status {self.status!r} but missing "
                             f"{self.missing or 'nothing'}")
        if self.status == "complete" and self.id != "this-paper" and not self.identity:
            raise ValueError(f"reference {self.id}: a complete entry says why the key is "
                             "this work (identity)")
        if self.status == "complete" and self.candidate:
            raise ValueError(f"reference {self.id}: a complete entry has no candidate")
        if self.unsourced:
            raise ValueError(f"reference {self.id}: fields {self.unsourced} are given by no "
                             "named source (checked_in[].gives or seed_gives)")
        return self


class SinceNote(Strict):
    """What is known since 2002 about one open cell, open claim, refuted conjecture or
    non-existence result (catalogue/since_2002.yaml). `record` is a claim id or a cell
    record id `<case>/cell/<row>`; `references` are ids of complete entries of
    references.yaml or of the file's own `literature` (later results, or the context a note
    names when none was found); `access` is the least that was read of them (abstract: only
    abstracts or records; none: the note cites nothing)."""

    record: str
    kind: Literal["open cell", "open claim", "refuted conjecture", "non-existence"]
    note: str
    found_later: bool  # a later result on this question was found in the sources read
    references: list[str] = []
    access: Literal["full", "abstract", "snippet", "none"]
    project: str | None = None  # where the project's own result appears new, with its scope

    @model_validator(mode="after")
    def _consistent(self) -> SinceNote:
        if not self.note.strip():
            raise ValueError(f"since-2002 note {self.record}: empty note")
        if self.found_later and not self.references:
            raise ValueError(f"since-2002 note {self.record}: a later result needs its "
                             "reference")
        if (self.access == "none") != (not self.references):
            raise ValueError(f"since-2002 note {self.record}: access 'none' exactly when "
                             "the note cites nothing")
        if not self.found_later and "no later result found in the sources checked" \
                not in self.note.lower():
            raise ValueError(f"since-2002 note {self.record}: say 'no later result found "
                             "in the sources checked'")
        return self


class Since2002(Strict):
    """catalogue/since_2002.yaml: the later literature (complete entries, each with where
    it was read) and the notes."""

    literature: list[Reference]
    notes: list[SinceNote]

    @model_validator(mode="after")
    def _complete(self) -> Since2002:
        for r in self.literature:
            if r.status != "complete":
                raise ValueError(f"since-2002 literature {r.id}: only complete entries")
        return self


class RubberSource(Strict):
    """A work of the rubber literature: how to cite it, how much of it was read (`access`)
    and where (`read`), and what it says at each place."""

    short: str  # how a table cell names it: authors and year
    cite: str
    access: Access
    read: str
    claims: list[dict]
    cited_by: list[dict] | None = None

    @model_validator(mode="after")
    def _read(self) -> RubberSource:
        if self.access is Access.DERIVED:
            raise ValueError("a source is a work read, not derived-here")
        for c in [*self.claims, *(self.cited_by or [])]:
            if Access(c.get("access")) is Access.DERIVED:
                raise ValueError("a source's statement is not derived-here")
        return self
