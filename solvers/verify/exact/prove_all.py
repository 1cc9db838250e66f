"""Prove every record the exact layer certifies and store the proofs (proofs.json):

    python -m solvers.verify.exact.prove_all [--seconds S] [--only SUBSTRING]
                                             [--workers W] [--retry]

Each proof runs in a process of its own (proofs.py says what is stored and how it is
fingerprinted).
"""

import json
import multiprocessing as mp
import sys
import time

from catalogue.load import load_catalogue
from solvers.verify import (
    checks,  # noqa: F401  (registers the checks)
    formulas,  # noqa: F401  (registers the formulas)
)
from solvers.verify.exact import certifiers as R
from solvers.verify.exact.certify import prove
from solvers.verify.exact.proofs import PROOFS, code_hash, fingerprint, stored_records
from solvers.verify.registry import CORRECTED


def _jobs(only):
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
    seed_key, drawer, res = job
    t = time.monotonic()
    status, info = prove(seed_key, drawer, res, seconds=seconds)
    queue.put((status, info, time.monotonic() - t))


def generate(seconds: float, only: str | None = None, workers: int = 1, retry=False):
    """Prove every record the exact layer certifies (certifiers.residual_job) with a symbolic
    budget of `seconds` each, each in a process of its own (killed at 2 x budget + 30 s:
    one flint operation cannot be interrupted). Records stored with a current fingerprint
    are kept; with `retry` the unproved ones are attempted again."""
    ctx = mp.get_context("fork")
    records = dict(stored_records())
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
    stored_records.cache_clear()
    n = sum(r["proved"] for r in records.values())
    print(f"{n} records proved of {len(records)} stored")


def _corrected(cat, claim):
    """Whether the claim can have a /corrected record (solvers/verify/run.py: the first of
    formula, system, bracket with a project correction)."""
    a = claim.check_args
    return any(f is not None and f in CORRECTED for f in (a.formula, a.system, a.bracket))


if __name__ == "__main__":
    args = sys.argv[1:]
    secs = float(args[args.index("--seconds") + 1]) if "--seconds" in args else 30.0
    only = args[args.index("--only") + 1] if "--only" in args else None
    workers = int(args[args.index("--workers") + 1]) if "--workers" in args else 1
    generate(secs, only, workers, retry="--retry" in args)
