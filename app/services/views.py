"""The catalogue and the case registry as the API shows them (plain dicts that the
response schemas validate): tables laid out like the paper, cases with their claims and
verdicts. Pure functions of (catalogue, registry, verdicts); cheap enough for the loop."""

from __future__ import annotations

import re
from functools import cache

from app.services.notation_page import case_formulas
from app.services.rubber_tables import rubber_table
from app.services.verdicts import VERDICTS, summary
from catalogue.load import load_catalogue, load_corrected_forms
from catalogue.notation import entry_for
from catalogue.numbering import cite, cite_latex, printed
from catalogue.plain_words import cite_names, phrases
from catalogue.schema import Attribution, Case, Cell, Claim, StateVariables, Table
from catalogue.since_2002 import note_json, notes_for
from catalogue.symbols import plain as plain_symbol
from catalogue.symbols import symbols as symbol_tokens
from solvers.models.bodies import STATE_LABELS
from solvers.models.cases import CaseSpec, beyond_table_ids, build, registry
from solvers.models.observables import RUBBER, rubber_integrals
from solvers.verify import marks as vocab
from solvers.verify.levels import formula_mark

UNCHECKED_MSG = "no verdict: the check has not run on this server (see /api/health, verification)"
PENDING_MSG = ("being checked now: this server is computing the verdicts of the cases whose "
               "catalogue entry or checking code changed (see /api/health, verification)")
SHOWN = (*VERDICTS, "pending")    # what a claim shows: a verdict, or pending (being checked)


def case_href(case_id: str) -> str:
    return f"/case/{case_id}"


@cache
def _references() -> dict:
    return {r.id: r for r in load_catalogue().references}


def attribution(a: Attribution) -> dict:
    ref = _references().get(a.ref)
    return {"ref": a.ref, "authors": a.authors, "year": a.year, "note": cite(a.note),
            "reference_authors": list(ref.authors) if ref else [],
            "reference_title": ref.title if ref else None}


def table_of(case_id: str) -> Table:
    cat = load_catalogue()
    return cat.plane if case_id.startswith("plane/") else cat.sphere


def symbol_refs(tex: str | None, text: bool = False) -> list[dict]:
    """The symbols of a formula as a page typesets it (catalogue/symbols.py), each with its
    entry on /notation; a symbol without an entry is left out (tests/test_notation.py
    keeps every symbol of a case page defined)."""
    out: list[dict] = []
    for token in symbol_tokens(tex or "", text):
        e = entry_for(token)
        if e is not None:
            out.append({"id": e.id, "tex": token, "text": plain_symbol(token),
                        "name": cite(e.name),
                        "href": f"/notation#sym-{e.id}"})
    return out


def page_notation(case: Case) -> list[dict]:
    """Every symbol of the formulas a case page can typeset (its cells, its claims and the
    project's corrected forms, notation_page.case_formulas), once per entry, in the page's
    order."""

    refs = [s for tex, text in case_formulas(case) for s in symbol_refs(tex, text)]
    seen: dict[str, dict] = {}
    for s in refs:
        seen.setdefault(s["id"], s)
    return list(seen.values())


def cell(row_label: str, row: str, c: Cell, by_claim: dict[str, dict],
         cases: list[str] | None = None, pending: set[str] | None = None) -> dict:
    # labels stay as data; what a reader sees carries the printed numbers (catalogue/numbering)
    return {"row": row, "row_label": row_label, "printed": cite_names(cite_latex(c.printed)),
            "plain": cite(c.plain), "shade": c.shade.value, "shade_note": cite(c.shade_note),
            "labels": list(c.labels), "numbers": [printed(x) or x for x in c.labels],
            "attribution": [attribution(a) for a in c.attribution],
            "merged": list(c.merged), "colspan": c.colspan,
            "subrow": c.subrow.model_dump() if c.subrow else None, "subrow_case": None,
            "claims": list(c.claims), "convention_note": cite(c.convention_note),
            "verdict": summary(list(c.claims), by_claim, row, cases or list(c.merged),
                               pending),
            "symbols": symbol_refs(c.printed + (" " + c.subrow.printed if c.subrow else ""),
                                   text=True)}


