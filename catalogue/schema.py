"""Schema of the catalogue: Tables 1 and 2 of Borisov & Mamaev (2002) and the claims of its text.

One pydantic model tree, bioregistry/dysts style: the YAML files are the registry and these
models are its contract.

    Catalogue
      plane, sphere: Table          (plane.yaml = Table 1, sphere.yaml = Table 2)
        rows, column_groups         (row headers, merged header cells, for a front-end)
        cases: Case                 (one column of the table, in the paper's order)
          cells: {RowKey: Cell}     (every row of the table, printed LaTeX + plain text)
          claims: Claim             (everything a computation could check)
      references: Reference         (references.yaml: \\cite keys and uncited names)
      formulas: Formula             (formulas.yaml: one entry per formula the solver implements)

The vocabularies (enumerations) and the Strict base are in catalogue/kinds.py, cells and
claims in catalogue/claims.py; every name is importable from here. Every model forbids
unknown keys. Cross-references (case ids of merged cells, claim ids of
cells, reference keys of attributions, formula ids of check arguments) are checked when a
Catalogue is built, so a dangling key fails at load time, not in the solver.
"""

from __future__ import annotations

import re
from typing import Literal

from pydantic import Field, RootModel, field_validator, model_validator

from catalogue.claims import (
    CASE_ID_RE,
    CLAIM_ID_RE,
    FORMULA_ID_RE,
    LABEL_RE,
    REF_ID_RE,
    Attribution,
    Cell,
    CheckArgs,
    Claim,
    Conditions,
    SubRow,
    check_labels,
)
from catalogue.kinds import (
    ARG_ROLES,
    DESCRIPTIVE_ROWS,
    FORMULA_ROLE_OF_CHECK,
    NEGATIVE_CHECKS,
    REQUIRED_ARGS,
    Body,
    CheckName,
    ClaimKind,
    FormulaRole,
    Gyrostat,
    InertiaRestriction,
    Origin,
    Potential,
    RowKey,
    Shade,
    StateVariables,
    Strict,
    Support,
)

# the names the rest of the code imports from here, wherever they are defined
__all__ = [
    "ARG_ROLES", "CASE_ID_RE", "CLAIM_ID_RE", "DESCRIPTIVE_ROWS", "FORMULA_ID_RE",
    "FORMULA_ROLE_OF_CHECK", "LABEL_RE", "NEGATIVE_CHECKS", "REF_ID_RE", "REQUIRED_ARGS",
    "Attribution", "Body", "Case", "Catalogue", "Cell", "CheckArgs", "CheckName", "CheckedIn",
    "Claim", "ClaimKind", "ColumnGroup", "Conditions", "CorrectedForm", "CorrectedForms",
    "Formula", "FormulaRole", "Gyrostat", "InertiaRestriction", "ModelSpec", "Origin",
    "Potential", "Reference", "RowKey", "RowSpec", "Shade", "Since2002", "SinceNote",
    "SourceKind", "StateVariables", "Strict", "SubRow", "Support", "Table",
]


class ModelSpec(Strict):
    """The system a case's claims are checked on (unless a claim names another)."""

    support: Support
    body: Body
    state: StateVariables
    equations: list[str]  # labels of the equations of motion
    conditions: Conditions

    @field_validator("equations")
    @classmethod
    def _labels(cls, v: list[str]) -> list[str]:
        return check_labels(v)


class Case(Strict):
    id: str
    column: int = Field(ge=1)  # 1-based column of the paper's table
    title: str
    model: ModelSpec
    cells: dict[RowKey, Cell]
    claims: list[Claim]
    remarks: list[str] = []

    @field_validator("id")
    @classmethod
    def _id(cls, v: str) -> str:
        if not CASE_ID_RE.match(v):
            raise ValueError(f"malformed case id {v!r}")
        return v

    @model_validator(mode="after")
    def _claims(self) -> Case:
        seen: set[str] = set()
        for claim in self.claims:
            if not claim.id.startswith(self.id + "/"):
                raise ValueError(f"claim {claim.id} is not prefixed by its case id {self.id}")
            if claim.id in seen:
                raise ValueError(f"duplicate claim id {claim.id}")
            seen.add(claim.id)
        for claim in self.claims:   # links of the verdict layer stay inside the case
            for other in [*claim.establishes, *([claim.inherits] if claim.inherits else [])]:
                if other not in seen or other == claim.id:
                    raise ValueError(f"claim {claim.id}: links to {other!r}, not another "
                                     f"claim of {self.id}")
        for row, cell in self.cells.items():
            if row in DESCRIPTIVE_ROWS and cell.shade is not Shade.NONE:
                raise ValueError(f"{self.id}: row {row} describes the case; shade must be none")
        return self

    def claim(self, claim_id: str) -> Claim:
        for claim in self.claims:
            if claim.id == claim_id:
                return claim
        raise KeyError(claim_id)


