"""Verification of the catalogue's claims by exact computations."""


def verify(case: str | None = None, claim: str | None = None) -> list[dict]:
    # imported here: importing the package must not load every check and formula
    from solvers.verify.run import verify as _verify
    return _verify(case, claim)
