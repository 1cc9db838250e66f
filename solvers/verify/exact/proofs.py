"""The symbolic proofs, computed once and kept (proofs.json), so `rolling verify` stays fast:
their fingerprints and the look-up of a stored proof.

A symbolic proof (certify.prove) of a measure or a reduced system takes seconds to a minute;
`rolling verify` runs in CI. So the proofs are computed by prove_all.py,

    python -m solvers.verify.exact.prove_all [--seconds S] [--only SUBSTRING]
                                             [--workers W] [--retry]

and stored with a fingerprint of everything they depend on: the claim's catalogue entry
(formula, check, conditions, corrected form) and the source of the code the residual runs
(solvers/verify/exact, formulas, variables, params, registry, the bodies and cases of
solvers/models), read as code: its syntax tree without comments and docstrings, so a
reworded comment keeps the proofs current and any change to the code does not. A record
whose fingerprint changed is not proved until the file is
regenerated (it keeps its probabilistic certificate). tests/test_exact_bounds.py recomputes
a sample of the stored proofs.
"""

import hashlib
import json
from functools import cache
from pathlib import Path

from solvers.models.code_text import code_text
from solvers.verify.registry import CORRECTED, FORMULAS

ROOT = Path(__file__).resolve().parents[3]
PROOFS = Path(__file__).with_name("proofs.json")
CODE = ["solvers/verify/exact/*.py", "solvers/verify/formulas/*.py",
        "solvers/verify/variables.py", "solvers/verify/params.py",
        "solvers/verify/registry.py", "solvers/models/bodies.py", "solvers/models/cases.py",
        "solvers/models/reduced_systems.py", "solvers/models/revolution.py",
        "solvers/verify/checks/common.py", "solvers/verify/checks/structure.py",
        "solvers/verify/checks/rotations.py",
        "solvers/verify/checks/pointwise.py", "solvers/verify/checks/ode.py",
        "solvers/verify/checks/negative.py"]


@cache
def code_hash() -> str:
    h = hashlib.sha256()
    for pattern in CODE:
        for f in sorted(ROOT.glob(pattern)):
            if f.name in ("proofs.py", "prove_all.py"):     # they store, never compute
                continue
            h.update(f.relative_to(ROOT).as_posix().encode())
            h.update(code_text(f.read_text(encoding="utf-8")).encode())
    return h.hexdigest()[:16]


def _functions(claim, corrected):
    """The code of the formulas the residual runs, as registered now (a formula replaced at
    run time, as the mutation tests do, changes the fingerprint: its stored proof is not
    used)."""
    a = claim.check_args
    out = []
    for fid in (a.formula, a.against, a.system, a.bracket, a.hamiltonian, a.multiplier,
                a.transform):
        for table in (FORMULAS, CORRECTED) if corrected else (FORMULAS,):
            fn = table.get(fid) if fid else None
            if fn is not None:
                code = getattr(fn, "__code__", None)
                out.append([fid, getattr(fn, "__module__", None),
                            getattr(fn, "__qualname__", repr(type(fn))),
                            None if code is None else _code_sig(code, fn.__doc__)])
    return out


def _code_sig(code, doc: str | None = None):
    """Bytecode, constants (nested code objects recursively, no memory addresses; the
    function's docstring left out) and names: stable across processes, different for a
    different function."""
    consts = list(code.co_consts)
    if doc is not None and consts and consts[0] == doc:
        consts = consts[1:]
    consts = [_code_sig(c) if hasattr(c, "co_code") else repr(c) for c in consts]
    return [code.co_code.hex(), consts, list(code.co_names)]


def fingerprint(catalogue, case, claim, corrected) -> str:
    entry = claim.model_dump(mode="json")
    fids = [a for a in (claim.check_args.formula, claim.check_args.against) if a]
    forms = [catalogue.formula(f).model_dump(mode="json") for f in fids
             if _has_formula(catalogue, f)]
    blob = json.dumps([case.id, entry, forms, corrected, code_hash(),
                       _functions(claim, corrected)], sort_keys=True, default=str)
    return hashlib.sha256(blob.encode()).hexdigest()[:16]


def _has_formula(catalogue, fid):
    try:
        catalogue.formula(fid)
        return True
    except (KeyError, LookupError, ValueError):
        return False


@cache
def stored_records() -> dict:
    """The records of proofs.json, by key (read once)."""
    if not PROOFS.exists():
        return {}
    return json.loads(PROOFS.read_text())["records"]


def lookup(key: str, fp: str):
    """The stored result of record `key` (proved, or why not) if its fingerprint is
    current, else None."""
    rec = stored_records().get(key)
    return rec if rec is not None and rec["fingerprint"] == fp else None