class RowSpec(Strict):
    key: RowKey
    printed: str  # the row header as printed
    plain: str
    header: bool  # above the table's double rule (describes the columns)


class ColumnGroup(Strict):
    """A merged header cell: `printed` spans the columns of `cases` in row `row`."""

    row: RowKey
    printed: str
    plain: str
    cases: list[str]


class Table(Strict):
    id: Support
    number: int
    caption_printed: str
    caption_plain: str
    remark_printed: str  # the shading remark under the table
    rows: list[RowSpec]
    column_groups: list[ColumnGroup]
    cases: list[Case]

    @model_validator(mode="after")
    def _layout(self) -> Table:
        ids = [c.id for c in self.cases]
        if len(set(ids)) != len(ids):
            raise ValueError(f"table {self.id}: duplicate case ids")
        position = {c.id: i for i, c in enumerate(self.cases)}
        for i, case in enumerate(self.cases):
            if not case.id.startswith(f"{self.id.value}/"):
                raise ValueError(f"case {case.id} is not in table {self.id}")
            if case.column != i + 1:
                raise ValueError(f"case {case.id}: column {case.column}, listed at {i + 1}")
            if case.model.support is not self.id:
                raise ValueError(f"case {case.id}: model support is {case.model.support}")
        row_keys = [r.key for r in self.rows]
        for case in self.cases:
            if set(case.cells) != set(row_keys):
                missing = set(row_keys) - set(case.cells)
                extra = set(case.cells) - set(row_keys)
                raise ValueError(f"case {case.id}: missing rows {missing}, extra rows {extra}")
        by_id = {c.id: c for c in self.cases}
        # merged cells: the spanned cases exist, are adjacent, and carry the same cell
        for case in self.cases:
            for row, cell in case.cells.items():
                group = cell.merged or [case.id]
                if case.id not in group:
                    raise ValueError(f"{case.id}/{row}: merged cell does not list its own case")
                unknown = [c for c in group if c not in by_id]
                if unknown:
                    raise ValueError(f"{case.id}/{row}: merged with unknown cases {unknown}")
                cols = [position[c] for c in group]
                if cols != list(range(cols[0], cols[0] + len(cols))):
                    raise ValueError(f"{case.id}/{row}: merged columns not adjacent/in order")
                for partner in group:
                    other = by_id[partner].cells[row]
                    if (other.merged, other.printed, other.shade) != (
                        cell.merged,
                        cell.printed,
                        cell.shade,
                    ):
                        raise ValueError(f"{case.id}/{row}: merged cell differs in {partner}")
                owned = {cl.id for c in group for cl in by_id[c].claims}
                for claim_id in cell.claims:
                    if claim_id not in owned:
                        raise ValueError(f"{case.id}/{row}: unknown claim {claim_id}")
        # column groups (merged header cells) agree with the cells of their row
        for grp in self.column_groups:
            for cid in grp.cases:
                if cid not in by_id:
                    raise ValueError(f"column group {grp.plain!r}: unknown case {cid}")
                cell = by_id[cid].cells[grp.row]
                if cell.printed != grp.printed or (cell.merged or [cid]) != grp.cases:
                    raise ValueError(f"column group {grp.plain!r} disagrees with {cid}/{grp.row}")
        return self


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


class CorrectedForm(Strict):
    """One registered correction of a printed formula (corrected_forms.yaml, keyed by the
    formula id): its TeX, what it changes in words, and, when the misprint stands in
    another formula's display, that formula."""

    latex: str
    change: str
    display: str | None = None  # a formula id of formulas.yaml

    @model_validator(mode="after")
    def _nonempty(self) -> CorrectedForm:
        if not self.latex.strip() or not self.change.strip():
            raise ValueError("a corrected form needs its latex and its change")
        return self


class CorrectedForms(RootModel[dict[str, CorrectedForm]]):
    pass