def table(table_id: str, by_claim: dict[str, dict], pending: set[str] | None = None) -> dict:
    """`pending`: the cases being checked now (VerdictStore.pending); their cells show
    "checking", not "not checkable"."""
    t: Table = getattr(load_catalogue(), table_id)
    labels = {r.key: r.plain for r in t.rows}
    grid = []
    for row in t.rows:
        cells, skip = [], set()
        for case in t.cases:
            if case.id in skip:
                continue
            c = case.cells[row.key]
            skip.update(c.merged)
            d = cell(labels[row.key], row.key.value, c, by_claim, list(c.merged) or [case.id],
                     pending)
            d["merged"] = list(c.merged) or [case.id]
            # a second line under one column of a merged cell (Table 2: a = 2R)
            for cid in d["merged"]:
                sub = next(x for x in t.cases if x.id == cid).cells[row.key].subrow
                if sub is not None:
                    d["subrow"], d["subrow_case"] = sub.model_dump(), cid
            cells.append(d)
        grid.append({"key": row.key.value, "cells": cells})
    out = {"id": t.id.value, "number": t.number, "caption_printed": t.caption_printed,
           "caption_plain": t.caption_plain, "remark_printed": t.remark_printed,
           "rows": [r.model_dump(mode="json") for r in t.rows],
           "columns": [{"id": c.id, "column": c.column, "title": c.title,
                        "href": case_href(c.id)} for c in t.cases],
           "grid": grid}
    out["mark_counts"] = table_cell_marks(out)
    out["summary"] = vocab.sentence(out["mark_counts"], "cell", "cells")
    return out


def _verdict(claim: Claim, rec: dict | None, pending: bool = False) -> dict:
    if rec is None:
        return {"claim": claim.id, "verdict": "pending" if pending else "unchecked",
                "residual": None, "message": PENDING_MSG if pending else UNCHECKED_MSG,
                "check": claim.check.value,
                "mark": "pending" if pending else "not-checkable",
                "mark_note": None if pending else "the check did not run on this server",
                "errata": []}
    return record(rec)


def _cite_all(x):
    """Every string inside x (evidence: nested dicts and lists) with printed numbers."""
    if isinstance(x, str):
        return cite(x)
    if isinstance(x, dict):
        return {k: _cite_all(v) for k, v in x.items()}
    if isinstance(x, list):
        return [_cite_all(v) for v in x]
    return x


_CORRECTION_OF = re.compile(r"\[project's correction of (\w+)\]\s*")


@cache
def corrected_forms() -> dict[str, str]:
    """fid -> the TeX of the project's corrected form (catalogue/corrected_forms.yaml)."""

    return {fid: cf.latex for fid, cf in load_corrected_forms().items()}


@cache
def _corrected_changes() -> dict[str, str]:
    """fid -> what the correction changes, in a reader's words (corrected_forms.yaml)."""

    return {fid: cf.change for fid, cf in load_corrected_forms().items()}


def record(rec: dict) -> dict:
    keys = ("claim", "verdict", "residual", "message", "check", "origin", "corrects",
            "evidence", "seconds", "printed", "computed_at", "version", "level", "qualifier",
            "convention", "inherits", "finding", "row", "rests_on", "notes", "exact")
    out = {k: rec.get(k) for k in keys if rec.get(k) is not None}
    # the texts a page shows (the mark's convention sentence, a finding, a cell's notes):
    # printed numbers, not labels (the Chaplygin convention named eq2b-*1)
    for k in ("message", "convention", "finding"):
        if k in out:
            out[k] = cite(out[k])
    if "notes" in out:
        out["notes"] = [cite(n) for n in out["notes"]]
    if "evidence" in out:
        out["evidence"] = _cite_all(out["evidence"])
    if "printed" in out:
        m = _CORRECTION_OF.match(out["printed"])
        if m and m[1] in corrected_forms():
            # a correction: its formula as TeX, the registered note as words
            out["printed_tex"] = corrected_forms()[m[1]]
            out["symbols"] = symbol_refs(out["printed_tex"])
            out["change"] = cite(_corrected_changes()[m[1]])
            out["printed"] = cite(out["printed"][m.end():])
        else:
            out["printed"] = cite_latex(out["printed"])
    if out.get("verdict") not in VERDICTS:
        out["verdict"] = "unchecked"
    if rec.get("mark") is None:       # a record stored before marks existed

        out["mark"], out["mark_note"], out["errata"] = formula_mark(
            {**rec, "verdict": out["verdict"]}, None, {})
    else:
        out["mark"], out["mark_note"] = rec["mark"], rec.get("mark_note")
        out["errata"] = list(rec.get("errata") or [])
    out["mark_note"] = cite(out["mark_note"])
    return out


def claim(c: Claim, by_claim: dict[str, dict], corrections: dict[str, list[dict]],
          pending: bool = False) -> dict:
    return {"id": c.id, "kind": c.kind.value, "printed": cite_names(cite_latex(c.printed)),
            "plain": cite(c.plain), "label": c.label, "number": printed(c.label),
            "where": cite(c.where),
            "attribution": [attribution(a) for a in c.attribution],
            "conditions": {k: cite(str(v)) for k, v in c.conditions.model_dump(
                mode="json", by_alias=True).items() if v is not None},
            "conditions_text": phrases(c.conditions.model_dump(mode="json", by_alias=True)),
            "variables": c.variables.value, "check": c.check.value,
            "check_args": {k: cite(v) if isinstance(v, str) else v for k, v in
                           c.check_args.model_dump(mode="json", exclude_defaults=True).items()},
            "convention_note": cite(c.convention_note), "remarks": cite(c.remarks),
            "verdict": _verdict(c, by_claim.get(c.id), pending),
            "corrections": [record(r) for r in corrections.get(c.id, [])],
            "symbols": symbol_refs(c.printed)}


