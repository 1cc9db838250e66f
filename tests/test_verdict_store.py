"""The verdicts' SQLite store (app/services/verdict_db.py), its per-case keys
(app/services/verdict_keys.py) and a real uvicorn restart that serves them at once."""

import sqlite3
import threading
import time
from pathlib import Path

import httpx
import pytest

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
        r = httpx.post(f"{url}/api/verify/{CASE}", json={}, timeout=300.0)
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


# --- a store that heals (issue 21) ------------------------------------------------------

KEYS = {"plane/a": "ka", "plane/b": "kb"}


def _store(cache_dir):
    s = VerdictStore(list(KEYS), cache_dir)
    s._keys = dict(KEYS)
    return s


def _filled(tmp_path):
    s = _store(tmp_path)
    s.put("plane/a", [{"claim": "plane/a/x", "verdict": "verified"}])
    return tmp_path / DB_NAME


def _damage_garbage(path):
    path.write_bytes(b"this is not a database, it was overwritten" * 200)


def _damage_truncated(path):
    con = sqlite3.connect(path)
    con.execute("PRAGMA wal_checkpoint(TRUNCATE)")
    for i in range(200):    # enough pages that a truncation cuts a table's b-tree
        con.execute("INSERT INTO verdicts VALUES (?, 0, 'c', 'k', ?, 0, 'v')",
                    (f"z/{i}", "x" * 500))
    con.commit()
    con.execute("PRAGMA wal_checkpoint(TRUNCATE)")
    con.close()
    data = path.read_bytes()
    path.write_bytes(data[:len(data) // 3])


def _damage_garbled(path):
    con = sqlite3.connect(path)
    con.execute("PRAGMA wal_checkpoint(TRUNCATE)")
    con.close()
    data = bytearray(path.read_bytes())
    data[100:4096] = b"\xff" * (4096 - 100)     # the first page's b-tree header and cells
    path.write_bytes(bytes(data))


@pytest.mark.parametrize("damage", [_damage_garbage, _damage_truncated, _damage_garbled],
                         ids=["overwritten", "truncated", "garbled"])
def test_a_damaged_store_is_moved_aside_and_rebuilt(tmp_path, damage, caplog):
    """Before: the server kept a damaged file, failed to store every verdict ("cannot
    store" x16) and computed everything again at every restart."""
    path = _filled(tmp_path)
    damage(path)
    broken = path.read_bytes()
    s = _store(tmp_path)
    with caplog.at_level("WARNING", logger="rolling.verdicts"):
        assert not s.load_cache()                   # nothing served from a damaged file
    aside = list(tmp_path.glob(f"{DB_NAME}.corrupt-*"))
    assert len(aside) == 1 and aside[0].read_bytes()[:len(broken)] == broken
    assert "moved aside" in caplog.text
    s.put("plane/b", [{"claim": "plane/b/y", "verdict": "fails"}])   # stored again
    t = _store(tmp_path)
    assert t.load_cache() and set(t.records) == {"plane/b"}
    con = sqlite3.connect(path)
    assert con.execute("PRAGMA quick_check").fetchone()[0] == "ok"
    con.close()


def test_a_store_deleted_while_serving_is_recreated_with_what_memory_holds(tmp_path, caplog):
    """Before: a 0-byte file was left and new verdicts stayed in memory only."""
    path = _filled(tmp_path)
    s = _store(tmp_path)
    s.load_cache()
    for p in tmp_path.glob(f"{DB_NAME}*"):
        p.unlink()
    with caplog.at_level("WARNING", logger="rolling.verdicts"):
        s.put("plane/b", [{"claim": "plane/b/y", "verdict": "fails"}])
    assert "deleted" in caplog.text and path.stat().st_size > 0
    t = _store(tmp_path)
    assert t.load_cache() and set(t.records) == {"plane/a", "plane/b"}


def test_an_uncreatable_cache_dir_serves_from_memory_and_says_so(tmp_path, caplog):
    (tmp_path / "file").write_text("a file where the directory should be")
    s = _store(tmp_path / "file" / "cache")
    with caplog.at_level("WARNING", logger="rolling.verdicts"):
        assert not s.load_cache()
        s.put("plane/a", [{"claim": "plane/a/x", "verdict": "verified"}])
    assert "NOT SAVED" in caplog.text and s.records["plane/a"]


READ_ONLY_CHILD = r"""
import json, logging, sys
from app.services.verdicts import VerdictStore
logging.basicConfig(level=logging.WARNING, stream=sys.stderr)
s = VerdictStore(["plane/a", "plane/b"], sys.argv[1])
s._keys = {"plane/a": "ka", "plane/b": "kb"}
served = s.load_cache()
s.put("plane/b", [{"claim": "plane/b/y", "verdict": "fails"}])
print(json.dumps({"served": served, "cases": sorted(s.records), "mode": s.db().mode}))
"""


def test_a_read_only_store_is_served_read_only(tmp_path):
    """Before: a valid store that the process may not write was not used at all (opening
    it tried to write). The child runs as an unprivileged user (root writes anyway)."""
    import json
    import os
    import shutil
    import subprocess
    import sys
    import tempfile

    if os.geteuid() == 0 and shutil.which("setpriv") is None:
        pytest.skip("root without setpriv: cannot take write permission away")
    cache = Path(tempfile.mkdtemp(prefix="rolling-ro-"))
    try:
        _filled(cache)
        for p in cache.glob(f"{DB_NAME}-*"):     # a clean close leaves no journal
            p.unlink()
        before = (cache / DB_NAME).read_bytes()
        os.chmod(cache / DB_NAME, 0o444)
        os.chmod(cache, 0o555)
        prefix = (["setpriv", "--reuid=65534", "--regid=65534", "--clear-groups"]
                  if os.geteuid() == 0 else [])
        r = subprocess.run([*prefix, sys.executable, "-c", READ_ONLY_CHILD, str(cache)],
                           capture_output=True, text=True, timeout=120,
                           env={**os.environ, "PYTHONPATH": str(Path(__file__).parents[1])},
                           cwd="/")
        assert r.returncode == 0, r.stderr[-2000:]
        out = json.loads(r.stdout.strip().splitlines()[-1])
        assert out == {"served": True, "cases": ["plane/a", "plane/b"], "mode": "read-only"}
        assert "read-only" in r.stderr and "NOT SAVED" in r.stderr
        assert (cache / DB_NAME).read_bytes() == before
    finally:
        os.chmod(cache, 0o755)
        shutil.rmtree(cache)
