"""The rubber density proofs that take minutes, computed once and kept (rubber_proofs.json).

`rubber_exact.revolution_density_residuals` proves rho = (I1 + m r^2) N(gamma) an invariant
density of a rubber body of revolution by reducing the Liouville residual to zero exactly.
For the disk and the ellipsoid of revolution that takes seconds; for the body of revolution
(ball, ellipsoid and offset together) and the body with spherical inertia, minutes. Those
are run by

    python -m solvers.models.rubber_proofs [CASE ...]

and stored with a fingerprint of what they ran: the syntax tree, without docstrings, of
rubber_exact.py (the field and the reduction) and the case's parameters as exact rationals
(from rubber_bodies.py). A record whose fingerprint differs from the current code's is stale: the
test that reads it (tests/test_rubber_tables_exact.py) fails until it is run again.
"""

from __future__ import annotations

import hashlib
import json
import sys
import time
from pathlib import Path

import sympy as sp

from solvers.models import rubber_bodies as rb
from solvers.models import rubber_exact as rx
from solvers.models.code_text import code_text

HERE = Path(__file__).resolve().parent
STORE = HERE / "rubber_proofs.json"
STORED_CASES = ("rubber-plane/body-of-revolution", "rubber-plane/spherical-inertia")


def fingerprint(case_id: str) -> str:
    h = hashlib.sha256(code_text((HERE / "rubber_exact.py").read_text(encoding="utf-8")).encode())
    h.update(repr(sorted(surface_params(case_id).items())).encode())
    return h.hexdigest()[:16]


def exact(x):
    return sp.nsimplify(x, rational=True)


def surface_params(case_id: str) -> dict:
    """The case's parameters (rubber_bodies.CASES) as exact rationals, in the keywords of
    revolution_density_residuals; the plane, no gyrostat, no Brun field."""
    b = rb.body(case_id)
    if not (b.k == 0 and not any(b.S) and b.eps == 0 and b.I[0] == b.I[1]):
        raise ValueError(f"{case_id}: not a body of revolution on the plane without S, eps")
    return dict(I=[exact(x) for x in b.I], m=exact(b.m), gravity=exact(b.g),
                B=[exact(x) for x in b.B], c=exact(b.c), a=[exact(x) for x in b.a],
                d=exact(b.d))


def prove(case_id: str) -> dict:
    t = time.monotonic()
    residuals = rx.revolution_density_residuals(**surface_params(case_id))
    return {"residuals": [str(r) for r in residuals], "fingerprint": fingerprint(case_id),
            "seconds": round(time.monotonic() - t)}


def stored() -> dict:
    return json.loads(STORE.read_text(encoding="utf-8")) if STORE.exists() else {}


def main(argv=None):
    argv = sys.argv[1:] if argv is None else argv
    records = stored()
    for case_id in argv or STORED_CASES:
        records[case_id] = prove(case_id)
        print(case_id, records[case_id])
        STORE.write_text(json.dumps(records, indent=1, sort_keys=True) + "\n", encoding="utf-8")


if __name__ == "__main__":
    main()
