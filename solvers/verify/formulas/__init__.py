"""Implementations of the formulas of catalogue/formulas.yaml, registered on import.

One module per part of the paper; each function takes (P, x) with x in the formula's own
variables (its `variables` field) and uses NumPy only (complex-safe)."""

from solvers.verify.formulas import (  # noqa: F401
    chaplygin,
    flat_base,
    general,
    hamiltonian_sphere,
    plane_bodies,
    reduced_flat,
    reduced_plane,
    reduced_sphere,
    sphere_bodies,
)
