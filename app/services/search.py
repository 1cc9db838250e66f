"""Search the knowledge base by text (GET /api/search, the page /search): cases (the rattleback
included), claims, the errata, the conventions and the findings (as /errata lists them),
the teaching scenes and the glossary, ranked by a full-text index, and filtered by body,
surface, kind, mark and verdict. Each claim carries its mark (solvers/verify/marks.yaml,
as on its case page), not only the coarse verdict.

The index is SQLite's FTS5 in memory, built once per process from the data: the porter
stemmer over `unicode61 remove_diacritics 2` (so "integrals" finds "integral", "Woronetz"
is accent-blind), bm25 ranking with the title above the body text. The rows that come from
verdicts (errata, conventions, findings) are replaced when the verdicts change.

A query is words, never FTS5 syntax: quotes, operators, `*`, `:` and brackets are only
separators. Words are matched by their stems, and a few words by what a researcher means by
them (SYNONYMS: "density" finds a measure, "disc" a disk, "Celtic stone" the rattleback).
Every word must match (AND); when fewer than TOO_FEW results have them all, the best
results with some of them follow (OR), and the answer says which (`match`: all, or any when
none has every word); a word nothing in the index has is left out and named (`ignored`)."""

from __future__ import annotations

import logging
import math
import re
import sqlite3
import threading
import unicodedata
from functools import cache
from typing import get_args

from app.services import views
from catalogue.glossary import load_glossary
from catalogue.load import load_catalogue
from catalogue.numbering import cite, printed
from catalogue.scenes import load_scenes
from catalogue.schema import ClaimKind
from solvers.models.cases import CaseSpec, beyond_table_ids, registry
from solvers.verify import marks as vocab

log = logging.getLogger(__name__)
SURFACES = ("plane", "sphere")
BODIES = tuple(get_args(CaseSpec.model_fields["body"].annotation))
KINDS = tuple(k.value for k in ClaimKind)
VERDICTS = ("verified", "fails", "evidence", "unchecked", "pending")
MARKS = tuple(vocab.IDS)
TYPES = ("case", "claim", "erratum", "convention", "finding", "scene", "glossary")

# bm25 weights of the index's columns: the title, the text a reader reads, the context
# (a claim's case, a case's model), the names (authors, years, ids, places in the paper),
# the type and kind words
COLUMNS = ("title", "text", "context", "names", "tags")
WEIGHTS = (8.0, 3.0, 1.5, 2.0, 1.5)
TOO_FEW = 5           # fewer results with every word: those with some words follow
MAX_SOME = 20         # ... at most these many
CASE_OF_CLAIM = 0.8   # a case whose claim matches scores this fraction of the claim's score

# What a researcher means by a word: each group's members find each other. A member is one
# word or a phrase (matched as consecutive words of the query, a plural as its singular);
# the index then matches each member by its stem. "sphere" is no synonym of "ball": it is
# the surface a body rolls on (a facet; "disc on a sphere" puts the sphere's results
# first), except in "Chaplygin sphere", the literature's name of the Chaplygin ball.
SYNONYMS: tuple[tuple[str, ...], ...] = (
    ("measure", "density", "invariant measure"),
    ("integral", "first integral", "conserved", "conservation law", "constant of motion"),
    ("misprint", "erratum", "errata", "correction", "typo"),
    ("disk", "disc"),
    ("rattleback", "celtic stone", "wobblestone"),
    ("brun field", "brun potential"),
    ("woronetz", "voronets", "voronetz"),
)
# a word of these groups names a kind of claim (or a type of result): those score higher
HINTS = {"measure": "measure", "integral": "integral", "misprint": "erratum", "brun field": "brun"}
HINT_BOOST = 1.5
# a phrase that means another, one way only
ALIASES = {"chaplygin sphere": ("chaplygin sphere", "chaplygin ball"),
           "poisson structure": ("poisson structure", "bracket")}
STOPWORDS = frozenset("a an and are as at be by for from has have in into is it its of on "
                      "or that the their this to what when which with".split())
