"""The verdicts' SQLite store (app/services/verdict_db.py), its per-case keys
(app/services/verdict_keys.py) and a real uvicorn restart that serves them at once."""

import sqlite3
import threading
import time

import httpx

from app.services.verdict_db import VerdictDB
from app.services.verdict_keys import case_keys
from app.services.verdicts import DB_NAME, VerdictStore
from app.testing import live_server

CASE = "sphere/borisov-fedorov"      # the quickest case to check (well under a second)


def test_rows_round_trip_and_stale_keys_are_not_served(tmp_path):
    db = VerdictDB(tmp_path / "v.sqlite3")
    recs = [{"claim": "plane/a/x", "verdict": "verified", "residual": 1e-15},
            {"claim": "plane/a/x/corrected", "verdict": "fails", "residual": float("nan")}]
    db.save("plane/a", "k1", recs, "0.1.0", computed_at=1000.0)
    db.save("plane/b", "k2", [{"claim": "plane/b/y", "verdict": "evidence"}], "0.1.0")
    got = db.load({"plane/a": "k1", "plane/b": "CHANGED", "plane/c": "k3"})
    assert set(got) == {"plane/a"}                 # b is stale, c never computed
    assert got["plane/a"]["computed_at"] == 1000.0 and got["plane/a"]["version"] == "0.1.0"
    assert [r["claim"] for r in got["plane/a"]["records"]] == [r["claim"] for r in recs]
    # one row per record; a re-check replaces the case's rows, never appends
    db.save("plane/a", "k1b", recs[:1], "0.1.0")
    assert db.count() == 2
    assert db.load({"plane/a": "k1"}) == {}
    assert len(db.load({"plane/a": "k1b"})["plane/a"]["records"]) == 1
    con = sqlite3.connect(tmp_path / "v.sqlite3")
    assert con.execute("PRAGMA journal_mode").fetchone()[0] == "wal"
    con.close()


def test_concurrent_writers_lose_nothing(tmp_path):
    """Threads of one process and a second connection (another server) write at once."""
    a, b = VerdictDB(tmp_path / "v.sqlite3"), VerdictDB(tmp_path / "v.sqlite3")
    errors = []

    def write(db, prefix):
        try:
            for i in range(25):
                db.save(f"{prefix}/{i}", "k", [{"claim": f"{prefix}/{i}/c",
                                                "verdict": "verified"}] * 3, "v")
        except Exception as exc:  # pragma: no cover - the assertion below reports it
            errors.append(exc)

    threads = [threading.Thread(target=write, args=(db, p))
               for db, p in ((a, "plane"), (b, "sphere"), (a, "x"))]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    assert not errors
    keys = {f"{p}/{i}": "k" for p in ("plane", "sphere", "x") for i in range(25)}
    got = a.load(keys)
    assert len(got) == 75 and all(len(v["records"]) == 3 for v in got.values())


def test_keys_are_per_case():
    """A case's key hashes its own catalogue entry and the formulas it names: two cases
    differ, the same inputs give the same key, and a case outside the catalogue still has
    one (the shared code)."""
    ids = ["plane/chaplygin-ball", "plane/routh-ball", CASE, "plane/not-a-case"]
    k1, k2 = case_keys(ids), case_keys(ids)
    assert k1 == k2 and len(set(k1.values())) == len(ids)


def test_store_serves_only_cases_whose_key_is_unchanged(tmp_path):
    s = VerdictStore(["plane/a", "plane/b"], tmp_path)
    s._keys = {"plane/a": "ka", "plane/b": "kb"}
    s.put("plane/a", [{"claim": "plane/a/x", "verdict": "verified"}])
    s.put("plane/b", [{"claim": "plane/b/y", "verdict": "fails"}])
    t = VerdictStore(["plane/a", "plane/b"], tmp_path)
    t._keys = {"plane/a": "ka", "plane/b": "kb-after-an-edit"}    # only b's inputs changed
    assert t.load_cache() and set(t.records) == {"plane/a"} and t.loaded == 1
    assert t.state != "done"                   # b is to be checked again, a is not
    assert t.computed["plane/a"]["version"]
    assert (tmp_path / DB_NAME).is_file()


def _get(url, path):
    r = httpx.get(url + path, timeout=10.0)
    assert r.status_code == 200, r.text
    return r.json()


def test_a_restarted_uvicorn_serves_stored_verdicts_at_once(tmp_path):
    cache = {"cache_dir": tmp_path, "use_verdict_cache": True, "verify_on_start": False,
             "warm_workers": False, "workers": 1}
    with live_server(**cache) as url:
        assert _get(url, f"/api/cases/{CASE}")["verification"] != "done"
        r = httpx.post(f"{url}/api/verify/{CASE}", timeout=300.0)
        assert r.status_code == 200, r.text
        first = {rec["claim"]: rec["verdict"] for rec in r.json()["records"]}
    assert first and (tmp_path / DB_NAME).is_file()
    t0 = time.monotonic()
    with live_server(**cache) as url:
        # no verification runs in this server (verify_on_start off): what it shows, it read
        d = _get(url, f"/api/cases/{CASE}")
        waited = time.monotonic() - t0
        assert d["verification"] == "done"
        assert {c["id"]: c["verdict"]["verdict"] for c in d["claims"]
                if c["id"] in first} == {k: v for k, v in first.items()
                                          if k in {c["id"] for c in d["claims"]}}
        h = _get(url, "/api/health")["verification"]
        assert h["cases_done"] == 1 and h["updated"] is not None
        assert _get(url, "/api/health")["pool"]["running"] == 0
    print(f"restart to stored verdicts: {waited:.1f} s")


def test_cases_without_a_verdict_are_pending_only_while_checked(tmp_path):
    from app.services import views

    s = VerdictStore([CASE, "plane/chaplygin-ball"], tmp_path)
    s.put(CASE, [{"claim": f"{CASE}/x", "verdict": "verified"}])
    assert s.pending() == set()                  # idle: nothing is being checked
    s.expect_checks()                            # start-up with background verification on
    assert s.state == "running" and s.pending() == {"plane/chaplygin-ball"}
    d = views.case_detail("plane/chaplygin-ball", {}, {}, s.case_state("plane/chaplygin-ball"))
    assert {c["verdict"]["verdict"] for c in d["claims"]} == {"pending"}
    assert d["verdicts"]["pending"] == len(d["claims"]) and d["verdicts"]["unchecked"] == 0
    s.state = "failed"                           # the check did not finish: not "checking"
    d = views.case_detail("plane/chaplygin-ball", {}, {}, s.case_state("plane/chaplygin-ball"))
    assert {c["verdict"]["verdict"] for c in d["claims"]} == {"unchecked"}
    full = VerdictStore([CASE], tmp_path)
    full.load_cache()
    full.expect_checks()                         # every case stored: nothing to check
    assert full.state == "done" and full.pending() == set()