def runnable(spec: CaseSpec) -> dict:

    model = build(spec.id, spec.example)
    params = [{"name": n, "required": True, "default": None,
               "example": spec.example.get(n)} for n in spec.required]
    params += [{"name": n, "required": False, "default": d, "example": spec.example.get(n)}
               for n, d in spec.optional.items()]
    return {"params": params, "example": dict(spec.example), "state": list(spec.state),
            "state_labels": list(STATE_LABELS[model.model]), "fixed_k": spec.fixed_k,
            "invariants_when": [i.model_dump() for i in spec.integrals]}


def case_summary(case: Case) -> dict:
    spec = registry()[case.id]
    return {"id": case.id, "title": case.title, "table": table_of(case.id).number,
            "column": case.column, "surface": spec.surface, "body": spec.body,
            "model_title": cite(spec.title), "href": case_href(case.id),
            "claims": len(case.claims), "in_tables": True, "note": None,
            "constraint": spec.constraint}


def beyond_summary(spec: CaseSpec) -> dict:
    """A runnable case that is no column of Tables 1-2 (the rattleback): no table, no
    column, no claims; its note says what it is instead."""
    return {"id": spec.id, "title": spec.title, "table": None, "column": None,
            "surface": spec.surface, "body": spec.body, "model_title": cite(spec.title),
            "href": case_href(spec.id), "claims": 0, "in_tables": False, "note": spec.note,
            "constraint": spec.constraint}


def case_summaries() -> list[dict]:
    """Every case: the columns of Tables 1 and 2 in the paper's order, then the runnable
    cases beyond the tables."""
    return ([case_summary(c) for c in load_catalogue().cases()]
            + [beyond_summary(registry()[cid]) for cid in beyond_table_ids()])


def is_case(case_id: str) -> bool:
    """A column of the tables or a runnable case beyond them."""
    return case_id in registry() and (not registry()[case_id].in_tables
                                      or _in_catalogue(case_id))


def _in_catalogue(case_id: str) -> bool:
    try:
        load_catalogue().case(case_id)
    except KeyError:
        return False
    return True


def _cited_model(case: Case) -> dict:
    m = case.model.model_dump(mode="json", by_alias=True)
    conds = m.get("conditions") or {}
    return {**m, "conditions": {k: cite(v) if isinstance(v, str) else v
                                for k, v in conds.items()},
            "conditions_text": phrases(conds)}


RUBBER_SENTENCE = (
    "Beyond the 2002 paper: this body rolls without slipping and without spinning about the "
    "normal, (ω, γ) = 0 (the rubber model). The paper's Tables 1 and 2 treat only rolling "
    "without slipping; the equations, their two derivations and the checks are the "
    "project's, with the literature each cell cites.")
RUBBER_EQUATIONS = "/guide/rubber/#equations"


def rubber_block(spec: CaseSpec) -> dict | None:
    """What a rubber case's page adds: that it is beyond the 2002 paper, where its equations
    are (the guide's docs/rubber.md), its cells in the rubber tables of the home page, and
    the quantities its run plots (solvers/models/observables.py RUBBER)."""
    if getattr(spec, "constraint", "marble") != "rubber":
        return None
    words = {m.id: f"{m.shape} {m.word}" for m in vocab.vocabulary()}
    cells = []
    table_id = f"rubber-{spec.surface}"
    for t in (rubber_table("rubber-plane"), rubber_table("rubber-sphere")):
        columns = {c["id"] for c in t["columns"] if c["model"] == spec.id}
        if columns:
            table_id = t["id"]
        plain = {r["key"]: r["plain"] for r in t["rows"]}
        cells += [{"case": c["case"], "row": c["row"], "row_words": plain[c["row"]],
                   "mark": words.get(c["mark"], c["mark"]),
                   "statement": c["plain"], "statement_tex": c["tex"],
                   "href": "/#" + c["anchor"]}
                  for row in t["grid"] for c in row["cells"] if c["case"] in columns]
    names = ["spin", "gamma_norm_defect", *rubber_integrals(spec.id, spec.example)]
    return {"sentence": RUBBER_SENTENCE, "equations_href": RUBBER_EQUATIONS,
            "table_href": f"/#tbl-{table_id}", "cells": cells,
            "quantities": [{"name": "energy", "label": "energy H = (M, ω)/2 + U"}]
            + [{"name": n, "label": RUBBER[n][0]} for n in names]}


