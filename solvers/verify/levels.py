"""Two levels of verdicts: printed formulas and the table cells they stand under.

A *formula* record judges one printed expression (a claim of the catalogue, or the project's
correction of it). A *cell* record judges the property a cell of Table 1 or 2 states, with
the best evidence the project has, in this order:

  1. the printed formula, if it holds (possibly under a stated convention, below);
  2. else the project's corrected formula, if it holds: the cell is `verified`, and the
     note "holds; printed formula corrected" sends the reader to the misprint;
  3. else a formula-free test of the property (a claim whose `establishes` names it);
  4. else the cell fails: the property itself is not supported.

So a red mark on a cell means the property fails, never only its printed formula.

Each formula record also gets a `qualifier` that says what kind of verdict it is:

  convention          verified: the printed form holds under the convention in `convention`
                      (the claim's `holds_under`), shown by the check of that reading; read
                      with the project's conventions it fails (residual kept in evidence)
  misprint            fails as printed; the project's correction is verified
  inherited           fails only because it uses the failing claim `inherits`, whose
                      correction makes it hold
  refuted-conjecture  the paper hedges ("probably does not exist"); the project answers it,
                      and `finding` names the object found
  refuted             a printed statement that fails with no correction the project could find
  formula-free        a project test of a cell's property that uses no printed formula
  None                nothing to qualify (verified as printed, evidence, unchecked)

Every record, formula and cell, also gets a `mark` from the vocabulary of marks.yaml (one
mark per meaning), with `mark_note` (one sentence: the convention, what an
inconclusive check found, the misprint) and `errata` (the formula records whose correction
holds, for "holds after correction"); `verdict` stays as it was for compatibility:

  as-printed        verified as printed (no qualifier)
  after-correction  misprint / inherited, or a project correction that holds
  under-convention  qualifier convention
  fails             refuted, refuted-conjecture, or a failing correction
  evidence-for      verdict evidence, or a verified formula-free test
  evidence-against  a failing formula-free test
  inconclusive      unchecked although a check ran (its message says what it found)
  open              check open_problem
  not-checkable     nothing ran (no formula printed, not decidable, not implemented)

A cell takes, over the claims it rests on, the first of: fails, evidence against,
inconclusive; else (ignoring open / not checkable claims) evidence for, after correction,
under a convention, as printed; else open, else not checkable. A cell of a table is judged
by the formula the table prints: where the text's display of the same formula differs
(a misprint in the text only), the cell lists the table's own claim.

Pure functions of the records and the catalogue: cheap, and the same for `rolling verify`,
its JSON and the API.
"""

from __future__ import annotations

from catalogue.schema import Case, Catalogue, RowKey
from solvers.verify import plain_notes

NEUTRAL_CHECKS = frozenset({"open_problem", "formula_not_printed", "not_checkable"})
CELL_NOTE = {"corrected": "holds; printed formula corrected",
             "formula-free": "holds; shown by a formula-free test (printed formula fails)",
             "formula-free-test": "confirmed by a formula-free test",
             "convention": "holds under a stated convention (see the mark's note)",
             "project": "holds with the project's derived formula (the paper prints none)"}
QUALIFIERS = ("convention", "misprint", "inherited", "refuted-conjecture", "refuted",
              "formula-free")


# How strong a record's check is, strongest first: a proof (an exact
# symbolic identity, an exact witness of a failure, the exact no-measure obstruction), an
# exact certificate (Schwartz-Zippel at rational points), a pointwise check with exact
# derivatives in floating point, evidence from trajectories. A cell's `rests_on` lists its
# records in this order (stable: a record stays next to its correction on ties).
PROOF_CHECKS = frozenset({"no_measure"})
TRAJECTORY_CHECKS = frozenset({"linear_integrals", "linear_integrals_return",
                               "negative_measure", "negative_integral", "permanent_rotations"})
STRENGTH = ("proof", "exact certificate", "pointwise", "trajectory")