MAX_TERMS = 24        # a query's words beyond these are ignored (q is at most 200 chars)
# a word: letters and digits, joined by hyphens or apostrophes, or a printed number (2.24)
_WORD = re.compile(r"\w+(?:(?:[-'’]|(?<=\d)\.(?=\d))\w+)*")
_DYNAMIC = 1_000_000  # rowids of the rows from verdicts start here


def claim_anchor(claim_id: str) -> str:
    """The claim's anchor on its case page (case.js anchor(), ssr._anchor)."""
    return "claim-" + re.sub(r"[^A-Za-z0-9_-]+", "_", claim_id)


def _fold(s: str) -> str:
    s = unicodedata.normalize("NFKD", s.casefold())
    s = "".join(ch for ch in s if not unicodedata.combining(ch))
    return s.replace("–", "-").replace("—", "-")


def _authors(attrs) -> str:
    return " ".join(f"{a.authors or ''} {a.year or ''}" for a in attrs)


def _words(text: str | None) -> str:
    """An id or a kind as words ("plane/routh-ball/integral/jellett" -> plane routh ball ...)."""
    return re.sub(r"[/_*-]+", " ", text or "")


_SURFACE_WORDS = {"plane": "rolling on a plane (Table 1)",
                  "sphere": "rolling on a sphere, inside or outside (Table 2)"}


def _spec_facets(case_id: str) -> dict:
    spec = registry().get(case_id)
    return {"surface": spec.surface if spec else None, "body": spec.body if spec else None}


# ---------------------------------------------------------------- the documents


def _case_docs() -> list[dict]:
    docs = []
    for case in load_catalogue().cases():
        spec = registry()[case.id]
        head = views.case_summary(case)
        # the remarks (which cite by keys) are searched with the names, not shown
        names = [case.id, _words(case.id), *(_authors(c.attribution) for c in case.claims),
                 *(_authors(c.attribution) for c in case.cells.values()),
                 *(cite(r) or "" for r in case.remarks)]
        docs.append({"type": "case", "id": case.id, "title": case.title,
                     "url": head["href"], "case": case.id, "kind": None,
                     **_spec_facets(case.id), "_public": head,
                     # the cells' words are its claims' (a long row ranks low in bm25)
                     "_cols": (case.title, cite(spec.title), _SURFACE_WORDS[spec.surface],
                               " ".join(names), f"case {spec.body} {_words(spec.body)}")})
    for cid in beyond_table_ids():
        spec = registry()[cid]
        head = views.beyond_summary(spec)
        docs.append({"type": "case", "id": cid, "title": spec.title, "url": head["href"],
                     "case": cid, "kind": None, **_spec_facets(cid), "_public": head,
                     "_cols": (spec.title, spec.note or "", _SURFACE_WORDS[spec.surface],
                               f"{cid} {_words(cid)}", f"case {spec.body} beyond the tables")})
    return docs


def _claim_docs() -> list[dict]:
    docs = []
    for case in load_catalogue().cases():
        spec = registry()[case.id]
        for c in case.claims:
            number = printed(c.label)
            name = _words(c.kind.value) + (f" {number}" if number else "")
            href = f"/case/{case.id}#{claim_anchor(c.id)}"
            public = {"id": c.id, "case": case.id, "case_title": case.title,
                      "kind": c.kind.value, "plain": cite(c.plain), "number": number,
                      "href": href, "body": spec.body, "surface": spec.surface}
            # the snippet comes from the text: what the claim's header shows; the notes
            # (which may name records) are searched with the names
            text = " ".join(x for x in (cite(c.plain), cite(c.where)) if x)
            names = " ".join([c.id, _words(c.id), _authors(c.attribution), number or "",
                              cite(c.remarks) or "", cite(c.convention_note) or ""])
            docs.append({"type": "claim", "id": c.id, "title": f"{case.title}: {name}",
                         "url": href, "case": case.id, "kind": c.kind.value,
                         **_spec_facets(case.id), "_public": public,
                         "_cols": (name, text, f"{case.title} {cite(spec.title)} "
                                   f"{_SURFACE_WORDS[spec.surface]}", names,
                                   f"claim {_words(c.kind.value)}")})
    return docs


