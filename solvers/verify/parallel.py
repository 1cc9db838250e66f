"""Run `verify` over both cores: claims are independent, so split them across processes."""

import os
from concurrent.futures import ProcessPoolExecutor


def _one(claim_id):
    from solvers.verify.run import verify
    return verify(claim=claim_id)


def verify_parallel(case=None, claim=None, workers=0) -> list[dict]:
    from catalogue.load import load_catalogue
    from solvers.verify.run import verify

    ids = [cl.id for c in load_catalogue().cases() if case in (None, c.id) for cl in c.claims
           if claim in (None, cl.id)]
    if case is not None or claim is not None:
        verify(case=case, claim=claim) if not ids else None   # validates the case id
    workers = workers or os.cpu_count() or 1
    if workers == 1 or len(ids) < 4:
        return [r for cid in ids for r in _one(cid)]
    with ProcessPoolExecutor(workers) as pool:
        return [r for part in pool.map(_one, ids, chunksize=2) for r in part]
