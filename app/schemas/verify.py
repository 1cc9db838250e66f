from typing import Any, Literal

from pydantic import BaseModel, ConfigDict, Field

# pending: the claim's case is being checked on this server right now (a fresh server
# recomputing changed cases); unchecked: nothing can be computed, or the check did not run
Verdict = Literal["verified", "fails", "evidence", "unchecked", "pending"]

# the vocabulary of marks (solvers/verify/marks.yaml): one mark per meaning; a test checks
# that this list is the YAML's
MarkId = Literal["as-printed", "after-correction", "under-convention", "project-formula",
                 "fails", "evidence-for",
                 "evidence-against", "inconclusive", "open", "not-checkable", "pending"]
MARK_FIELD = Field("not-checkable", description="what was shown, one mark per meaning "
                   "(GET /api/marks defines each): as-printed | after-correction | "
                   "under-convention | project-formula | fails | evidence-for | "
                   "evidence-against | inconclusive | open | not-checkable | pending (being "
                   "checked now)")
MARK_NOTE_FIELD = Field(None, description="one sentence that goes with the mark: the "
                        "convention, the misprint, or what an inconclusive check found")
ERRATA_FIELD = Field(default_factory=list, description="after-correction: the formula "
                     "records whose printed form is misprinted and whose correction holds "
                     "(their errata)")


class VerifyRequest(BaseModel):
    """The body of POST /api/verify/{id}: an empty object (the case is in the path; a
    verification has no options). It is there because every POST is JSON
    (Content-Type: application/json), as the guard of the requests that change state
    has it (app/core/guards.py)."""

    model_config = ConfigDict(extra="forbid", json_schema_extra={"examples": [{}]})


class SymbolRef(BaseModel):
    """A symbol of a typeset formula and its entry on /notation (catalogue/notation.yaml)."""

    id: str = Field(description="the entry's id: /notation#sym-<id>")
    tex: str = Field(description="the symbol as the formula writes it (TeX)")
    text: str = Field("", description="the symbol in plain letters (a link's accessible "
                      "name), e.g. ρ0")
    name: str = Field(description="what it is, in a few words")
    href: str


class VerdictPublic(BaseModel):
    """The outcome of a claim's check (solvers.verify), or 'unchecked' when there is none."""

    claim: str
    verdict: Verdict
    residual: float | None = Field(None, description="what the check measured (e.g. "
                                   "max |dF/dt| relative), null when nothing numeric")
    message: str = ""
    check: str | None = None
    origin: str = Field("paper", description="paper | project-correction")
    corrects: str | None = None
    evidence: dict[str, Any] | None = None
    seconds: float | None = None
    printed: str | None = None
    printed_tex: str | None = Field(None, description="a correction's formula (TeX)")
    symbols: list[SymbolRef] = Field(default_factory=list, description="the symbols of "
                                     "printed_tex, each with its entry on /notation")
    change: str | None = Field(None, description="a correction: what it changes in the "
                               "printed formula, in a reader's words")
    computed_at: str | None = Field(None, description="when the verdict was computed (UTC)")
    version: str | None = Field(None, description="the project version that computed it")
    level: Literal["cell", "formula"] = Field(
        "formula", description="formula: one printed expression (or the project's "
        "correction of it); cell: the property a table cell states (solvers.verify.levels)")
    qualifier: str | None = Field(
        None, description="what kind of verdict: convention | misprint | inherited | "
        "refuted-conjecture | refuted | formula-free (null: nothing to qualify)")
    convention: str | None = Field(None, description="the convention under which the "
                                   "printed form holds (qualifier convention)")
    inherits: str | None = Field(None, description="the failing claim this one fails "
                                 "through (qualifier inherited)")
    finding: str | None = Field(None, description="what the project found (qualifier "
                                "refuted-conjecture)")
    row: str | None = Field(None, description="cell records: the row of the table")
    rests_on: list[str] | None = Field(None, description="cell records: the formula "
                                       "records the cell's verdict rests on")
    notes: list[str] | None = Field(None, description="cell records: e.g. 'holds; printed "
                                    "formula corrected'")
    exact: dict[str, Any] | None = Field(None, description="exact certificate in rational "
                                         "arithmetic, when one applies")
    mark: MarkId = MARK_FIELD
    mark_note: str | None = MARK_NOTE_FIELD
    errata: list[str] = ERRATA_FIELD


class CellMark(BaseModel):
    """The mark of a cell's property for one case (body) the cell spans."""

    case: str
    column: int
    mark: MarkId = MARK_FIELD
    mark_note: str | None = MARK_NOTE_FIELD
    errata: list[str] = ERRATA_FIELD
    verdict: Verdict = Field(description="the coarse verdict (kept for compatibility); "
                             "pending: not computed yet")
    notes: list[str] = Field(default_factory=list)
    message: str = ""
    rests_on: list[str] = Field(default_factory=list)


class VerdictSummary(BaseModel):
    """The mark of a table cell: the property it states, per case it spans."""

    mark: MarkId = Field(description="the cell's mark over the cases it spans (the first "
                         "of fails, evidence-against, inconclusive, pending, evidence-for, "
                         "project-formula, after-correction, under-convention, as-printed, open, "
                         "not-checkable among them)")
    verdict: Verdict = Field(description="the coarse verdict (kept for compatibility)")
    mark_counts: dict[str, int] = Field(default_factory=dict, description="number of "
                                        "spanned cases per mark")
    counts: dict[str, int] = Field(description="number of spanned cases per verdict")
    claims: list[str]
    marks: list[CellMark] = Field(default_factory=list, description="one per case the "
                                  "cell spans, in column order")
    notes: list[str] = Field(default_factory=list)


class MarkPublic(BaseModel):
    """One mark of the vocabulary (solvers/verify/marks.yaml)."""

    id: MarkId
    shape: str = Field(description="the sign drawn before the word")
    word: str = Field(description="the short word shown in a table cell")
    name: str
    counted: str = Field(description="a summary's words for several: 'N cells <counted>'")
    counted_one: str
    definition: str


class MarksPublic(BaseModel):
    """The vocabulary of marks, and how many table cells carry each so far."""

    marks: list[MarkPublic]
    cells: dict[str, int] = Field(description="table cells (one per body and row) per mark, "
                                  "over both tables")
    cells_total: int
    summary: str = Field(description="the counts in words")


class VerifyPublic(BaseModel):
    case: str
    records: list[VerdictPublic]
    seconds: float
