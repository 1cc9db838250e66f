from typing import Any

from pydantic import BaseModel, Field


class _Entry(BaseModel):
    claim: str = Field(description="the claim (record id) in the catalogue")
    case: str
    kind: str | None = Field(None, description="misprint | inherited | convention | "
                             "refuted-conjecture | refuted")
    label: str | None = Field(None, description="the equation's LaTeX label (data)")
    number: str | None = Field(None, description="its number in the printed paper, '(2.15)'")
    where: str | None = Field(None, description="where it is printed, if not a label")
    section: str | None = None
    printed: str = Field(description="the printed form (LaTeX, as in the paper)")
    plain: str = ""
    residual_printed: float | None = Field(None, description="normalised residual of the "
                                           "printed form (the project's conventions)")
    message: str = ""
    exact: dict[str, Any] | None = Field(None, description="exact certificate or witness "
                                         "in rational arithmetic, when one applies")
    reproduce: str = Field(description="the command that reproduces the record")


class ErratumPublic(_Entry):
    """A printed formula that fails while the project's correction of it holds."""

    corrected: str = Field(description="the project's corrected form and what changed")
    corrected_formula: str | None = None
    corrected_claim: str | None = Field(None, description="record id of the correction")
    corrected_verdict: str | None = None
    residual_corrected: float | None = None
    corrected_exact: dict[str, Any] | None = None
    inherits: str | None = Field(None, description="for an inherited failure: the failing "
                                 "claim it fails through")


class ConventionPublic(_Entry):
    """A printed form that holds under another convention than the project's."""

    convention: str | None = None
    residual_under_convention: float | None = None


class FindingPublic(_Entry):
    """What the project found that the paper does not have."""

    title: str
    finding: str
    evidence: dict[str, Any] = Field(default_factory=dict)
