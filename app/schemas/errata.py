from typing import Any

from pydantic import BaseModel, Field

from app.schemas.verify import SymbolRef


class _Entry(BaseModel):
    claim: str = Field(description="the claim (record id) in the catalogue; figure/<key> for a "
                       "finding about one of the paper's figures")
    case: str
    case_title: str | None = Field(None, description="the case's title, as its page names it")
    claim_name: str | None = Field(None, description="the claim as a reader knows it: its "
                                   "kind and printed number, 'integral (2.24)'")
    kind: str | None = Field(None, description="misprint | inherited | convention | "
                             "refuted-conjecture | refuted | inconclusive")
    label: str | None = Field(None, description="the equation's LaTeX label (data)")
    number: str | None = Field(None, description="its number in the printed paper, '(2.15)'")
    where: str | None = Field(None, description="where it is printed, if not a label")
    place: str | None = Field(None, description="how the table names where the claim stands: "
                              "its number, or e.g. 'unnumbered, after (2.37)'")
    section: str | None = None
    section_title: str | None = Field(None, description="the paper's title of the section")
    anchor: str = Field(description="the row's id on /errata: /errata#<anchor>")
    printed: str = Field(description="the printed form (LaTeX, as in the paper)")
    plain: str = ""
    residual_printed: float | None = Field(None, description="normalised residual of the "
                                           "printed form (the project's conventions)")
    message: str = ""
    exact: dict[str, Any] | None = Field(None, description="exact certificate or witness "
                                         "in rational arithmetic, when one applies")
    reproduce: str = Field(description="the command that reproduces the record")
    symbols: dict[str, list[SymbolRef]] = Field(
        default_factory=dict, description="the symbols of each typeset formula of the row "
        "(printed: the display as printed; claim: the claim as printed, where another "
        "display; corrected: the project's corrected form), each with its entry on /notation")


class ErratumPublic(_Entry):
    """A printed formula that fails while the project's correction of it holds."""

    corrected: str = Field(description="the project's corrected form and what changed, in words")
    corrected_tex: str | None = Field(None, description="the corrected form as TeX (KaTeX "
                                      "renders it)")
    change: str | None = Field(None, description="what the correction changes, in words")
    corrected_display: str | None = Field(None, description="the display that is actually "
                                          "corrected: its printed number, or where it "
                                          "stands when unnumbered")
    corrected_printed: str | None = Field(None, description="the corrected display as "
                                          "printed (LaTeX)")
    corrected_number: str | None = None
    corrected_where: str | None = None
    corrected_label: str | None = Field(None, description="its LaTeX label (data)")
    corrected_section: str | None = None
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
    """What the project found that the paper does not have, or a check that could not
    decide while what it found leans against the paper (kind inconclusive)."""

    title: str
    finding: str
    leans: str | None = Field(None, description="'against the paper' when the finding "
                              "contradicts or weighs against a printed statement")
    href: str | None = Field(None, description="where the finding is shown, if not the case "
                             "page (a figure on /poincare)")
    evidence: dict[str, Any] = Field(default_factory=dict)
