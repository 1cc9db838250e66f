"""Check functions, registered by name (catalogue.schema.CheckName) on import."""

from solvers.verify.checks import (  # noqa: F401
    formula_free,
    negative,
    nonexistence,
    ode,
    pointwise,
    recorded,
    rotations,
    structure,
)
