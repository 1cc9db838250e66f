"""Verdicts of the catalogue's claims, computed by solvers.verify in the worker pool.

At start-up the store loads the verdicts kept in an SQLite database under
Settings.cache_dir (app.services.verdict_db), each case keyed by a hash of everything its
verdicts depend on (app.services.verdict_keys): a restart serves them at once, and a
background task re-checks only the cases whose key changed (one worker at a time, so
simulations keep the others), logging "computing verdicts: k of n cases".
`POST /api/verify/{id}` recomputes one case.
"""

from __future__ import annotations

import logging
import time
from pathlib import Path

import anyio

from app import __version__
from app.core.pool import QueueFull, WorkerPool
from app.services import jobs
from app.services.verdict_db import VerdictDB
from app.services.verdict_keys import case_keys
from catalogue.load import load_catalogue
from catalogue.numbering import cite
from solvers.verify import marks as vocab
from solvers.verify.levels import DECIDING, combine, formula_mark

log = logging.getLogger("rolling.verdicts")
VERDICTS = ("verified", "fails", "evidence", "unchecked")
DB_NAME = "verdicts.sqlite3"


class VerdictStore:
    def __init__(self, case_ids: list[str], cache_dir: Path | None):
        self.case_ids = list(case_ids)
        self.records: dict[str, list[dict]] = {}     # case id -> records
        self.computed: dict[str, dict] = {}          # case id -> {computed_at, version}
        self.updated: float | None = None
        self.state = "idle"
        self.message = ""
        self.cache_dir = cache_dir
        self.loaded = 0                               # cases served from the database
        self._keys: dict[str, str] | None = None
        self._db: VerdictDB | None = None
        self._no_store = False

    def keys(self) -> dict[str, str]:
        """case id -> hash of what its verdicts depend on (computed once per process)."""
        if self._keys is None:

            self._keys = case_keys(self.case_ids)
        return self._keys

    def key(self, case_id: str) -> str:
        keys = self.keys()
        if case_id not in keys:

            keys.update(case_keys([case_id]))
        return keys[case_id]

    # --- lookups ---------------------------------------------------------------------

    def by_claim(self) -> dict[str, dict]:
        return {r["claim"]: r for recs in self.records.values() for r in recs}

    def corrections(self) -> dict[str, list[dict]]:
        out: dict[str, list[dict]] = {}
        for recs in self.records.values():
            for r in recs:
                if r.get("corrects"):
                    out.setdefault(r["corrects"], []).append(r)
        return out

    def pending(self) -> set[str]:
        """The cases being checked now (or queued for it): no verdict yet, and the
        background verification is running."""
        if self.state != "running":
            return set()
        return {c for c in self.case_ids if c not in self.records}

    def expect_checks(self) -> None:
        """Called at start-up when the background verification will run: the cases it
        will check are "checking" from the first request, not "unchecked" while the
        workers warm up."""
        if any(c not in self.records for c in self.case_ids):
            self.state = "running"

    def case_state(self, case_id: str) -> str:
        if case_id in self.records:
            return "done"
        return self.state if self.state in ("running", "unavailable", "failed") else "idle"

    # --- updates ---------------------------------------------------------------------

    def put(self, case_id: str, records: list[dict]) -> None:
        now = time.time()
        # every verdict says when and by which version of the project it was computed
        stamp = time.strftime("%Y-%m-%dT%H:%M:%SZ", time.gmtime(now))
        records = [{"computed_at": stamp, "version": __version__, **r} for r in records]
        self.records[case_id] = records
        self.computed[case_id] = {"computed_at": now, "version": __version__}
        self.updated = now
        self._save(case_id, records, now)

    def db(self) -> VerdictDB | None:
        if self.cache_dir is None or self._no_store:
            return None
        if self._db is None:
            try:
                self._db = VerdictDB(Path(self.cache_dir) / DB_NAME)
            except (OSError, Exception) as exc:   # an uncreatable directory, a dead disk
                self._no_store = True
                log.warning("no verdict store in %s (%s): verdicts are computed at every "
                            "start and NEW VERDICTS ARE NOT SAVED", self.cache_dir, exc)
                return None
        return self._db

    def load_cache(self) -> bool:
        """Load every case whose stored key is today's; True when some were found."""
        try:
            db = self.db()
            stored = db.load(self.keys()) if db is not None else {}
        except Exception as exc:  # an unreadable database: check everything again
            log.warning("cannot read stored verdicts in %s: %r", self.cache_dir, exc)
            return False
        for cid, row in stored.items():
            self.records[cid] = row["records"]
            self.computed[cid] = {"computed_at": row["computed_at"], "version": row["version"]}
        self.loaded = len(stored)
        if stored:
            self.updated = max(r["computed_at"] for r in stored.values())
        if all(c in self.records for c in self.case_ids):
            self.state = "done"
        log.info("verdicts: %d of %d cases served from %s", len(stored), len(self.case_ids),
                 self.cache_dir)
        return bool(stored)

    def _save(self, case_id: str, records: list[dict], at: float) -> None:
        try:
            db = self.db()
            if db is None:
                return
            recreated = db.recreated
            db.save(case_id, self.key(case_id), records, __version__, at)
            if db.recreated != recreated:     # the file was deleted: store what we hold
                for cid, recs in self.records.items():
                    if cid != case_id:
                        db.save(cid, self.key(cid), recs, __version__,
                                self.computed[cid]["computed_at"])
        except Exception as exc:  # a disk error: verdicts stay in memory
            log.warning("cannot store verdicts in %s: %r", self.cache_dir, exc)

    def progress(self) -> str:
        return f"computing verdicts: {len(self.records)} of {len(self.case_ids)} cases"

    async def verify_all(self, pool: WorkerPool, deadline: float) -> None:
        """Verify every case not yet verified, one at a time (background task)."""
        todo = [c for c in self.case_ids if c not in self.records]
        if not todo:
            self.state = "done"
            return
        self.state, self.message = "running", ""
        log.info("%s (%d to check)", self.progress(), len(todo))
        for cid in todo:
            try:
                recs = await verify_case(pool, cid, deadline)
            except QueueFull as exc:    # the share is full of requested checks: wait
                await anyio.sleep(exc.retry_after)
                todo.append(cid)
                continue
            except ImportError as exc:
                self.state = "unavailable"
                self.message = f"solvers.verify cannot be imported: {exc}"
                log.warning(self.message)
                return
            except Exception as exc:  # keep serving; the case stays unchecked
                log.warning("verification of %s failed: %r", cid, exc)
                self.message = f"verification of {cid} failed: {exc}"
                await anyio.sleep(0.5)
                continue
            self.put(cid, recs)
            log.info(self.progress())
        self.state = "done" if all(c in self.records for c in self.case_ids) else "failed"


