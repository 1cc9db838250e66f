"""Claims with nothing to compute: recorded as unchecked, with the reason."""

from solvers.verify.registry import Outcome, check

REASONS = {
    "open_problem": "the paper states this is unknown: an open problem, nothing to verify",
    "formula_not_printed": "asserted in the paper without a printed formula to test",
    "not_checkable": "not decidable by a pointwise or trajectory computation",
}


def _recorded(name):
    def fn(catalogue, case, claim):
        return Outcome("unchecked", None, REASONS[name])
    fn.__name__ = f"check_{name}"
    return fn


for _name in REASONS:
    check(_name)(_recorded(_name))
