"""Rolling-body models, integrators and invariant checks."""