def _scene_docs() -> list[dict]:
    docs = []
    for s in load_scenes().values():
        case = s.scene.case
        docs.append({"type": "scene", "id": s.id, "title": s.title, "url": f"/scenes#{s.id}",
                     "case": case, "kind": None, **_spec_facets(case), "_public": {},
                     "_cols": (s.title, f"{cite(s.explanation)} {cite(s.claim)}",
                               cite(registry()[case].title) if case in registry() else "",
                               f"{case} {_words(case)} {s.id} {_words(s.id)}",
                               "scene teaching demonstration")})
    return docs


def _glossary_docs() -> list[dict]:
    docs = []
    # the parameters and state variables; the names of a run's outputs (kind integral) are
    # not indexed: their claims are, with where the paper has them, and ten rows more
    # about integrals would shift the weight of the word for every other result
    for e in (e for e in load_glossary().entries if e.kind != "integral"):
        numbers = " ".join(printed(x) or "" for x in e.paper)
        docs.append({"type": "glossary", "id": e.symbol,
                     "title": f"{e.symbol}: {cite(e.meaning)}", "url": f"/glossary#g-{e.symbol}",
                     "case": None, "kind": None, "surface": None, "body": None,
                     "_public": {},
                     "_cols": (e.symbol, f"{cite(e.meaning)} {e.range}", "",
                               f"{e.group} {numbers}",
                               f"glossary notation {e.kind} {e.group}")})
    return docs


def _verdict_docs(records: list[dict]) -> list[dict]:
    """The rows GET /api/errata, /api/conventions and /api/findings list, from the
    verdicts computed so far."""
    from solvers.verify import errata as er

    cat = load_catalogue()
    docs = []
    for e in er.errata(records, cat):
        word = "Misprint" if e.get("kind") == "misprint" else "Inherited misprint"
        docs.append(_row_doc(e, "erratum", f"{word}: {e['claim_name']}, {e['case_title']}",
                             " ".join(x for x in (e.get("change"), e.get("plain"),
                                                  e.get("corrected"), e.get("place")) if x),
                             "erratum misprint correction"))
    for e in er.conventions(records, cat):
        docs.append(_row_doc(e, "convention",
                             f"Convention: {e['claim_name']}, {e['case_title']}",
                             " ".join(x for x in (e.get("convention"), e.get("plain"),
                                                  e.get("place")) if x), "convention"))
    for e in er.findings(records, cat):
        docs.append(_row_doc(e, "finding", e["title"],
                             " ".join(x for x in (e.get("finding"), e.get("plain"),
                                                  e.get("place")) if x),
                             f"finding {_words(e.get('kind'))}"))
    return docs


def _row_doc(e: dict, typ: str, title: str, text: str, tags: str) -> dict:
    claim = load_catalogue().claim(e["claim"])
    return {"type": typ, "id": e["claim"], "title": title, "url": f"/errata#{e['anchor']}",
            "case": e["case"], "kind": claim.kind.value, **_spec_facets(e["case"]),
            "_public": {}, "_cols": (title, text, e["case_title"],
                                     f"{e['claim']} {_words(e['claim'])} "
                                     f"{e.get('number') or ''} {e.get('section') or ''}",
                                     f"{tags} {_words(claim.kind.value)}")}


# ---------------------------------------------------------------- the index