def strength(rec: dict) -> int:
    """Index into STRENGTH of the check a record rests on."""
    ex = rec.get("exact") or {}
    if rec.get("check") in PROOF_CHECKS or ex.get("proved") or \
            (ex.get("negative") and ex.get("holds") is False and ex.get("witness")):
        return 0
    if ex.get("holds") is True and not ex.get("negative"):
        return 1
    return 3 if rec.get("check") in TRAJECTORY_CHECKS else 2


def _rank(rid: str, by_claim: dict) -> int:
    """strength of a record in a cell; a printed form that fails ranks with its correction,
    so the two stay side by side (printed first, the sort being stable)."""
    corr = by_claim.get(f"{rid}/corrected")
    own = strength(by_claim[rid])
    return min(own, strength(corr)) if corr is not None else own


def cell_id(case_id: str, row: str) -> str:
    return f"{case_id}/cell/{row}"


# --- formula records ---------------------------------------------------------------------

def annotate(records: list[dict], cat: Catalogue) -> list[dict]:
    """Set level, qualifier, convention, inherits and finding on every formula record
    (in place; returns the list)."""
    by_claim = {r["claim"]: r for r in records}
    claims = {cl.id: cl for cl in cat.claims()}
    for r in records:
        r.setdefault("level", "formula")
        for key in ("qualifier", "convention", "inherits", "finding"):
            r.setdefault(key, None)
        cl = claims.get(r["claim"])
        if cl is None:           # a project correction: judged by its own residual
            continue
        corr = by_claim.get(f"{cl.id}/corrected")
        corr_ok = corr is not None and corr["verdict"] == "verified"
        if cl.establishes:
            r["origin"] = "project-test"
            r["qualifier"] = "formula-free"
        elif r["verdict"] == "fails" and cl.holds_under and corr_ok:
            r["verdict"], r["qualifier"], r["convention"] = "verified", "convention", \
                cl.holds_under
            ev = dict(r.get("evidence") or {})
            ev["residual read with the project's convention"] = r["residual"]
            r["evidence"], r["residual"] = ev, corr["residual"]
            r["message"] = (f"holds under the convention: {cl.holds_under} (residual "
                            f"{corr['residual']:.1e}); read with the project's convention: "
                            + r["message"])
            # the exact certificate follows the verdict: the printed form read under the
            # convention is the correction's reading; the witness against our reading stays
            if r.get("exact") is not None and corr.get("exact") is not None:
                r["exact"] = {**corr["exact"], "under": "the convention above",
                              "read_with_project_convention": r["exact"]}
        elif r["verdict"] == "fails" and cl.hedged:
            r["qualifier"] = "refuted-conjecture"
            r["finding"] = (r.get("evidence") or {}).get("found density") or r["message"]
        elif r["verdict"] == "fails" and cl.inherits and corr_ok and \
                by_claim.get(cl.inherits, {}).get("verdict") == "fails":
            r["qualifier"], r["inherits"] = "inherited", cl.inherits
        elif r["verdict"] == "fails":
            r["qualifier"] = "misprint" if corr_ok else "refuted"
    for r in records:
        r["mark"], r["mark_note"], r["errata"] = formula_mark(r, claims.get(r["claim"]),
                                                              by_claim)
    return records


# --- marks -------------------------------------------------------------------------------

def _what(cl, r: dict) -> str:
    """The printed formula as a reader finds it: its label (printed number on the pages)."""
    label = r.get("label") or (cl.label if cl is not None else None)
    where = (cl.where or "") if cl is not None else ""
    if where.startswith("Table "):
        return f"the formula printed in {where.split(',')[0]}"
    if label:
        return f"the printed formula {label}"
    return f"the printed formula ({where})" if where else "the printed formula"


def _res(x) -> str:
    return f" (residual {x:.1e})" if isinstance(x, float) else ""


