"""Registries of the verification layer: formula implementations and check functions.

A formula id of catalogue/formulas.yaml maps to one Python function
    f(P: Params, x: ndarray) -> scalar | vector | matrix
evaluated in the formula's own variables (its `variables` field), written with NumPy
operations only so that complex x gives exact derivatives by complex step. A check name
(catalogue.schema.CheckName) maps to one function
    check(claim, case, settings) -> Outcome.
Nothing is ever looked up by evaluating strings from YAML: names resolve here.
"""

from collections.abc import Callable
from dataclasses import dataclass, field

FORMULAS: dict[str, Callable] = {}
CORRECTED: dict[str, Callable] = {}     # the project's correction of a formula that fails
CORRECTION_NOTES: dict[str, str] = {}
CHECKS: dict[str, Callable] = {}
# identity check: how to compare formula `fid` with `against` (None: with its own second
# printed form) when the two values are not directly comparable (a density that the measure
# check needs as a scalar, a definition against a condition, ...)
COMPARISONS: dict[tuple[str, str | None], Callable] = {}


def formula(fid: str):
    """Register the implementation of formula `fid` as printed in the paper."""
    def deco(fn):
        if fid in FORMULAS:
            raise ValueError(f"formula {fid} registered twice")
        FORMULAS[fid] = fn
        return fn
    return deco


def corrected(fid: str, note: str):
    """Register the project's corrected form of formula `fid` (used when the printed one
    fails); `note` says what was changed and why."""
    def deco(fn):
        CORRECTED[fid] = fn
        CORRECTION_NOTES[fid] = note
        return fn
    return deco


def compares(fid: str, against: str | None = None):
    """Register (P, x, corrected=False) -> (lhs, rhs), x in the variables of `fid`: the two
    sides the `identity` check compares for the claim `fid == against` (`against` None: the
    formula's own printed forms); corrected=True uses the project's correction."""
    def deco(fn):
        if (fid, against) in COMPARISONS:
            raise ValueError(f"comparison {fid} vs {against} registered twice")
        COMPARISONS[(fid, against)] = fn
        return fn
    return deco


def check(name: str):
    def deco(fn):
        if name in CHECKS:
            raise ValueError(f"check {name} registered twice")
        CHECKS[name] = fn
        return fn
    return deco


@dataclass
class Outcome:
    verdict: str                       # verified | fails | evidence | unchecked
    residual: float | None = None      # normalised residual (max over points) or None
    message: str = ""
    evidence: dict = field(default_factory=dict)   # numbers a person can re-run / plot
    corrected_residual: float | None = None        # residual of the project's correction
