from typing import Any, Literal

from pydantic import BaseModel, Field

from app.schemas.verify import SymbolRef, VerdictPublic, VerdictSummary


class AttributionPublic(BaseModel):
    ref: str
    authors: str | None = None
    year: int | None = None
    note: str | None = None
    reference_authors: list[str] = Field(default_factory=list)
    reference_title: str | None = None


class ParamBounds(BaseModel):
    min: float = Field(description="the lower bound the model's validation checks")
    min_inclusive: bool = Field(description="true: min itself is valid (>=); false: > min")


class ParamPublic(BaseModel):
    name: str
    required: bool
    default: float | None = Field(None, description="default of an optional parameter "
                                  "(null for I2: equal to I1)")
    example: float | None = None
    meaning: str = Field("", description="what the parameter is (the glossary's entry)")
    units: str = Field("", description="its dimension in any consistent units "
                       "(units_convention of GET /api/cases/{id}), e.g. mass × length²")
    range: str = Field("", description="the values the model accepts, in words, with the "
                       "conditions between parameters (triangle inequality, fit)")
    bounds: ParamBounds | None = Field(None, description="the lower bound as data, as the "
                                       "model's validation checks it; null: any real "
                                       "number but for the conditions `range` states")
    paper_numbers: list[str] = Field(default_factory=list, description="the printed "
                                     "numbers of the paper's equations that use it")


class RunnablePublic(BaseModel):
    """What POST /api/simulate accepts for this case."""

    params: list[ParamPublic]
    example: dict[str, float]
    state: list[float]
    state_labels: list[str]
    fixed_k: str | None = None
    invariants_when: list[dict[str, Any]] = Field(default_factory=list)
    units_convention: str = Field("", description="the units every parameter is in")


class CaseHead(BaseModel):
    """What every view of a case starts with (the list and the permalink page)."""

    id: str
    title: str
    table: int | None = Field(description="1 or 2; null for a case beyond the tables")
    column: int | None = Field(description="the column in its table; null beyond the tables")
    surface: str
    body: str
    model_title: str
    href: str
    in_tables: bool = Field(True, description="a column of the paper's Tables 1 and 2; false "
                            "for a runnable case the paper only mentions (the rattleback)")
    note: str | None = Field(None, description="for a case beyond the tables: what it is")
    constraint: Literal["marble", "rubber"] = Field(
        "marble", description="marble: rolling without slipping (the paper's); rubber: also "
        "without spinning about the normal, (omega, gamma) = 0 (beyond the 2002 paper)")


class CaseSummary(CaseHead):
    claims: int
    params: list[ParamPublic] = Field(default_factory=list, description="what POST "
                                      "/api/simulate takes for the case: each parameter's "
                                      "meaning, units and valid range")


class CellPublic(BaseModel):
    row: str
    row_label: str
    printed: str
    plain: str
    shade: str
    shade_note: str | None = None
    labels: list[str] = Field(default_factory=list, description="the seed's equation labels "
                              "(data; a reader sees `numbers`)")
    numbers: list[str] = Field(default_factory=list, description="the same equations as the "
                               "printed paper numbers them, e.g. (2.24)")
    attribution: list[AttributionPublic] = Field(default_factory=list)
    merged: list[str] = Field(default_factory=list)
    colspan: int = 1
    subrow: dict[str, str] | None = Field(None, description="a second line of the cell "
                                          "(Table 2, restrictions: a = 2R)")
    subrow_case: str | None = Field(None, description="the column the second line is under")
    claims: list[str] = Field(default_factory=list)
    convention_note: str | None = None
    verdict: VerdictSummary | None = None
    symbols: list[SymbolRef] = Field(default_factory=list, description="the symbols of the "
                                     "cell's typeset math, each with its entry on /notation")


class ClaimPublic(BaseModel):
    id: str
    kind: str
    printed: str
    plain: str
    label: str | None = Field(description="the seed's LaTeX label (data, not for display)")
    number: str | None = Field(None, description="the equation's number in the printed paper, "
                               "e.g. (2.24) (docs/equation-numbers.md)")
    where: str | None = None
    attribution: list[AttributionPublic] = Field(default_factory=list)
    conditions: dict[str, str] = Field(default_factory=dict)
    conditions_text: list[str] = Field(default_factory=list, description="the conditions "
                                       "as a reader reads them, e.g. 'no gyrostat (S = 0)'")
    variables: str
    check: str
    check_args: dict[str, Any] = Field(default_factory=dict)
    convention_note: str | None = None
    remarks: str | None = None
    verdict: VerdictPublic
    corrections: list[VerdictPublic] = Field(default_factory=list)
    symbols: list[SymbolRef] = Field(default_factory=list, description="the symbols of the "
                                     "printed formula, each with its entry on /notation")


class CasePublic(CaseHead):
    model: dict[str, Any]
    remarks: list[str] = Field(default_factory=list)
    cells: list[CellPublic]
    claims: list[ClaimPublic]
    runnable: RunnablePublic
    verdicts: dict[str, int] = Field(description="number of claims per verdict")
    marks: dict[str, int] = Field(default_factory=dict, description="number of claims "
                                  "(printed formulas and statements) per mark")
    cell_marks: dict[str, int] = Field(default_factory=dict, description="number of this "
                                       "case's table cells per mark")
    summary: str = Field("", description="the cell and claim counts by mark, in words")
    since_2002: list[dict[str, Any]] = Field(
        default_factory=list, description="what is known since 2002 about this case's open "
        "cells and claims, refuted conjectures and non-existence results "
        "(catalogue/since_2002.yaml): record, kind, note, found_later, access, project, "
        "references resolved to their citations")
    verification: str = Field(description="done | running | idle | unavailable | failed")
    rubber: dict[str, Any] | None = Field(None, description="for a rubber case (rolling "
                                          "without slipping or spinning, beyond the 2002 "
                                          "paper): sentence, equations_href, table_href, "
                                          "cells (its rubber table cells: row, mark, "
                                          "statement in plain text, statement_tex its "
                                          "LaTeX, href), quantities (name, label) "
                                          "plotted along a run (POST /api/observables)")
    notation: list[SymbolRef] = Field(default_factory=list, description="every symbol of the "
                                      "page's typeset formulas (cells, claims, corrected "
                                      "forms), each with its entry on /notation")