async def verify_case(pool: WorkerPool, case_id: str, deadline: float) -> list[dict]:
    """The checks of one case in a worker, within the pool's share of verifications (they
    run for minutes: they must not take every worker from the runs)."""
    return await pool.run(jobs.verify_case, case_id, deadline=deadline, share="verify")


def cell_mark_of(rec: dict | None, waiting: bool) -> tuple[str, str | None, list[str], str]:
    """(mark, mark_note, errata, verdict) of one case's cell record; without a record,
    pending while the case is being checked, else not checkable (its check did not run)."""
    if rec is None:
        return ("pending", None, [], "pending") if waiting else \
            ("not-checkable", "the check did not run on this server", [], "unchecked")
    mark = rec.get("mark")
    if mark is None:                  # a record stored before marks existed

        mark, note, errata = formula_mark(rec, None, {})
    else:
        note, errata = rec.get("mark_note"), list(rec.get("errata") or [])
    return mark, note, errata, rec["verdict"]


def summary(claim_ids: list[str], by_claim: dict[str, dict], row: str,
            case_ids: list[str], pending: set[str] | None = None) -> dict | None:
    """Mark of a table cell: the cell record (solvers.verify.levels) of each case it spans,
    in column order; the overall mark is the first of fails, evidence against,
    inconclusive, pending (a case still being checked), evidence for, after correction,
    under a convention, as printed, open, not checkable among them (levels.combine). The
    coarse verdict is kept beside it. `pending`: the cases being checked now (None: every
    case without a record is); a case without a record that is not being checked (its
    check failed) is not checkable."""
    if not claim_ids:
        return None

    cat = load_catalogue()
    marks, notes = [], []
    for cid in case_ids:
        rec = by_claim.get(f"{cid}/cell/{row}")
        case = cat.case(cid)
        waiting = pending is None or cid in pending
        mark, note, errata, verdict = cell_mark_of(rec, waiting)
        marks.append({"case": cid, "column": case.column, "mark": mark,
                      "mark_note": cite(note), "errata": errata, "verdict": verdict,
                      # what the cell shows a reader: printed numbers, not labels
                      "notes": [cite(n) for n in rec.get("notes") or []] if rec else [],
                      "message": cite(rec.get("message", "")) if rec else "",
                      "rests_on": list(rec.get("rests_on") or []) if rec else []})
        for n in marks[-1]["notes"]:
            if n not in notes:
                notes.append(n)
    shown = [m["mark"] for m in marks]
    decided = [m for m in shown if m in DECIDING]
    mark = combine(decided) if decided else "pending" if "pending" in shown else combine(shown)
    verdicts = [m["verdict"] for m in marks]
    done = [v for v in verdicts if v != "pending"]
    counts = {v: done.count(v) for v in VERDICTS if v in done}
    if "fails" in counts:
        verdict = "fails"
    elif len(done) < len(verdicts):   # a spanned case is being checked
        verdict = "pending"
    elif done and set(counts) == {"verified"}:
        verdict = "verified"
    elif done and set(counts) <= {"verified", "evidence"}:
        verdict = "evidence"
    else:
        verdict = "unchecked"
    return {"mark": mark, "verdict": verdict, "mark_counts": vocab.counts(shown),
            "counts": counts, "claims": claim_ids, "marks": marks, "notes": notes}
