"""Check functions, registered by name (catalogue.schema.CheckName) on import."""

from solvers.verify.checks import negative, ode, pointwise, recorded, structure  # noqa: F401
