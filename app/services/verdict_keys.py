"""What a case's verdicts depend on, as one hash per case.

A verdict is a function of (a) the case's entry in the catalogue (its model, cells and
claims), (b) the formulas its claims name (their formulas.yaml entries and the source of
the module that implements each one, solvers/verify/formulas/*.py) and (c) the shared
checking code (every other solver source, the catalogue's schema, the versions of numpy
and scipy). A change in (a) or (b) re-checks only the cases that name it; a change in (c)
re-checks every case.
"""

from __future__ import annotations

import hashlib
import inspect
import json
from functools import cache
from pathlib import Path

import numpy
import scipy

from catalogue.load import load_catalogue

ROOT = Path(__file__).resolve().parents[2]
FORMULA_DIR = ROOT / "solvers" / "verify" / "formulas"
# sources outside solvers/ that change what a check computes
SHARED_EXTRA = ("catalogue/schema.py", "catalogue/kinds.py", "catalogue/claims.py",
                "catalogue/load.py", "app/services/jobs.py", "app/services/worker_run.py")


def _digest(*parts: bytes) -> str:
    h = hashlib.sha256()
    for p in parts:
        h.update(len(p).to_bytes(8, "little"))
        h.update(p)
    return h.hexdigest()


def shared_key() -> str:
    """Hash of the checking code every case shares (formula modules excluded)."""
    parts = [f"numpy {numpy.__version__} scipy {scipy.__version__}".encode()]
    files = sorted(p for p in (ROOT / "solvers").rglob("*")
                   if p.suffix in (".py", ".yaml", ".json") and FORMULA_DIR not in p.parents)
    files += [ROOT / f for f in SHARED_EXTRA]
    for p in files:
        parts += [str(p.relative_to(ROOT)).encode(), p.read_bytes()]
    return _digest(*parts)


@cache
def _module_sources() -> dict[str, bytes]:
    return {p.stem: p.read_bytes() for p in sorted(FORMULA_DIR.glob("*.py"))}


def _implementing_modules(fid: str) -> list[str]:
    """The formula modules holding the implementation, correction or comparison of `fid`
    (their short names); every module when the registry cannot be imported."""
    try:
        # lazy: the formula modules of the checks, which register every formula on import,
        # not at the server's start: only a re-check needs them
        import solvers.verify.formulas  # noqa: F401  (registers on import)
        from solvers.verify import registry as reg
    except Exception:  # the check itself will say so; hash conservatively
        return sorted(_module_sources())
    fns = [reg.FORMULAS.get(fid), reg.CORRECTED.get(fid)]
    fns += [fn for (a, b), fn in reg.COMPARISONS.items() if fid in (a, b)]
    mods = set()
    for fn in fns:
        if fn is None:
            continue
        try:
            mods.add(Path(inspect.getfile(fn)).stem)
        except TypeError:
            mods.update(_module_sources())
    return sorted(mods)


def case_keys(case_ids: list[str]) -> dict[str, str]:
    """case id -> hash of everything its verdicts depend on."""

    cat = load_catalogue()
    formulas = {f.id: f for f in cat.formulas}
    sources = _module_sources()
    shared = shared_key()
    out = {}
    for cid in case_ids:
        try:
            case = cat.case(cid)
        except KeyError:  # not in the catalogue: nothing but the shared code to hash
            out[cid] = _digest(shared.encode(), cid.encode())[:24]
            continue
        parts = [shared.encode(), json.dumps(case.model_dump(mode="json"),
                                             sort_keys=True).encode()]
        fids = sorted({f for c in case.claims for f in c.check_args.formula_ids()})
        for fid in fids:
            f = formulas.get(fid)
            parts.append(json.dumps(f.model_dump(mode="json") if f else fid,
                                    sort_keys=True).encode())
            for mod in _implementing_modules(fid):
                parts += [mod.encode(), sources.get(mod, b"")]
        out[cid] = _digest(*parts)[:24]
    return out
