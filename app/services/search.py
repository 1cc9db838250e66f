"""Search and filter the cases and claims by text, body, surface, kind, mark and verdict
(GET /api/search, the page /search). Each claim carries its mark (solvers/verify/marks.yaml,
as on its case page), not only the coarse verdict (one mark per meaning). Text
matches every word, case- and accent-blind, against what a reader sees: titles, plain
statements, printed numbers, credited authors."""

from __future__ import annotations

import re
import unicodedata
from functools import cache

from app.services import views
from catalogue.load import load_catalogue
from catalogue.numbering import cite, printed
from solvers.models.cases import registry
from solvers.verify import marks as vocab


def claim_anchor(claim_id: str) -> str:
    """The claim's anchor on its case page (case.js anchor(), ssr._anchor)."""
    return "claim-" + re.sub(r"[^A-Za-z0-9_-]+", "_", claim_id)


def _fold(s: str) -> str:
    s = unicodedata.normalize("NFKD", s.casefold())
    s = "".join(ch for ch in s if not unicodedata.combining(ch))
    return s.replace("–", "-").replace("—", "-")


def _authors(attrs) -> str:
    return " ".join(f"{a.authors or ''} {a.year or ''}" for a in attrs)


@cache
def _index() -> tuple[list[dict], list[dict]]:
    cases, claims = [], []
    for case in load_catalogue().cases():
        spec = registry()[case.id]
        head = views.case_summary(case)
        text = " ".join([case.id, case.title, spec.title, spec.body, spec.surface,
                         *(cite(r) or "" for r in case.remarks),
                         *(cite(c.plain) or "" for c in case.cells.values())])
        cases.append({**head, "_text": _fold(text), "_title": _fold(case.title + spec.title)})
        for c in case.claims:
            t = " ".join([c.id, c.kind.value, cite(c.plain) or "", printed(c.label) or "",
                          cite(c.where) or "", _authors(c.attribution), case.title, spec.title])
            claims.append({"id": c.id, "case": case.id, "case_title": case.title,
                           "kind": c.kind.value, "plain": cite(c.plain),
                           "number": printed(c.label),
                           "href": f"/case/{case.id}#{claim_anchor(c.id)}",
                           "body": spec.body, "surface": spec.surface, "_text": _fold(t)})
    return cases, claims


def facets() -> dict[str, list[str]]:
    cases, claims = _index()
    return {"body": sorted({c["body"] for c in cases}),
            "surface": sorted({c["surface"] for c in cases}),
            "kind": sorted({c["kind"] for c in claims}),
            "verdict": ["verified", "fails", "evidence", "unchecked", "pending"],
            "mark": list(vocab.IDS)}


def search(q: str = "", body: str = "", surface: str = "", kind: str = "", verdict: str = "",
           by_claim: dict[str, dict] | None = None, pending: set[str] = frozenset(),
           mark: str = "") -> dict:
    """`pending`: the cases being checked now; their claims without a verdict are pending.
    A claim's mark is the one its case page shows (views._verdict: no record is pending
    while its case is checked, else not checkable, "the check did not run")."""
    by_claim = by_claim or {}
    words = _fold(q).split()
    cases, claims = _index()

    def hit(item: dict) -> bool:
        return all(w in item["_text"] for w in words)

    def verdict_of(cid: str) -> tuple[str, str]:
        if cid in by_claim:
            r = views.record(by_claim[cid])
            return r["verdict"], r["mark"]
        if "/".join(cid.split("/")[:2]) in pending:
            return "pending", "pending"
        return "unchecked", "not-checkable"

    out_claims = []
    for c in claims:
        if (body and c["body"] != body) or (surface and c["surface"] != surface):
            continue
        if (kind and c["kind"] != kind) or not hit(c):
            continue
        v, m = verdict_of(c["id"])
        if (verdict and v != verdict) or (mark and m != mark):
            continue
        out_claims.append({k: x for k, x in c.items() if not k.startswith("_")}
                          | {"verdict": v, "mark": m})
    with_claims = {c["case"] for c in out_claims}
    out_cases = [c for c in cases
                 if (not body or c["body"] == body) and (not surface or c["surface"] == surface)
                 and (hit(c) or (words and (kind or verdict or mark) and c["id"] in with_claims)
                      or (not words and (not (kind or verdict or mark)
                                         or c["id"] in with_claims)))]
    # titles that match come first
    out_cases.sort(key=lambda c: not all(w in c["_title"] for w in words))
    return {"query": {"q": q, "body": body, "surface": surface, "kind": kind,
                      "verdict": verdict, "mark": mark},
            "cases": [{k: x for k, x in c.items() if not k.startswith("_")} for c in out_cases],
            "claims": out_claims}
