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

    RubberTables  (beyond the paper: sources: RubberSource, rubber_sources.yaml; plane,
      sphere: RubberTable of RubberCase columns, each cell a MarkedCell: a mark of the one
      vocabulary and its SourcedClaims; loaded by load.load_rubber)

The vocabularies (enumerations) and the Strict base are in catalogue/kinds.py, cells and
claims in catalogue/claims.py, the bibliography in catalogue/bibliography.py; every name is
importable from here. Every model forbids
unknown keys. Cross-references (case ids of merged cells, claim ids of
cells, reference keys of attributions, formula ids of check arguments) are checked when a
Catalogue is built, so a dangling key fails at load time, not in the solver.
"""

from __future__ import annotations

from typing import Literal

from pydantic import Field, RootModel, field_validator, model_validator

from catalogue.bibliography import (
    BIB_FIELDS,
    BibField,
    CheckedIn,
    Reference,
    RubberSource,
    Since2002,
    SinceNote,
    SourceKind,
)
from catalogue.claims import (
    CASE_ID_RE,
    CLAIM_ID_RE,
    DERIVED,
    FORMULA_ID_RE,
    LABEL_RE,
    REF_ID_RE,
    ROW_WORDS,
    Attribution,
    BeyondRowSpec,
    Cell,
    CheckArgs,
    Claim,
    Conditions,
    MarkedCell,
    RubberCase,
    SourcedClaim,
    SubRow,
    check_labels,
)
from catalogue.kinds import (
    ARG_ROLES,
    BEYOND_MARKS,
    DESCRIPTIVE_ROWS,
    FORMULA_ROLE_OF_CHECK,
    NEGATIVE_CHECKS,
    REQUIRED_ARGS,
    Access,
    Agreement,
    BeyondRowKey,
    Body,
    CheckLevel,
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
    "ARG_ROLES",
    "BEYOND_MARKS",
    "BIB_FIELDS",
    "CASE_ID_RE",
    "CLAIM_ID_RE",
    "DERIVED",
    "DESCRIPTIVE_ROWS",
    "FORMULA_ID_RE",
    "FORMULA_ROLE_OF_CHECK",
    "LABEL_RE",
    "NEGATIVE_CHECKS",
    "REF_ID_RE",
    "REQUIRED_ARGS",
    "Access",
    "Agreement",
    "Attribution",
    "BeyondRowKey",
    "BeyondRowSpec",
    "BibField",
    "Body",
    "Case",
    "Catalogue",
    "Cell",
    "CheckArgs",
    "CheckLevel",
    "CheckName",
    "CheckedIn",
    "Claim",
    "ClaimKind",
    "ColumnGroup",
    "Conditions",
    "CorrectedForm",
    "CorrectedForms",
    "Formula",
    "FormulaRole",
    "Gyrostat",
    "InertiaRestriction",
    "MarkedCell",
    "ModelSpec",
    "Origin",
    "Potential",
    "Reference",
    "RowKey",
    "RowSpec",
    "RubberCase",
    "RubberSource",
    "RubberTable",
    "RubberTables",
    "Shade",
    "Since2002",
    "SinceNote",
    "SourceKind",
    "SourcedClaim",
    "StateVariables",
    "Strict",
    "SubRow",
    "Support",
    "Table",
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


# --- the tables beyond the 2002 paper: the rubber hierarchy ---------------------------------

class RubberTable(Strict):
    id: Literal["rubber-plane", "rubber-sphere"]
    title: str
    note: str
    rows: list[BeyondRowSpec]
    cases: list[RubberCase]

    @model_validator(mode="after")
    def _layout(self) -> RubberTable:
        keys = [r.key for r in self.rows]
        if sorted(keys) != sorted(BeyondRowKey):
            raise ValueError(f"{self.id}: rows must be {[k.value for k in BeyondRowKey]}")
        for key, words in {r.key.value: r.plain for r in self.rows}.items():
            if key in ROW_WORDS and words != ROW_WORDS[key]:
                raise ValueError(f"{self.id}: row {key} is {ROW_WORDS[key]!r} as in Tables "
                                 "1 and 2")
        ids = [c.id for c in self.cases]
        if len(set(ids)) != len(ids):
            raise ValueError(f"{self.id}: duplicate case ids")
        for case in self.cases:
            if not case.id.startswith(self.id + "/"):
                raise ValueError(f"case {case.id} is not in table {self.id}")
            if set(case.cells) != set(keys):
                raise ValueError(f"case {case.id}: rows {sorted(case.cells)}, not {keys}")
        return self


class RubberTables(Strict):
    """The rubber tables and their sources: every claim's source resolves, and no claim
    says more of a source was read than the source's record does."""

    sources: dict[str, RubberSource]
    plane: RubberTable
    sphere: RubberTable

    @model_validator(mode="after")
    def _resolve(self) -> RubberTables:
        if (self.plane.id, self.sphere.id) != ("rubber-plane", "rubber-sphere"):
            raise ValueError("rubber_plane.yaml holds the plane table, rubber_sphere.yaml "
                             "the sphere one")
        depth = [Access.NOT_REACHED, Access.ABSTRACT_ONLY, Access.PARTIAL, Access.TEXT_READ]
        for case in self.cases():
            for row, cell in case.cells.items():
                for c in cell.claims:
                    if c.source == DERIVED:
                        continue
                    if c.source not in self.sources:
                        raise ValueError(f"{case.id} {row}: unknown source {c.source!r}")
                    known = self.sources[c.source].access
                    if depth.index(c.access) > depth.index(known):
                        raise ValueError(f"{case.id} {row}: {c.source} was read as "
                                         f"{known}; the claim cannot say {c.access}")
        return self

    def tables(self) -> tuple[RubberTable, RubberTable]:
        return (self.plane, self.sphere)

    def cases(self) -> list[RubberCase]:
        return [*self.plane.cases, *self.sphere.cases]
