"""Verification of the catalogue's claims by exact computations."""


def verify(case: str | None = None, claim: str | None = None) -> list[dict]:
    from solvers.verify.run import verify as _verify
    return _verify(case, claim)