class _Index:
    """The FTS5 table and the documents by rowid; one per process (a lock: the app may
    answer from several threads)."""

    def __init__(self, docs: list[dict]):
        self.lock = threading.Lock()
        self.db = sqlite3.connect(":memory:", check_same_thread=False)
        self.db.execute(
            f"CREATE VIRTUAL TABLE docs USING fts5({', '.join(COLUMNS)}, "
            "tokenize = 'porter unicode61 remove_diacritics 2')")
        self.docs: dict[int, dict] = {}
        self._insert(docs, 1)
        self.cases = {d["id"]: i for i, d in self.docs.items() if d["type"] == "case"}
        self.dynamic_key: tuple = ()

    def _insert(self, docs: list[dict], start: int) -> None:
        for i, d in enumerate(docs, start):
            self.db.execute(f"INSERT INTO docs(rowid, {', '.join(COLUMNS)}) "
                            f"VALUES (?, {', '.join('?' * len(COLUMNS))})", (i, *d["_cols"]))
            self.docs[i] = d

    def set_dynamic(self, key: tuple, make) -> None:
        """Replace the rows from verdicts when `key` (what they are made of) changed."""
        if key == self.dynamic_key:
            return
        try:
            docs = make()
        except Exception:          # the rest of the index still answers
            log.exception("search: the errata, conventions and findings are not indexed")
            docs = []
        self.db.execute("DELETE FROM docs WHERE rowid >= ?", (_DYNAMIC,))
        for i in [i for i in self.docs if i >= _DYNAMIC]:
            del self.docs[i]
        self._insert(docs, _DYNAMIC)
        self.dynamic_key = key

    def order(self) -> list[int]:
        return sorted(self.docs)

    def scores(self, phrase: str) -> dict[int, float]:
        """rowid -> bm25 score of one quoted phrase (higher is better: FTS5's bm25 is
        negative), for the rows that have it."""
        w = ", ".join(str(x) for x in WEIGHTS)
        try:
            rows = self.db.execute(f"SELECT rowid, bm25(docs, {w}) FROM docs "
                                   "WHERE docs MATCH ?", (phrase,)).fetchall()
        except sqlite3.OperationalError:   # cannot happen for a quoted phrase: no match
            return {}
        return {i: -score for i, score in rows}

    def snippets(self, expr: str, rowids: set[int]) -> dict[int, str]:
        """The text around the words of `expr` (an OR of quoted phrases), per row."""
        try:
            rows = self.db.execute("SELECT rowid, snippet(docs, 1, '', '', '…', 16) "
                                   "FROM docs WHERE docs MATCH ?", (expr,)).fetchall()
        except sqlite3.OperationalError:
            return {}
        return {i: snip for i, snip in rows if i in rowids}


@cache
def _index() -> _Index:
    return _Index(_case_docs() + _claim_docs() + _scene_docs() + _glossary_docs())


# ---------------------------------------------------------------- the query


def _phrase(words: list[str] | tuple[str, ...]) -> str:
    # a quoted FTS5 string: the words come from \w+ runs, so they carry no quote
    return '"' + " ".join(words) + '"'


@cache
def _groups() -> list[tuple[tuple[str, ...], tuple[tuple[str, ...], ...]]]:
    """(the words a query may say, the alternatives they stand for), longest first."""
    out = []
    for group in SYNONYMS:
        alts = tuple(tuple(m.split()) for m in group)
        out += [(a, alts) for a in alts]
    out += [(tuple(k.split()), tuple(tuple(v.split()) for v in vs))
            for k, vs in ALIASES.items()]
    return sorted(out, key=lambda x: -len(x[0]))


@cache
def _hints() -> dict[tuple[str, ...], str]:
    """A synonym group's phrases -> the kind of claim (or type of result) it names."""
    return {tuple(_phrase(m.split()) for m in g): HINTS[g[0]] for g in SYNONYMS
            if g[0] in HINTS}


@cache
def _group_words() -> frozenset[str]:
    return frozenset(w for words, _ in _groups() for w in words)


def _singular(word: str) -> str:
    if word in _group_words():
        return word
    for end, sub in (("ies", "y"), ("s", "")):
        if word.endswith(end) and not word.endswith("ss"):
            one = word[:-len(end)] + sub
            if one in _group_words():
                return one
    return word


def terms(q: str) -> list[tuple[str, ...]]:
    """The query as terms, one per word or synonym group: each the quoted FTS5 phrases
    that stand for it (any one of them matches it). Never FTS5 syntax from q: the words
    are runs of letters and digits, joined by hyphens or apostrophes, and numbers."""
    units = [u.replace("’", "'") for u in _WORD.findall(_fold(q))[:MAX_TERMS * 2]]
    units = [u for u in units if u not in STOPWORDS] or units
    # a plural finds a synonym group as its singular does ("integrals", "Celtic stones")
    tokens = [_singular(u) for u in units]
    out, i = [], 0
    while i < len(tokens) and len(out) < MAX_TERMS:
        for words, alts in _groups():
            n = len(words)
            if tuple(tokens[i:i + n]) == words:
                out.append(tuple(_phrase(a) for a in alts))
                i += n
                break
        else:
            # a hyphenated word or a number is a phrase of its parts ("no-such-word", 2.24)
            out.append((_phrase(re.split(r"[-'.]", tokens[i])),))
            i += 1
    return list(dict.fromkeys(out))


