"""The verdicts on disk: an SQLite database (standard library), one row per record.

    cases(case_id, case_key, computed_at, version)           a case whose check finished
    verdicts(case_id, seq, claim, case_key, record, computed_at, version)

`case_key` is the hash of everything the case's verdicts depend on
(app.services.verdict_keys); a row whose key differs from today's is stale and is never
served. WAL journal: readers never wait for the writer; writes go through one lock per
process and `busy_timeout` between processes (two servers on one cache directory).

The store heals: a file that is not a database, is truncated or fails SQLite's
quick check is moved aside as `verdicts.sqlite3.corrupt-<time>` (kept for inspection) and
a new one is built; a file or directory the process may not write is opened read-only
(`mode`: "read-only"), served, and `save` stores nothing (logged once, clearly); a file
deleted while the server runs is created again at the next save (`recreated` counts it,
and app.services.verdicts stores the verdicts it holds in memory again).
"""

from __future__ import annotations

import json
import logging
import os
import sqlite3
import threading
import time
from pathlib import Path

log = logging.getLogger("rolling.verdicts")

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
        self.mode = "read-write"
        self.moved_aside: list[Path] = []
        self.recreated = 0
        self.path.parent.mkdir(parents=True, exist_ok=True)   # OSError: no store at all
        if not self._writable():
            self._open_read_only()
            return
        try:
            self._init()
        except sqlite3.DatabaseError as exc:
            self._move_aside(exc)
            self._init()

    def _writable(self) -> bool:
        d = self.path.parent
        return os.access(d, os.W_OK | os.X_OK) and (not self.path.exists()
                                                   or os.access(self.path, os.W_OK))

    def _init(self) -> None:
        with self._lock:
            con = self._connect()
            try:
                con.execute("PRAGMA journal_mode=WAL")
                con.executescript(SCHEMA)
                check = con.execute("PRAGMA quick_check").fetchone()[0]
                if check != "ok":
                    raise sqlite3.DatabaseError(f"quick_check: {check}")
            finally:
                con.close()

    def _open_read_only(self) -> None:
        self.mode = "read-only"
        log.warning("the verdict store %s is read-only: its verdicts are served, NEW VERDICTS "
                    "ARE NOT SAVED (they are kept in memory until the server stops)", self.path)
        if self.path.exists():
            con = self._connect()
            try:
                con.execute("SELECT COUNT(*) FROM cases").fetchone()
            except sqlite3.DatabaseError as exc:
                log.warning("the read-only verdict store %s cannot be read either (%s): "
                            "every verdict is computed again", self.path, exc)
                self.mode = "unreadable"
            finally:
                con.close()

    def _move_aside(self, exc: BaseException) -> None:
        """Keep the broken file (and its journal) for inspection under another name."""
        stamp = time.strftime("%Y%m%dT%H%M%SZ", time.gmtime())
        target = self.path.with_name(f"{self.path.name}.corrupt-{stamp}")
        n = 1
        while target.exists():
            n += 1
            target = self.path.with_name(f"{self.path.name}.corrupt-{stamp}-{n}")
        os.replace(self.path, target)
        for suffix in ("-wal", "-shm"):
            side = self.path.with_name(self.path.name + suffix)
            if side.exists():
                os.replace(side, target.with_name(target.name + suffix))
        self.moved_aside.append(target)
        log.warning("the verdict store %s is damaged (%s): moved aside to %s and built anew; "
                    "the verdicts are computed again", self.path, exc, target.name)

    def _connect(self) -> sqlite3.Connection:
        if self.mode != "read-write":
            # immutable: no -shm/-wal is created beside a file in a directory we may not write
            con = sqlite3.connect(f"file:{self.path}?mode=ro&immutable=1", uri=True,
                                  timeout=30.0, isolation_level=None)
            return con
        con = sqlite3.connect(self.path, timeout=30.0, isolation_level=None)
        con.execute("PRAGMA busy_timeout=30000")
        return con

    def load(self, keys: dict[str, str]) -> dict[str, dict]:
        """case id -> {"records", "computed_at", "version"} for the cases whose stored key
        is today's key (`keys`); stale and unknown cases are left out. A store found damaged
        here is moved aside and rebuilt (nothing is served from it)."""
        if self.mode == "unreadable" or (self.mode == "read-only" and not self.path.exists()):
            return {}
        try:
            return self._load(keys)
        except (sqlite3.DatabaseError, json.JSONDecodeError) as exc:
            if self.mode != "read-write":
                raise
            self._move_aside(exc)
            self._init()
            return {}

    def _load(self, keys: dict[str, str]) -> dict[str, dict]:
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
             computed_at: float | None = None) -> bool:
        """Replace the case's rows by `records`, in one transaction. False when nothing
        was stored (a read-only store)."""
        if self.mode != "read-write":
            return False
        if not self.path.exists():      # deleted under the running server
            self.recreated += 1
            log.warning("the verdict store %s was deleted: created again", self.path)
            for suffix in ("-wal", "-shm"):   # a journal of the deleted file is not ours
                self.path.with_name(self.path.name + suffix).unlink(missing_ok=True)
            self._init()
        try:
            self._save(case_id, key, records, version, computed_at)
        except sqlite3.DatabaseError as exc:
            if isinstance(exc, sqlite3.OperationalError) and "locked" in str(exc):
                raise
            self._move_aside(exc)
            self._init()
            self._save(case_id, key, records, version, computed_at)
        return True

    def _save(self, case_id: str, key: str, records: list[dict], version: str,
              computed_at: float | None = None) -> None:
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