def formula_mark(r: dict, cl, by_claim: dict) -> tuple[str, str | None, list[str]]:
    """(mark, mark_note, errata) of one formula record, after `annotate`'s qualifiers (also
    of a record stored before marks existed, with cl None and by_claim empty)."""
    v, q = r["verdict"], r.get("qualifier")
    if r.get("origin") == "project-correction":
        if v == "verified":
            return ("after-correction", "the project's correction of a misprinted formula; "
                    "it holds", [r["corrects"]] if r.get("corrects") else [])
        return "fails", "the project's correction does not hold either", []
    if r.get("origin") == "project":     # the paper prints no formula: the project's own
        if v == "verified":
            level = (r.get("evidence") or {}).get("level of") \
                if r.get("check") == "hamiltonian_field_on_level" else None
            where = f" on the zero level of the integral {level} only" if level else ""
            return ("project-formula", "the paper asserts this without printing a formula; "
                    f"the project's derived formula holds{where}" + _res(r.get("residual")),
                    [])
        if v == "fails":
            return "fails", "the project's derived formula does not hold" + \
                _res(r.get("residual")), []
    if v == "verified":
        if q == "convention":
            return "under-convention", r.get("convention"), []
        if q == "formula-free":
            return "evidence-for", "a formula-free test along trajectories: " + \
                plain_notes.note(r, "evidence-for", _what(cl, r)), []
        return "as-printed", None, []
    if v == "fails":
        if q == "misprint":
            corr = by_claim.get(f"{r['claim']}/corrected") or {}
            printed = _res(r.get("residual")).replace(")", " as printed)")
            return ("after-correction", f"{_what(cl, r)} has a misprint{printed}; the "
                    f"project's correction holds{_res(corr.get('residual'))}", [r["claim"]])
        if q == "inherited":
            src = by_claim.get(r["inherits"]) or {}
            used = f"the printed formula {src['label']}" if src.get("label") else \
                "another printed formula"
            return ("after-correction", f"fails as printed only because it uses {used}, "
                    "which is misprinted; with that correction it holds",
                    [r["claim"], r["inherits"]])
        if q == "formula-free":
            return "evidence-against", "a formula-free test along trajectories: " + \
                plain_notes.note(r, "evidence-against", _what(cl, r)), []
        if q == "refuted-conjecture":
            return "fails", f"the paper doubts it exists; found: {r['finding']}", []
        return "fails", (f"{_what(cl, r)} does not hold{_res(r.get('residual'))} and the "
                         "project found no correction that does"), []
    if v == "evidence":     # the reader's note in plain words; the message stays as it is
        return "evidence-for", plain_notes.note(r, "evidence-for", _what(cl, r)), []
    # unchecked: did anything run?
    check, msg = r.get("check"), r.get("message") or ""
    if check == "open_problem":
        return "open", msg or None, []
    if check in NEUTRAL_CHECKS or msg.startswith("not implemented"):
        return "not-checkable", msg or None, []
    # what the check found, in plain words, without repeating the mark's own word
    return "inconclusive", plain_notes.note(r, "inconclusive", _what(cl, r)), []


# a cell's mark over its claims' marks: the first present of DECIDING, else of HOLDING
# (open / not checkable claims aside), else of NEUTRAL
DECIDING = ("fails", "evidence-against", "inconclusive")
HOLDING = ("evidence-for", "project-formula", "after-correction", "under-convention",
           "as-printed")
NEUTRAL = ("open", "not-checkable")


def combine(marks: list[str]) -> str:
    for m in (*DECIDING, *HOLDING, *NEUTRAL):
        if m in marks:
            return m
    return "not-checkable"


# --- cell records ------------------------------------------------------------------------

def _cell_claims(case: Case, cell) -> list[str]:
    own = [c for c in cell.claims if c.startswith(case.id + "/")]
    return own or list(cell.claims)