def _surface_said(q: str) -> str | None:
    """The surface a query names in words ("disc on a sphere"), not as a facet."""
    f = " ".join(_WORD.findall(_fold(q))).replace("chaplygin sphere", "")
    said = [s for s in SURFACES if re.search(rf"\b{s}s?\b", f)]
    return said[0] if len(said) == 1 else None


def _ranked(q: str, idx: _Index) -> tuple[list[tuple[int, float, str, bool]], list]:
    """(rowid, score, snippet, has every term) of the rows matching q, best first, and
    the terms nothing in the index has (left out).

    A row's score is bm25's sum over the terms, and a term scores by its best synonym
    (a row that says both "measure" and "density" is not counted twice). The rows with
    every term come first; when they are fewer than TOO_FEW, the best rows with some of
    the terms follow."""
    ts = terms(q)
    per_term = []
    for alts in ts:
        found = [idx.scores(a) for a in alts]
        # a synonym group is one term: each phrase's bm25 with the group's IDF (that of
        # the rows having any of them), so a rare synonym does not outweigh the word said
        group = _idf(len(idx.docs), len(set().union(*found)))
        best: dict[int, float] = {}
        for sc in found:
            scale = group / _idf(len(idx.docs), len(sc)) if len(alts) > 1 and sc else 1.0
            for i, x in sc.items():
                best[i] = max(best.get(i, 0.0), x * scale)
        hint = _hints().get(alts)
        if hint:
            for i in best:
                if hint in (idx.docs[i]["kind"], idx.docs[i]["type"]):
                    best[i] *= HINT_BOOST
        per_term.append(best)
    known = [(t, b) for t, b in zip(ts, per_term, strict=True) if b]
    ignored = [t for t, b in zip(ts, per_term, strict=True) if not b]
    if not known:
        return [], ignored

    def total(i: int) -> float:
        return sum(b.get(i, 0.0) for _, b in known)

    every = set.intersection(*(set(b) for _, b in known))
    score = {i: total(i) for i in every}
    # a case holds its claims: it matches with its best claim, a little below it
    for i in list(every):
        d = idx.docs[i]
        if d["type"] == "claim" and d["case"] in idx.cases:
            c = idx.cases[d["case"]]
            score[c] = max(score.get(c, 0.0), CASE_OF_CLAIM * score[i])
    every = set(score)
    rows = sorted(every, key=lambda i: (-score[i], i))
    if len(rows) < TOO_FEW and len(known) > 1:
        some = set.union(*(set(b) for _, b in known)) - every
        rows += sorted(some, key=lambda i: (-sum(i in b for _, b in known), -total(i), i)
                       )[:MAX_SOME]
    snips = idx.snippets(" OR ".join(a for t, _ in known for a in t), set(rows))
    return [(i, score.get(i) or total(i), snips.get(i, ""), i in every) for i in rows], ignored


def _idf(n_rows: int, n_having: int) -> float:
    """FTS5's bm25 IDF of a phrase that n_having of n_rows rows have."""
    return max(math.log((n_rows - n_having + 0.5) / (n_having + 0.5)), 1e-6)


def _plain_term(t: tuple[str, ...]) -> str:
    return " | ".join(a.strip('"') for a in t)


# ---------------------------------------------------------------- search


def facets() -> dict[str, list[str]]:
    """The values each filter accepts (anything else is a 422)."""
    return {"body": sorted(BODIES), "surface": list(SURFACES), "kind": list(KINDS),
            "verdict": list(VERDICTS), "mark": list(MARKS), "type": list(TYPES)}


def _records_key(by_claim: dict[str, dict]) -> tuple:
    return tuple(sorted((c, r.get("verdict"), r.get("qualifier"), r.get("mark"),
                         r.get("residual"), r.get("computed_at"))
                        for c, r in by_claim.items()))


