"""The documents of the explorer's search (search.py indexes them): one per case, claim,
teaching scene and glossary entry, and one per erratum, convention and finding of the
verdicts; each with its facets, its public fields and its text columns (`_cols`: title,
text, context, names, tags, the order of search.COLUMNS).
"""

from __future__ import annotations

import re

from app.services import views
from app.services.anchors import claim_anchor
from catalogue.glossary import load_glossary
from catalogue.load import load_catalogue
from catalogue.numbering import cite, printed
from solvers.models.cases import beyond_table_ids, registry
from solvers.scenes.teaching import load_scenes
from solvers.verify import errata as er


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


def case_docs() -> list[dict]:
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


def claim_docs() -> list[dict]:
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


def scene_docs() -> list[dict]:
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


def glossary_docs() -> list[dict]:
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


def verdict_docs(records: list[dict]) -> list[dict]:
    """The rows GET /api/errata, /api/conventions and /api/findings list, from the
    verdicts computed so far."""

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
