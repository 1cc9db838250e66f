"""Verdicts of the catalogue's claims, computed by solvers.verify in the worker pool.

The store starts empty (every claim 'unchecked'); at start-up a background task verifies
the cases one by one (one worker at a time, so simulations keep the others) and
`POST /api/verify/{id}` recomputes one case. Verdicts are cached on disk under a key
made of everything they depend on (the catalogue's YAML, the solvers' sources, the
versions of numpy and scipy), so a restart with unchanged code shows them at once.
"""

from __future__ import annotations

import hashlib
import json
import logging
import time
from pathlib import Path

import anyio

from app.core.pool import WorkerPool
from app.services import jobs

log = logging.getLogger("rolling.verdicts")
ROOT = Path(__file__).resolve().parents[2]
VERDICTS = ("verified", "fails", "evidence", "unchecked")


def inputs_key() -> str:
    """A hash of every file the verdicts depend on."""
    import numpy
    import scipy

    h = hashlib.sha256(f"{numpy.__version__} {scipy.__version__}".encode())
    files = sorted((ROOT / "catalogue").glob("*.yaml")) + sorted(
        p for p in (ROOT / "solvers").rglob("*") if p.suffix in (".py", ".yaml", ".json"))
    for p in files:
        h.update(str(p.relative_to(ROOT)).encode())
        h.update(p.read_bytes())
    return h.hexdigest()[:20]


class VerdictStore:
    def __init__(self, case_ids: list[str], cache_dir: Path | None):
        self.case_ids = list(case_ids)
        self.records: dict[str, list[dict]] = {}     # case id -> records
        self.updated: float | None = None
        self.state = "idle"
        self.message = ""
        self.cache_dir = cache_dir
        self._key: str | None = None

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

    def case_state(self, case_id: str) -> str:
        if case_id in self.records:
            return "done"
        return self.state if self.state in ("running", "unavailable", "failed") else "idle"

    # --- updates ---------------------------------------------------------------------

    def put(self, case_id: str, records: list[dict]) -> None:
        self.records[case_id] = records
        self.updated = time.time()
        self._save()

    def _cache_file(self) -> Path | None:
        if self.cache_dir is None:
            return None
        if self._key is None:
            self._key = inputs_key()
        return self.cache_dir / f"verdicts-{self._key}.json"

    def load_cache(self) -> bool:
        f = self._cache_file()
        if f is None or not f.is_file():
            return False
        try:
            data = json.loads(f.read_text())
        except (OSError, ValueError):
            return False
        self.records = {k: v for k, v in data.get("records", {}).items() if k in self.case_ids}
        self.updated = data.get("updated")
        if all(c in self.records for c in self.case_ids):
            self.state = "done"
        return bool(self.records)

    def _save(self) -> None:
        f = self._cache_file()
        if f is None:
            return
        try:
            f.parent.mkdir(parents=True, exist_ok=True)
            tmp = f.with_suffix(".tmp")
            tmp.write_text(json.dumps({"updated": self.updated, "records": self.records}))
            tmp.replace(f)
        except OSError as exc:  # a read-only home: verdicts stay in memory
            log.warning("cannot cache verdicts in %s: %s", f, exc)

    async def verify_all(self, pool: WorkerPool, deadline: float) -> None:
        """Verify every case not yet verified, one at a time (background task)."""
        todo = [c for c in self.case_ids if c not in self.records]
        if not todo:
            self.state = "done"
            return
        self.state, self.message = "running", ""
        for cid in todo:
            try:
                recs = await verify_case(pool, cid, deadline)
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
        self.state = "done" if all(c in self.records for c in self.case_ids) else "failed"


async def verify_case(pool: WorkerPool, case_id: str, deadline: float) -> list[dict]:
    return await pool.run(jobs.verify_case, case_id, deadline=deadline)


def summary(claim_ids: list[str], by_claim: dict[str, dict], row: str,
            case_ids: list[str]) -> dict | None:
    """Verdict of a table cell: the cell record (solvers.verify.levels) of each case it
    spans, in column order; the overall mark is fails if any case's property fails, else
    verified if all are, evidence if all are verified or evidence, else unchecked."""
    if not claim_ids:
        return None
    from catalogue.load import load_catalogue

    cat = load_catalogue()
    marks, notes = [], []
    for cid in case_ids:
        rec = by_claim.get(f"{cid}/cell/{row}")
        case = cat.case(cid)
        marks.append({"case": cid, "column": case.column,
                      "mark": rec["verdict"] if rec else "pending",
                      "notes": list(rec.get("notes") or []) if rec else [],
                      "message": rec.get("message", "") if rec else "",
                      "rests_on": list(rec.get("rests_on") or []) if rec else []})
        for n in marks[-1]["notes"]:
            if n not in notes:
                notes.append(n)
    done = [m["mark"] for m in marks if m["mark"] != "pending"]
    counts = {v: done.count(v) for v in VERDICTS if v in done}
    pending = len(done) < len(marks)      # a spanned case not computed yet
    if "fails" in counts:
        mark = "fails"
    elif pending:
        mark = "unchecked"
    elif done and set(counts) == {"verified"}:
        mark = "verified"
    elif done and set(counts) <= {"verified", "evidence"}:
        mark = "evidence"
    else:
        mark = "unchecked"
    return {"mark": mark, "counts": counts, "claims": claim_ids, "marks": marks,
            "notes": notes}
