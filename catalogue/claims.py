"""The parts of a table column: a cell of the table (printed LaTeX and plain text) and a
claim of the text (what a computation could check, with its check and its arguments), with
the conditions and attributions they carry; catalogue/schema.py assembles them into cases
and tables.
"""

from __future__ import annotations

import re
from typing import Literal

from pydantic import Field, field_validator, model_validator

from catalogue import rubber_tex
from catalogue.kinds import (
    BEYOND_MARKS,
    NEGATIVE_CHECKS,
    REQUIRED_ARGS,
    Access,
    Agreement,
    BeyondRowKey,
    CheckLevel,
    CheckName,
    ClaimKind,
    Gyrostat,
    InertiaRestriction,
    Origin,
    Potential,
    Shade,
    StateVariables,
    Strict,
)

LABEL_RE = re.compile(r"^[A-Za-z0-9.\-*/]+$")
CASE_ID_RE = re.compile(r"^(plane|sphere)/[a-z0-9][a-z0-9-]*$")
CLAIM_ID_RE = re.compile(r"^(plane|sphere)/[a-z0-9-]+(/[A-Za-z0-9_\-]+)+$")
FORMULA_ID_RE = re.compile(r"^[A-Za-z][A-Za-z0-9_]*$")
REF_ID_RE = re.compile(r"^[A-Za-z][A-Za-z0-9\-:]*$")
DERIVED = "derived-here"  # the source of a claim the project derived itself
# a check a claim beyond the paper names: a test (path::name) or a module run as a script
CHECK_RE = re.compile(r"^(tests/[\w/]+\.py::\w+|python -m solvers\.[\w.]+)$")


def check_labels(labels: list[str]) -> list[str]:
    for label in labels:
        if not LABEL_RE.match(label):
            raise ValueError(f"malformed equation label {label!r}")
    return labels


class Attribution(Strict):
    """Who the paper credits at this place: a reference key and the name(s)/year as printed."""

    ref: str
    authors: str | None = None
    year: int | None = Field(default=None, ge=1800, le=2100)
    note: str | None = None


class Conditions(Strict):
    """Parameter restrictions under which a claim is made (None: as in the case's model)."""

    potential: Potential | None = None
    S: Gyrostat | None = None
    I: InertiaRestriction | None = None
    # offset of the centre of mass from the geometric centre ((2.28), (2.18)); for the
    # Borisov-Fedorov ball, "2R" is the paper's a = 2R (a: ball radius, R: fixed sphere)
    a: Literal["0", "nonzero", "any", "2R", "not 2R"] | None = None
    z: Literal["0", "nonzero", "any"] | None = None  # flat base: r = (r1, r2, z)
    lambda_: Literal["0", "1", "not 0 or 1", "any"] | None = Field(default=None, alias="lambda")
    k: Literal["0", "nonzero", "any"] | None = None  # signed curvature of the support
    text: str | None = None


class CheckArgs(Strict):
    """What a check needs; every *formula id* here must exist in formulas.yaml."""

    formula: str | None = None  # the integral / density / system / expression under test
    against: str | None = None  # what it is compared with (ODE, other form, full system)
    system: str | None = None  # equations of motion to use if not the case's model
    bracket: str | None = None
    hamiltonian: str | None = None
    multiplier: str | None = None  # time change d tau = N dt
    transform: str | None = None  # change of variables
    potential: str | None = None  # the potential U, when the claim is made with a field
    casimirs: list[str] = []
    rank: int | None = Field(default=None, ge=0)
    candidate: bool = False  # the formula is NOT printed for this claim: a plausible guess
    expect: str | None = None  # the expected outcome, in words, for the solver

    def formula_ids(self) -> list[str]:
        ids = [
            self.formula,
            self.against,
            self.system,
            self.bracket,
            self.hamiltonian,
            self.multiplier,
            self.transform,
            self.potential,
            *self.casimirs,
        ]
        return [i for i in ids if i is not None]


class SubRow(Strict):
    """Second line of a row cell (Table 2's restrictions row has one: `a = 2R`)."""

    printed: str
    plain: str