def _judge(cid: str, by_claim: dict, establishers: dict) -> tuple[str, str | None, list[str]]:
    """(effective verdict, basis, records it rests on) of one claim of a cell."""
    r = by_claim[cid]
    if r["verdict"] != "fails":
        basis = "convention" if r.get("qualifier") == "convention" else (
            "formula-free-test" if r.get("qualifier") == "formula-free" else
            "project" if r.get("origin") == "project" else "printed")
        return r["verdict"], basis, [cid]
    corr = by_claim.get(f"{cid}/corrected")
    if corr is not None and corr["verdict"] == "verified":
        return "verified", "corrected", [cid, corr["claim"]]
    free = [e for e in establishers.get(cid, []) if by_claim.get(e, {}).get("verdict")
            == "verified"]
    if free:
        return "verified", "formula-free", [cid, *free]
    return "fails", None, [cid]


def _claim_mark(r: dict, basis: str | None, on: list[str], by_claim: dict):
    """(mark, note, errata) of one claim as the cell uses it (see _judge)."""
    if basis == "corrected":
        note = r.get("mark_note") if r.get("mark") == "after-correction" else None
        return ("after-correction", note or "the printed formula has a misprint; the "
                "project's correction holds", r.get("errata") or [r["claim"]])
    if basis == "formula-free":
        tests = "; ".join(plain_notes.note(by_claim[x], "evidence-for", "the property")
                          for x in on[1:])
        return ("evidence-for", "the printed formula fails and no correction was found; a "
                f"formula-free test along trajectories shows the property: {tests}", [])
    return r["mark"], r.get("mark_note"), list(r.get("errata") or [])


def aggregate(judged: list[tuple[str, dict]]) -> str:
    verdicts = [v for v, _ in judged]
    if "fails" in verdicts:
        return "fails"
    if any(v == "unchecked" and r["check"] not in NEUTRAL_CHECKS for v, r in judged):
        return "unchecked"
    checked = [v for v in verdicts if v != "unchecked"]
    if not checked:
        return "unchecked"
    if all(v == "verified" for v in checked):
        return "verified"
    return "evidence" if all(v in ("evidence", "verified") for v in checked) else "unchecked"


def cell_records(records: list[dict], cat: Catalogue, case_ids=None) -> list[dict]:
    """One record per (case, row) whose cell lists claims, for the cases in case_ids (all
    if None) whose claims have records."""
    by_claim = {r["claim"]: r for r in records}
    establishers: dict[str, list[str]] = {}
    establishes: dict[str, list[str]] = {}
    for cl in cat.claims():
        for target in cl.establishes:
            establishers.setdefault(target, []).append(cl.id)
            establishes.setdefault(cl.id, []).append(target)
    out = []
    for table in cat.tables():
        rows = {r.key: r.plain for r in table.rows}
        for case in table.cases:
            if case_ids is not None and case.id not in case_ids:
                continue
            for row, cell in case.cells.items():
                ids = [c for c in _cell_claims(case, cell) if c in by_claim]
                if not ids:
                    continue
                judged, rests, bases, notes, marked = [], [], {}, [], []
                for c in ids:
                    v, basis, on = _judge(c, by_claim, establishers)
                    judged.append((v, by_claim[c]))
                    rests += [x for x in on if x not in rests]
                    if basis is not None:
                        bases[c] = basis
                    if basis in CELL_NOTE and CELL_NOTE[basis] not in notes:
                        notes.append(CELL_NOTE[basis])
                    marked.append(_claim_mark(by_claim[c], basis, on, by_claim))
                rests.sort(key=lambda x: _rank(x, by_claim))
                verdict = aggregate(judged)
                # a formula-free test of another claim of this cell is support for that
                # claim's property (already in its judgement), not one more condition: it
                # counts here only when it goes against (fails, evidence against, undecided)
                support = {c for c in ids if any(t in ids for t in establishes.get(c, ()))}
                mark = combine([m for (m, _, _), c in zip(marked, ids, strict=True)
                                if c not in support or m in DECIDING])
                mark_notes = [n for m, n, _ in marked if m == mark and n]
                if mark != "project-formula" and CELL_NOTE["project"] in notes:
                    # a project formula that holds beside an attempt that decides nothing
                    # (inconclusive): the cell does not "hold", its mark's note says what held
                    notes.remove(CELL_NOTE["project"])
                errata = [e for _, _, es in marked for e in es]
                failing = [c for (v, _), c in zip(judged, ids, strict=True) if v == "fails"]
                if verdict == "fails":
                    msg = "the property fails: " + ", ".join(failing)
                elif notes:
                    msg = "; ".join(notes)
                elif len(ids) == 1:
                    msg = by_claim[ids[0]]["message"]
                elif mark == "inconclusive":     # several claims, none "as printed"
                    msg = "inconclusive: " + "; ".join(dict.fromkeys(mark_notes))
                else:
                    msg = f"{verdict}: {len(ids)} claims, each as printed"
                out.append({
                    "case": case.id, "claim": cell_id(case.id, row.value), "kind": "cell",
                    "verdict": verdict, "residual": None, "printed": cell.plain,
                    "label": cell.labels[0] if cell.labels else None, "check": "cell",
                    "message": msg, "origin": "paper", "corrects": None,
                    "evidence": {"basis": bases} if bases else None, "seconds": 0.0,
                    "level": "cell", "row": row.value, "row_label": rows[row],
                    "rests_on": rests, "notes": notes, "qualifier": None, "mark": mark,
                    "mark_note": "; ".join(dict.fromkeys(mark_notes)) or None,
                    "errata": list(dict.fromkeys(errata)),
                    "convention": None, "inherits": None, "finding": None,
                    # a cell's exact certificates are those of the records it rests on
                    "exact": None})
    return out


