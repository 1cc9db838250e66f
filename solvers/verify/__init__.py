"""Verification of the catalogue's claims by exact computations."""


def verify(case: str | None = None, claim: str | None = None) -> list[dict]:
    # lazy: every check and formula (solvers.verify.run: scipy, flint), not when
    # the package or a light submodule of it is imported
    from solvers.verify.run import verify as _verify
    return _verify(case, claim)
