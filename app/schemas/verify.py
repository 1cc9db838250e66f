from typing import Any, Literal

from pydantic import BaseModel, Field

Verdict = Literal["verified", "fails", "evidence", "unchecked"]


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
    computed_at: str | None = Field(None, description="when the verdict was computed (UTC)")
    version: str | None = Field(None, description="the project version that computed it")


class VerdictSummary(BaseModel):
    """The verdict mark of a table cell from the verdicts of its claims."""

    mark: Verdict
    counts: dict[str, int]
    claims: list[str]


class VerifyPublic(BaseModel):
    case: str
    records: list[VerdictPublic]
    seconds: float