class Formula(Strict):
    id: str
    printed: str  # LaTeX exactly as printed
    plain: str
    label: str | None
    where: str | None = None
    variables: StateVariables
    role: FormulaRole
    origin: Origin = Origin.PAPER  # project: `printed` is the sentence asserting it
    convention_note: str | None = None
    remarks: str | None = None

    @model_validator(mode="after")
    def _consistent(self) -> Formula:
        if not FORMULA_ID_RE.match(self.id):
            raise ValueError(f"malformed formula id {self.id!r}")
        if self.label is None and not self.where:
            raise ValueError(f"formula {self.id}: give a label or say `where` it is printed")
        if self.label is not None:
            check_labels([self.label])
        return self


def _check_roles(claim: Claim, roles: dict[str, str]) -> None:
    """A check argument must name a formula of the matching role (an integral check an
    integral, a bracket argument a bracket, ...): catches a formula id put in the wrong slot."""
    args = claim.check_args
    for arg, role in ARG_ROLES.items():
        fid = getattr(args, arg)
        if fid is not None and roles[fid] != role:
            raise ValueError(f"claim {claim.id}: check_args.{arg} {fid!r} has role {roles[fid]}")
    wanted = FORMULA_ROLE_OF_CHECK.get(claim.check)
    if wanted and args.formula is not None and roles[args.formula] not in wanted:
        raise ValueError(
            f"claim {claim.id}: check {claim.check} needs a formula of role "
            f"{'/'.join(wanted)}; {args.formula!r} has role {roles[args.formula]}"
        )
    if args.casimirs and any(roles[c] != "integral" for c in args.casimirs):
        raise ValueError(f"claim {claim.id}: casimirs must be integrals")


class Catalogue(Strict):
    plane: Table
    sphere: Table
    references: list[Reference]
    formulas: list[Formula]

    @model_validator(mode="after")
    def _resolve(self) -> Catalogue:
        if self.plane.id is not Support.PLANE or self.sphere.id is not Support.SPHERE:
            raise ValueError("plane.yaml must hold the plane table, sphere.yaml the sphere one")
        refs = {r.id: r for r in self.references}
        if len(refs) != len(self.references):
            raise ValueError("duplicate reference ids")
        formulas = {f.id: f.role.value for f in self.formulas}
        if len(formulas) != len(self.formulas):
            raise ValueError("duplicate formula ids")
        claim_ids: set[str] = set()
        for case in self.cases():
            attributions = [
                (f"{case.id}/cell:{row}", a)
                for row, cell in case.cells.items()
                for a in cell.attribution
            ]
            for claim in case.claims:
                if claim.id in claim_ids:
                    raise ValueError(f"duplicate claim id {claim.id}")
                claim_ids.add(claim.id)
                attributions += [(claim.id, a) for a in claim.attribution]
                for fid in claim.check_args.formula_ids():
                    if fid not in formulas:
                        raise ValueError(f"claim {claim.id}: unknown formula id {fid!r}")
                _check_roles(claim, formulas)
            for where, att in attributions:
                if att.ref not in refs:
                    raise ValueError(f"{where}: unknown reference {att.ref!r}")
                years = refs[att.ref].years
                if att.year is not None and years and att.year not in years:
                    raise ValueError(
                        f"{where}: year {att.year} not among the years of {att.ref}: {years}"
                    )
        return self

    # --- lookups -----------------------------------------------------------------------

    def tables(self) -> tuple[Table, Table]:
        return (self.plane, self.sphere)

    def cases(self) -> list[Case]:
        return [*self.plane.cases, *self.sphere.cases]

    def case(self, case_id: str) -> Case:
        for case in self.cases():
            if case.id == case_id:
                return case
        raise KeyError(case_id)

    def claims(self) -> list[Claim]:
        return [claim for case in self.cases() for claim in case.claims]

    def claim(self, claim_id: str) -> Claim:
        for claim in self.claims():
            if claim.id == claim_id:
                return claim
        raise KeyError(claim_id)

    def find(self, claim_id: str) -> tuple[Case, Claim]:
        """The case that holds a claim, and the claim."""
        for case in self.cases():
            for claim in case.claims:
                if claim.id == claim_id:
                    return case, claim
        raise KeyError(claim_id)

    def formula(self, formula_id: str) -> Formula:
        for formula in self.formulas:
            if formula.id == formula_id:
                return formula
        raise KeyError(formula_id)

    def reference(self, ref_id: str) -> Reference:
        for ref in self.references:
            if ref.id == ref_id:
                return ref
        raise KeyError(ref_id)