def search(q: str = "", body: str = "", surface: str = "", kind: str = "", verdict: str = "",
           by_claim: dict[str, dict] | None = None, pending: set[str] = frozenset(),
           mark: str = "", type: str = "") -> dict:
    """`pending`: the cases being checked now; their claims without a verdict are pending.
    A claim's mark is the one its case page shows (views._verdict: no record is pending
    while its case is checked, else not checkable, "the check did not run"); an erratum,
    a convention and a finding carry their claim's.

    The answer: `results`, every kind of result ranked together (type, title, snippet,
    url, facets, mark); `cases` and `claims` as before (each with its snippet), in the
    same order; `match` says whether every word matched (all), only some (any), or the
    query had none to match (none; an empty q lists everything)."""
    by_claim = by_claim or {}
    idx = _index()
    with idx.lock:
        idx.set_dynamic(_records_key(by_claim),
                        lambda: _verdict_docs(list(by_claim.values())))
        words = bool(_WORD.search(q or ""))
        if words:
            rows, ignored = _ranked(q, idx)
        else:
            rows, ignored = [(i, 0.0, "", True) for i in idx.order()], []
        docs = [(idx.docs[i], score, snip, full) for i, score, snip, full in rows]

    def verdict_of(cid: str) -> tuple[str, str]:
        if cid in by_claim:
            r = views.record(by_claim[cid])
            return r["verdict"], r["mark"]
        if "/".join(cid.split("/")[:2]) in pending:
            return "pending", "pending"
        return "unchecked", "not-checkable"

    claim_filter = bool(kind or verdict or mark)
    said = None if surface else _surface_said(q)
    kept = []
    for d, score, snip, full in docs:
        if (body and d["body"] != body) or (surface and d["surface"] != surface):
            continue
        if type and d["type"] != type:
            continue
        v = m = None
        if d["type"] in ("claim", "erratum", "convention", "finding"):
            v, m = verdict_of(d["id"])
            if (kind and d["kind"] != kind) or (verdict and v != verdict) or (mark and m != mark):
                continue
        elif d["type"] != "case" and claim_filter:
            continue
        kept.append((d, score, snip, v, m, full))

    # a case stays under a claim filter when it has a claim that passes it
    if claim_filter:
        with_claims = _cases_with_claims(kind, verdict, mark, verdict_of)
        kept = [k for k in kept if k[0]["type"] != "case" or k[0]["id"] in with_claims]
    if said and words:                          # "disc on a sphere": that surface first
        kept.sort(key=lambda k: k[0]["surface"] not in (said, None))
    # every word matched by some result (all), only some words by each (any), no word to
    # match (none: the filters alone)
    how = "none" if not words or not (kept or rows) else (
        "all" if any(k[5] for k in kept) or (not kept and any(r[3] for r in rows)) else "any")

    results, cases, claims = [], [], []
    for d, score, snip, v, m, _ in kept:
        snippet = snip or _first_words(d["_cols"][1]) or _first_words(d["_cols"][2])
        results.append({"type": d["type"], "id": d["id"], "title": d["title"],
                        "snippet": snippet, "url": d["url"], "case": d["case"],
                        "surface": d["surface"], "body": d["body"], "kind": d["kind"],
                        "mark": m, "verdict": v, "score": round(score, 6)})
        if d["type"] == "case":
            cases.append({**d["_public"], "snippet": snippet})
        elif d["type"] == "claim":
            claims.append({**d["_public"], "snippet": snippet, "verdict": v, "mark": m})
    return {"query": {"q": q, "body": body, "surface": surface, "kind": kind,
                      "verdict": verdict, "mark": mark, "type": type},
            "match": how, "terms": [_plain_term(t) for t in terms(q)],
            "ignored": [_plain_term(t) for t in ignored],
            "results": results, "cases": cases, "claims": claims}


def _cases_with_claims(kind, verdict, mark, verdict_of) -> set[str]:
    out = set()
    for d in _index().docs.values():
        if d["type"] != "claim" or (kind and d["kind"] != kind):
            continue
        v, m = verdict_of(d["id"])
        if (not verdict or v == verdict) and (not mark or m == mark):
            out.add(d["case"])
    return out


def _first_words(text: str, n: int = 24) -> str:
    words = text.split()
    return " ".join(words[:n]) + (" …" if len(words) > n else "")