class Cell(Strict):
    printed: str  # the cell's LaTeX exactly as printed (inside its \parbox)
    plain: str  # plain-text rendering for people
    labels: list[str] = []  # equation labels the cell refers to
    attribution: list[Attribution] = []
    colspan: int = Field(default=1, ge=1)
    # a merged cell: the ids of ALL the cases it spans (itself included), in column order;
    # the YAML shares such a cell between its columns with an anchor
    merged: list[str] = []
    shade: Shade
    shade_note: str | None = None
    subrow: SubRow | None = None
    claims: list[str] = []  # claim ids that make the cell checkable
    convention_note: str | None = None

    @field_validator("labels")
    @classmethod
    def _labels(cls, v: list[str]) -> list[str]:
        return check_labels(v)

    @model_validator(mode="after")
    def _span(self) -> Cell:
        if len(self.merged) == 1:
            raise ValueError("a merged cell spans at least two cases")
        if self.colspan != max(1, len(self.merged)):
            raise ValueError(f"colspan {self.colspan} but the cell spans {self.merged or 1}")
        return self


class Claim(Strict):
    id: str
    kind: ClaimKind
    printed: str  # LaTeX (or text) exactly as printed
    plain: str  # plain-text statement
    label: str | None  # the paper's equation label, or null ...
    where: str | None = None  # ... with where the statement is printed
    attribution: list[Attribution] = []
    conditions: Conditions = Conditions()
    variables: StateVariables
    check: CheckName
    check_args: CheckArgs = CheckArgs()
    origin: Origin = Origin.PAPER  # project: `printed` is the assertion, the formula ours
    convention_note: str | None = None
    remarks: str | None = None
    # verdict layer: how this record relates to others of its case
    establishes: list[str] = []  # a formula-free test of the property these claims state
    inherits: str | None = None  # fails only through this (failing) claim's formula
    holds_under: str | None = None  # the convention under which the printed form holds
    hedged: bool = False  # the paper hedges ("probably", "we were unable"): a conjecture

    @field_validator("id")
    @classmethod
    def _id(cls, v: str) -> str:
        if not CLAIM_ID_RE.match(v):
            raise ValueError(f"malformed claim id {v!r}")
        return v

    @model_validator(mode="after")
    def _consistent(self) -> Claim:
        if self.label is None and not self.where:
            raise ValueError(f"claim {self.id}: give a label or say `where` it is printed")
        if self.label is not None:
            check_labels([self.label])
        for arg in REQUIRED_ARGS[self.check]:
            if getattr(self.check_args, arg) in (None, []):
                raise ValueError(f"claim {self.id}: check {self.check} needs check_args.{arg}")
        if self.check in NEGATIVE_CHECKS and self.kind is not ClaimKind.NEGATIVE:
            raise ValueError(f"claim {self.id}: check {self.check} is only for kind negative")
        if self.origin is Origin.PROJECT and not self.remarks:
            raise ValueError(f"claim {self.id}: a project claim says in `remarks` what the "
                             "paper asserts and what the project derived")
        return self


class SourcedClaim(Strict):
    """A claim of a table beyond the paper: what `source` (a key of rubber_sources.yaml, or
    derived-here for the project's own result) says at `place`, how much of the source was
    read (`access`), how the project's check relates to it (`agreement`) and which check
    backs it (a test path::name or `python -m solvers...`). A derived-here claim also says
    how strong its check is (`level`); a source's claim does not (its check, if any, is
    another claim's)."""

    source: str
    place: str
    access: Access
    says: str
    agreement: Agreement
    check: str | None = None
    level: CheckLevel | None = None

    @model_validator(mode="after")
    def _honest(self) -> SourcedClaim:
        derived = self.source == DERIVED
        if derived != (self.access is Access.DERIVED):
            raise ValueError(f"claim from {self.source!r} has access {self.access}: "
                             "derived-here and only it has access derived-here")
        if derived and (not self.check or self.level is None):
            raise ValueError("a derived-here claim names its check and the check's level")
        if not derived and self.level is not None:
            raise ValueError(f"claim from {self.source!r}: only a derived-here claim has a "
                             "level (a source's statement is not a check)")
        if derived and self.agreement is not Agreement.NOT_APPLICABLE:
            raise ValueError("a derived-here claim agrees with no source: agreement n/a")
        if self.agreement in (Agreement.CONFIRMED, Agreement.CONTRADICTED) and not self.check:
            raise ValueError("confirming or contradicting a source needs a named check")
        if self.check and not CHECK_RE.match(self.check):
            raise ValueError(f"check {self.check!r}: a test tests/...py::name or "
                             "python -m solvers....")
        return self