# --- which claims a record id needs ------------------------------------------------------

def plan(cat: Catalogue, case: str | None, claim: str | None):
    """(claim ids to run, keep(record) -> bool, case ids of the cell records) for
    `verify(case, claim)`; claim may be any record id: a claim, `<claim>/corrected` or a
    cell `<case>/cell/<row>`. Raises KeyError for an unknown id."""

    cases = [c for c in cat.cases() if case in (None, c.id)]
    if claim is None:
        ids = [cl.id for c in cases for cl in c.claims]
        return ids, lambda r: True, {c.id for c in cases}
    owner = {cl.id: c for c in cat.cases() for cl in c.claims}
    if "/cell/" in claim:
        cid, row = claim.split("/cell/", 1)
        c = next((x for x in cases if x.id == cid), None)
        if c is None or row not in {k.value for k in RowKey} or \
                not c.cells[RowKey(row)].claims:
            raise KeyError(claim)
        base = _cell_claims(c, c.cells[RowKey(row)])
        keep_ids = {claim}
    else:
        base_id = claim.removesuffix("/corrected")
        if base_id not in owner or owner[base_id] not in cases:
            raise KeyError(claim)
        base, keep_ids = [base_id], {claim}
    need = list(base)
    for cid in base:                     # what the qualifiers and cells look at
        cl = owner[cid].claim(cid)
        need += [x for x in ([cl.inherits] if cl.inherits else []) if x not in need]
        need += [cl2.id for cl2 in owner[cid].claims if cid in cl2.establishes
                 and cl2.id not in need]
    if "/cell/" in claim:
        keep_ids |= set(need)
        return need, lambda r: r["claim"] in keep_ids, {claim.split("/cell/", 1)[0]}
    if claim == base[0]:                 # a claim id: the claim and its correction
        return need, lambda r: r["claim"] == claim or r.get("corrects") == claim, set()
    return need, lambda r: r["claim"] == claim, set()


def finish(raw: list[dict], cat: Catalogue, keep, cell_cases) -> list[dict]:
    """Annotate the formula records, add the cell records, keep what was asked for."""
    annotate(raw, cat)
    return [r for r in [*raw, *cell_records(raw, cat, cell_cases)] if keep(r)]
