"""What GET /api/cases says of each parameter of a case: its meaning, units and valid
range in words (catalogue/glossary.yaml), and its lower bound as data, which is the one the
model's validation checks (solvers/models/bodies.py param_bounds)."""

from __future__ import annotations

from functools import cache

from catalogue.glossary import load_glossary
from catalogue.numbering import cite, printed
from solvers.models.bodies import param_bounds
from solvers.models.cases import registry


@cache
def describe(case_id: str) -> tuple[dict, ...]:
    """Every parameter of the case, the required ones first: name, required, default,
    example, meaning, units, range, bounds ({"min", "min_inclusive"} or null: any real
    but for the conditions `range` states) and the printed numbers of the equations where
    the paper uses it. A parameter the glossary lacks is a defect of the data: KeyError."""
    spec = registry()[case_id]
    g = load_glossary()
    bounds = param_bounds(spec.body, spec.symmetry)
    rows = [(n, True, None) for n in spec.required]
    rows += [(n, False, d) for n, d in spec.optional.items()]
    out = []
    for name, required, default in rows:
        e = g.get(name)
        if e is None:
            raise KeyError(f"{case_id}: parameter {name} has no glossary entry")
        out.append({"name": name, "required": required, "default": default,
                    "example": spec.example.get(name), "meaning": cite(e.meaning),
                    "units": e.units, "range": e.range, "bounds": bounds.get(name),
                    "paper_numbers": [n for n in map(printed, e.paper) if n]})
    return tuple(out)


def units_convention() -> str:
    """The units every case uses (the glossary's `units`)."""
    return load_glossary().units
