"""Check functions, registered by name (catalogue.schema.CheckName) on import."""

from solvers.verify.checks import pointwise, recorded  # noqa: F401