_LEVEL_ORDER = (CheckLevel.EXACT, CheckLevel.POINTWISE, CheckLevel.NUMERICAL)
_EVIDENCE = ("evidence-for", "evidence-against", "inconclusive")


class MarkedCell(Strict):
    """A cell of a table beyond the paper: its mark (one of the vocabulary's, BEYOND_MARKS),
    the statement in plain text (`statement`: search, CSV, the API's words, screen readers)
    and as LaTeX for the pages to typeset (`statement_tex`: text with `$...$`, as the cells
    of Tables 1 and 2 are printed; both required, and both must name the same symbols,
    catalogue/rubber_tex.py), and the claims it rests on. A mark that says something was shown
    rests on a derived-here claim: 'holds with the project's formula' on an exact or
    pointwise check, evidence on a numerical one; a cell with no check of the project's is
    not checkable, whatever its sources say."""

    mark: str
    statement: str
    statement_tex: str
    claims: list[SourcedClaim]

    @property
    def derived(self) -> list[SourcedClaim]:
        return [c for c in self.claims if c.source == DERIVED]

    @property
    def level(self) -> CheckLevel | None:
        """The level of the check the mark rests on: the strongest exact or pointwise
        derived-here check for a mark that says something holds or fails, a numerical one
        for evidence (a cell's other claims may be stronger: they back parts of it)."""
        levels = {c.level for c in self.derived}
        wanted = (CheckLevel.NUMERICAL,) if self.mark in _EVIDENCE else _LEVEL_ORDER[:2]
        return next((lv for lv in wanted if lv in levels), None)

    @model_validator(mode="after")
    def _mark_has_backing(self) -> MarkedCell:
        if self.mark not in BEYOND_MARKS:
            raise ValueError(f"mark {self.mark!r}: a cell beyond the paper takes one of "
                             f"{BEYOND_MARKS}")
        if not self.statement.strip() or not self.statement_tex.strip():
            raise ValueError("a cell states what it claims, in plain text and in LaTeX")
        why = rubber_tex.mismatch(self.statement, self.statement_tex)
        if why:
            raise ValueError(f"statement and statement_tex differ: {why}")
        if self.mark == "not-checkable" and self.derived:
            raise ValueError("a cell with a check of the project's is not 'not checkable'")
        if self.mark != "not-checkable" and self.level is None:
            raise ValueError(f"mark {self.mark} needs a derived-here check of its level: "
                             "exact or pointwise to hold or fail, numerical for evidence")
        return self


RUBBER_CASE_ID_RE = re.compile(r"^rubber-(plane|sphere)/[a-z0-9][a-z0-9-]*$")


# the words of the rows the rubber tables share with Tables 1 and 2 (plane.yaml's `plain`)
ROW_WORDS = {"measure": "measure", "integrals": "additional integrals",
             "gyrostat": "integrable addition of gyrostat",
             "hamiltonian_form": "Hamiltonian form"}


class BeyondRowSpec(Strict):
    """A row of a table beyond the paper: its key and its header in words."""

    key: BeyondRowKey
    plain: str


class RubberCase(Strict):
    """A column: the body (`model`, a case of solvers/models/rubber_bodies.py, which the
    catalogue does not import) and one marked cell per row."""

    id: str
    model: str
    title: str
    cells: dict[BeyondRowKey, MarkedCell]

    @field_validator("id", "model")
    @classmethod
    def _id(cls, v: str) -> str:
        if not RUBBER_CASE_ID_RE.match(v):
            raise ValueError(f"malformed rubber case id {v!r}")
        return v
