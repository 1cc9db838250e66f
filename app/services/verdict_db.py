"""The verdicts on disk: an SQLite database (standard library), one row per record.

    cases(case_id, case_key, computed_at, version)           a case whose check finished
    verdicts(case_id, seq, claim, case_key, record, computed_at, version)

`case_key` is the hash of everything the case's verdicts depend on
(app.services.verdict_keys); a row whose key differs from today's is stale and is never
served. WAL journal: readers never wait for the writer; writes go through one lock per
process and `busy_timeout` between processes (two servers on one cache directory).
"""

from __future__ import annotations

import json
import sqlite3
import threading
import time
from pathlib import Path

SCHEMA = """
CREATE TABLE IF NOT EXISTS cases (
    case_id TEXT PRIMARY KEY, case_key TEXT NOT NULL,
    computed_at REAL NOT NULL, version TEXT NOT NULL);
CREATE TABLE IF NOT EXISTS verdicts (
    case_id TEXT NOT NULL, seq INTEGER NOT NULL, claim TEXT NOT NULL,
    case_key TEXT NOT NULL, record TEXT NOT NULL, computed_at REAL NOT NULL,
    version TEXT NOT NULL, PRIMARY KEY (case_id, seq));
"""


class VerdictDB:
    def __init__(self, path: Path):
        self.path = Path(path)
        self._lock = threading.Lock()
        self.path.parent.mkdir(parents=True, exist_ok=True)
        with self._connect() as con:
            con.execute("PRAGMA journal_mode=WAL")
            con.executescript(SCHEMA)

    def _connect(self) -> sqlite3.Connection:
        con = sqlite3.connect(self.path, timeout=30.0, isolation_level=None)
        con.execute("PRAGMA busy_timeout=30000")
        return con

    def load(self, keys: dict[str, str]) -> dict[str, dict]:
        """case id -> {"records", "computed_at", "version"} for the cases whose stored key
        is today's key (`keys`); stale and unknown cases are left out."""
        con = self._connect()
        try:
            done = {cid: (key, at, ver) for cid, key, at, ver in con.execute(
                "SELECT case_id, case_key, computed_at, version FROM cases")}
            rows = con.execute(
                "SELECT case_id, case_key, record FROM verdicts ORDER BY case_id, seq").fetchall()
        finally:
            con.close()
        out: dict[str, dict] = {}
        for cid, key in keys.items():
            if cid in done and done[cid][0] == key:
                out[cid] = {"records": [], "computed_at": done[cid][1],
                            "version": done[cid][2]}
        for cid, key, text in rows:
            if cid in out and key == keys[cid]:
                out[cid]["records"].append(json.loads(text))
        return out

    def save(self, case_id: str, key: str, records: list[dict], version: str,
             computed_at: float | None = None) -> None:
        """Replace the case's rows by `records`, in one transaction."""
        at = time.time() if computed_at is None else computed_at
        with self._lock:
            con = self._connect()
            try:
                con.execute("BEGIN IMMEDIATE")
                con.execute("DELETE FROM verdicts WHERE case_id = ?", (case_id,))
                con.executemany(
                    "INSERT INTO verdicts VALUES (?, ?, ?, ?, ?, ?, ?)",
                    [(case_id, i, str(r.get("claim", "")), key, json.dumps(r), at, version)
                     for i, r in enumerate(records)])
                con.execute("INSERT OR REPLACE INTO cases VALUES (?, ?, ?, ?)",
                            (case_id, key, at, version))
                con.execute("COMMIT")
            except BaseException:
                if con.in_transaction:
                    con.execute("ROLLBACK")
                raise
            finally:
                con.close()

    def count(self) -> int:
        con = self._connect()
        try:
            return con.execute("SELECT COUNT(*) FROM verdicts").fetchone()[0]
        finally:
            con.close()
