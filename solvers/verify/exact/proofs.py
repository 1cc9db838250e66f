"""The symbolic proofs, computed once and kept (proofs.json), so `rolling verify` stays fast.

A symbolic proof (certify.prove) of a measure or a reduced system takes seconds to a minute;
`rolling verify` runs in CI. So the proofs are computed by

    python -m solvers.verify.exact.proofs [--seconds S] [--only SUBSTRING] [--workers W] [--retry]

and stored with a fingerprint of everything they depend on: the claim's catalogue entry
(formula, check, conditions, corrected form) and the source of the code the residual runs
(solvers/verify/exact, formulas, variables, params, registry, the bodies and cases of
solvers/models), read as code: its syntax tree without comments and docstrings, so a
reworded comment keeps the proofs current and any change to the code does not. A record
whose fingerprint changed is not proved until the file is
regenerated (it keeps its probabilistic certificate). tests/test_exact_bounds.py recomputes
a sample of the stored proofs.
"""

import ast
import hashlib
import json
import sys
import time
from functools import cache
from pathlib import Path

ROOT = Path(__file__).resolve().parents[3]
PROOFS = Path(__file__).with_name("proofs.json")
CODE = ["solvers/verify/exact/*.py", "solvers/verify/formulas/*.py",
        "solvers/verify/variables.py", "solvers/verify/params.py",
        "solvers/verify/registry.py", "solvers/models/bodies.py", "solvers/models/cases.py",
        "solvers/models/reduced.py", "solvers/models/revolution.py",
        "solvers/verify/checks/common.py", "solvers/verify/checks/structure.py",
        "solvers/verify/checks/pointwise.py", "solvers/verify/checks/ode.py",
        "solvers/verify/checks/negative.py"]


@cache
def code_hash() -> str:
    h = hashlib.sha256()
    for pattern in CODE:
        for f in sorted(ROOT.glob(pattern)):
            if f.name == "proofs.py":
                continue
            h.update(f.relative_to(ROOT).as_posix().encode())
            h.update(_code_text(f.read_text(encoding="utf-8")).encode())
    return h.hexdigest()[:16]


def _code_text(source: str) -> str:
    """The module's syntax tree without its docstrings (comments are not in the tree)."""
    tree = ast.parse(source)
    for node in ast.walk(tree):
        if isinstance(node, ast.Module | ast.ClassDef | ast.FunctionDef | ast.AsyncFunctionDef):
            body = node.body
            if body and isinstance(body[0], ast.Expr) and isinstance(body[0].value, ast.Constant) \
                    and isinstance(body[0].value.value, str):
                node.body = body[1:] or [ast.Pass()]
    return ast.dump(tree)


def _functions(claim, corrected):
    """The code of the formulas the residual runs, as registered now (a formula replaced at
    run time, as the mutation tests do, changes the fingerprint: its stored proof is not
    used)."""
    from solvers.verify.registry import CORRECTED, FORMULAS
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
def _stored() -> dict:
    if not PROOFS.exists():
        return {}
    return json.loads(PROOFS.read_text())["records"]


def lookup(key: str, fp: str):
    """The stored result of record `key` (proved, or why not) if its fingerprint is
    current, else None."""
    rec = _stored().get(key)
    return rec if rec is not None and rec["fingerprint"] == fp else None


def _jobs(only):
    from catalogue.load import load_catalogue
    from solvers.verify import run  # noqa: F401  (registers formulas and checks)
    from solvers.verify.exact import registry as R
    cat = load_catalogue()
    for case in cat.cases():
        for claim in case.claims:
            for corrected in (False, True):
                if corrected and not _corrected(cat, claim):
                    continue
                key = claim.id + ("/corrected" if corrected else "")
                if only and only not in key:
                    continue
                job = R.residual_job(cat, case, claim, corrected)
                if job is not None:
                    yield key, fingerprint(cat, case, claim, corrected), job


def _prove_to(queue, job, seconds):
    from solvers.verify.exact.certify import prove
    seed_key, drawer, res = job
    t = time.monotonic()
    status, info = prove(seed_key, drawer, res, seconds=seconds)
    queue.put((status, info, time.monotonic() - t))


def generate(seconds: float, only: str | None = None, workers: int = 1, retry=False):
    """Prove every record the exact layer certifies (registry.residual_job) with a symbolic
    budget of `seconds` each, each in a process of its own (killed at 2 x budget + 30 s:
    one flint operation cannot be interrupted). Records stored with a current fingerprint
    are kept; with `retry` the unproved ones are attempted again."""
    import multiprocessing as mp
    ctx = mp.get_context("fork")
    records = dict(_stored())
    pending = [(k, fp, job) for k, fp, job in _jobs(only)
               if not (k in records and records[k]["fingerprint"] == fp
                       and (records[k]["proved"] or not retry))]
    running = []

    def finish(key, fp, proc, queue, started):
        if not queue.empty():
            status, info, dt = queue.get()
        else:
            status, info, dt = "no", "killed: past the hard time limit", time.monotonic() - started
        if status == "proved":
            records[key] = {"fingerprint": fp, "proved": True, "variables": info,
                            "seconds": round(dt, 1)}
        else:
            why = (f"the residual is a nonzero rational function (numerator of degree "
                   f"{info[0]})" if status == "nonzero" else info)
            records[key] = {"fingerprint": fp, "proved": False,
                            "reason": f"{why} (budget {seconds:g} s)"}
        print(f"{dt:6.1f}s {status:8s} {key} {'' if status == 'proved' else info}",
              flush=True)

    while pending or running:
        while pending and len(running) < workers:
            key, fp, job = pending.pop(0)
            q = ctx.Queue()
            proc = ctx.Process(target=_prove_to, args=(q, job, seconds))
            proc.start()
            running.append((key, fp, proc, q, time.monotonic()))
        time.sleep(0.05)
        for item in list(running):
            key, fp, proc, q, started = item
            late = time.monotonic() - started > 2 * seconds + 30
            if not q.empty() or not proc.is_alive() or late:
                if late and q.empty():
                    proc.kill()
                proc.join(1)
                finish(key, fp, proc, q, started)
                running.remove(item)
    PROOFS.write_text(json.dumps({"about": "symbolic proofs (solvers/verify/exact/proofs.py)",
                                  "code": code_hash(),
                                  "records": dict(sorted(records.items()))}, indent=1) + "\n")
    _stored.cache_clear()
    n = sum(r["proved"] for r in records.values())
    print(f"{n} records proved of {len(records)} stored")


def _corrected(cat, claim):
    """Whether the claim can have a /corrected record (solvers/verify/run.py: the first of
    formula, system, bracket with a project correction)."""
    from solvers.verify.registry import CORRECTED
    a = claim.check_args
    return any(f is not None and f in CORRECTED for f in (a.formula, a.system, a.bracket))


if __name__ == "__main__":
    args = sys.argv[1:]
    secs = float(args[args.index("--seconds") + 1]) if "--seconds" in args else 30.0
    only = args[args.index("--only") + 1] if "--only" in args else None
    workers = int(args[args.index("--workers") + 1]) if "--workers" in args else 1
    generate(secs, only, workers, retry="--retry" in args)