def beyond_detail(spec: CaseSpec) -> dict:
    """A case beyond the tables as its page and GET /api/cases/{id} show it: what runs,
    and the note in place of cells and claims (nothing to check: verification done); a
    rubber case also its `rubber` block (rubber_block)."""
    run = runnable(spec)
    note = spec.note or "Not a case of the paper's Tables 1 and 2."
    return {**beyond_summary(spec), "rubber": rubber_block(spec),
            "model": {"support": spec.surface, "body": spec.body,
                      "state": (StateVariables.M_GAMMA.value if len(run["state_labels"]) == 6
                                else ", ".join(run["state_labels"])), "equations": [],
                      "equation_numbers": [], "conditions": {}, "conditions_text": []},
            "remarks": [note], "cells": [], "claims": [], "runnable": run,
            "verdicts": {v: 0 for v in SHOWN}, "marks": {}, "cell_marks": {},
            "summary": note, "verification": "done"}


def case_detail(case_id: str, by_claim: dict[str, dict], corrections: dict[str, list[dict]],
                verification: str) -> dict:
    spec = registry()[case_id]
    if not spec.in_tables:
        return beyond_detail(spec)
    case = load_catalogue().case(case_id)
    t = table_of(case_id)
    labels = {r.key: r.plain for r in t.rows}
    # "running" (VerdictStore.case_state): this case has no verdict yet and is being checked
    checking = verification == "running"
    claims = [claim(c, by_claim, corrections, checking) for c in case.claims]
    verdicts = [c["verdict"]["verdict"] for c in claims]
    cells = [cell(labels[r.key], r.key.value, case.cells[r.key], by_claim, [case_id],
                  {case_id} if checking else set()) for r in t.rows]
    claim_marks = vocab.counts(c["verdict"]["mark"] for c in claims)
    cell_marks = vocab.counts(c["verdict"]["mark"] for c in cells if c["verdict"])
    out = {**case_summary(case),
            "model": {**_cited_model(case),
                      "equation_numbers": [printed(x) or x for x in case.model.equations]},
            "remarks": [cite(r) for r in case.remarks],
            "cells": cells,
            "claims": claims,
            "runnable": runnable(registry()[case_id]),
            "verdicts": {v: verdicts.count(v) for v in SHOWN},
            "marks": claim_marks, "cell_marks": cell_marks,
            "summary": case_sentence(cell_marks, claim_marks),
            "since_2002": [note_json(n) for n in notes_for(case_id)],
            "verification": verification}
    out["notation"] = page_notation(case)
    return out


def case_sentence(cell_marks: dict[str, int], claim_marks: dict[str, int]) -> str:
    """'Of its 6 table cells, 4 hold as printed and 2 are open in the paper. Of its 11
    claims, ...': the counts by mark, never a bare 'verified'."""
    parts = []
    for counts, unit, units, its in ((cell_marks, "cell", "cells", "table cell"),
                                     (claim_marks, "claim", "claims", "claim")):
        n = sum(counts.values())
        if n:
            parts.append(f"Of its {n} {its}{'' if n == 1 else 's'}: "
                         f"{vocab.sentence(counts, unit, units)}.")
    return " ".join(parts)


def cells_sentence(counts: dict[str, int]) -> str:
    """The home page's summary over the cells of both tables."""
    n = sum(counts.values())
    if not n:
        return ""
    return (f"Of the {n} table cells with a claim (one per body and row): "
            f"{vocab.sentence(counts, 'cell', 'cells')}.")


def marks_overview(by_claim: dict[str, dict], pending: set[str] | None = None) -> dict:
    """GET /api/marks: the vocabulary, and the cells of both tables counted by mark."""
    counts = tables_cell_marks(table(tid, by_claim, pending) for tid in ("plane", "sphere"))
    return {"marks": [m.model_dump() for m in vocab.vocabulary()], "cells": counts,
            "cells_total": sum(counts.values()), "summary": cells_sentence(counts)}


def tables_cell_marks(tables) -> dict[str, int]:
    """The cells of several laid-out tables counted by mark (vocabulary order)."""
    counts: dict[str, int] = {}
    for t in tables:
        for k, n in t["mark_counts"].items():
            counts[k] = counts.get(k, 0) + n
    return {k: counts[k] for k in vocab.IDS if k in counts}


def table_cell_marks(t: dict) -> dict[str, int]:
    """The marks of a laid-out table's cells, one per body (merged cells count per body)."""
    return vocab.counts(m["mark"] for row in t["grid"] for c in row["cells"]
                        if c["verdict"] for m in c["verdict"]["marks"])
