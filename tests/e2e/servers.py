"""Servers the browser tests start besides the session's (tests/e2e/conftest.py)."""

import time
from contextlib import contextmanager

import httpx

from app.testing import live_server


@contextmanager
def stored_verdicts_server(records, cache_dir):
    """A server that verifies on start and finds every case's verdicts in its store, the
    store filled from `records` (the session's full verification, the `catalogue_records`
    fixture) as an earlier run of the server would have left it. Computing verdicts in
    the server and serving them after a restart is what tests/e2e/test_checking_browser.py
    and tests/test_verdict_store.py check; the pages that only show verdicts read them
    here (a module that asked the session's server to verify its cases paid 40-55 s of
    CPU for records the session has already computed)."""
    from app.services.payloads import finite as _finite
    from app.services.verdicts import VerdictStore
    from solvers.models.cases import table_case_ids

    store = VerdictStore(table_case_ids(), cache_dir)
    for cid in store.case_ids:
        store.put(cid, [_finite(dict(r)) for r in records if r["case"] == cid])
    with live_server(max_steps=10**9, deadline_s=60.0, verify_on_start=True,
                     use_verdict_cache=True, cache_dir=str(cache_dir)) as url:
        deadline = time.monotonic() + 1800
        while True:
            v = httpx.get(f"{url}/api/health", timeout=5).json()["verification"]
            if v["state"] == "done":
                break
            assert time.monotonic() < deadline, f"verification did not finish: {v}"
            time.sleep(0.5)
        yield url
