"""Run `verify` over both cores: claims are independent, so split them across processes;
the two levels (solvers.verify.levels) are then put together in the parent."""

import os
from concurrent.futures import ProcessPoolExecutor


def _one(claim_id):
    # lazy: the catalogue and every check (solvers.verify.run: scipy, flint), loaded
    # in the worker process on its first claim, not when a process imports this module
    from catalogue.load import load_catalogue
    from solvers.verify.run import run_claim

    cat = load_catalogue()
    case, claim = cat.find(claim_id)
    return [r.to_json() for r in run_claim(cat, case, claim)]


def verify_parallel(case=None, claim=None, workers=0) -> list[dict]:
    # lazy: the catalogue and every check and formula (solvers.verify.run: scipy and flint,
    # slow to import), which a caller that only imports this module (app/cli) needs only to verify
    from catalogue.load import load_catalogue
    from solvers.verify import levels
    from solvers.verify.run import resolve

    cat = load_catalogue()
    ids, keep, cell_cases = resolve(cat, case, claim)
    workers = workers or os.cpu_count() or 1
    if workers == 1 or len(ids) < 4:
        raw = [r for cid in ids for r in _one(cid)]
    else:
        with ProcessPoolExecutor(workers) as pool:
            raw = [r for part in pool.map(_one, ids, chunksize=2) for r in part]
    return levels.finish(raw, cat, keep, cell_cases)
