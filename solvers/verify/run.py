"""`verify(case=None)`: run the check of every claim of the catalogue and return records."""

import time
from dataclasses import asdict, dataclass

import numpy as np

from catalogue.load import load_catalogue
from solvers.errors import InputError
from solvers.verify import (
    checks,  # noqa: F401  (registers the checks)
    formulas,  # noqa: F401  (registers the formulas)
    levels,
)
from solvers.verify.checks.common import TOL
from solvers.verify.exact.certifiers import exact_for
from solvers.verify.registry import CHECKS, CORRECTED, CORRECTION_NOTES, Outcome

VERDICTS = ("verified", "fails", "evidence", "unchecked")


@dataclass
class Record:
    case: str
    claim: str
    kind: str
    verdict: str
    residual: float | None
    printed: str
    label: str | None
    check: str
    message: str
    origin: str = "paper"              # paper | project | project-correction
    corrects: str | None = None        # for a correction: the claim it corrects
    evidence: dict | None = None
    seconds: float = 0.0
    exact: dict | None = None          # exact certificate or witness (solvers/verify/exact)

    def to_json(self) -> dict:
        d = asdict(self)
        if d["residual"] is not None and not np.isfinite(d["residual"]):
            d["residual"] = None
            d["message"] += " (residual not finite)"
        return d


def run_claim(catalogue, case, claim) -> list[Record]:
    t0 = time.perf_counter()
    fn = CHECKS.get(claim.check.value)
    try:
        if fn is None:
            raise LookupError(f"no check registered under {claim.check.value!r}")
        out = fn(catalogue, case, claim)
    except LookupError as e:      # a formula or check not implemented: say so, honestly
        out = Outcome("unchecked", None, f"not implemented: {e}")
    rec = Record(case.id, claim.id, claim.kind.value, out.verdict, out.residual, claim.printed,
                 claim.label, claim.check.value, out.message, origin=claim.origin.value,
                 evidence=out.evidence or None, seconds=time.perf_counter() - t0)
    rec.exact = exact_for(catalogue, case, claim)
    records = [rec]
    args = claim.check_args          # the corrected object: the first with a correction
    fid = next((f for f in (args.formula, args.system, args.bracket) if f in CORRECTED), None)
    if out.verdict == "fails" and out.corrected_residual is not None and fid in CORRECTED:
        ok = out.corrected_residual <= TOL
        records.append(Record(
            case.id, f"{claim.id}/corrected", claim.kind.value,
            "verified" if ok else "fails", out.corrected_residual,
            f"[project's correction of {fid}] {CORRECTION_NOTES[fid]}", claim.label,
            claim.check.value,
            f"corrected form: max normalised residual {out.corrected_residual:.2e}",
            origin="project-correction", corrects=claim.id,
            exact=exact_for(catalogue, case, claim, corrected=True)))
    return records


def verify(case: str | None = None, claim: str | None = None) -> list[dict]:
    """Check the paper's claims (the catalogue) and return one record per verdict.

    Each claim of the catalogue (a printed formula, integral, invariant measure,
    Hamiltonian form, reduction or statement of nonexistence of Tables 1-2 and their
    sections) is checked by computation; the table cells get records of their own, judged
    on the best evidence (solvers/verify/levels.py).

    Parameters
    ----------
    case : str or None, default None
        Only the claims and cells of this case (a key of `cases()` with
        `CaseSpec.in_tables`); None: every case.
    claim : str or None, default None
        Only this record id: a claim id such as "plane/chaplygin-ball/measure", the
        project's correction of one, "<claim>/corrected", or a table cell,
        "<case>/cell/<row>" (a cell record comes with the formula records it rests on).

    Returns
    -------
    list of dict
        JSON-ready records with at least "case", "claim" (the record id), "kind",
        "verdict" ("verified", "fails", "evidence" or "unchecked"), "residual" (the
        largest normalised residual, or None), "printed" (the LaTeX as printed), "label"
        (the paper's equation number), "level" ("formula" or "cell"), "qualifier" and
        "mark" (what kind of verdict it is, e.g. "as-printed", "after-correction",
        "fails"), "mark_note" and "message".

    Raises
    ------
    InputError
        An unknown case or record id.

    Examples
    --------
    The invariant measure of the Chaplygin ball, eq2.17, holds as printed; the reduction
    of the Borisov-Fedorov case to the Chaplygin sphere as printed, eq3.13, does not:

    >>> import solvers
    >>> (measure,) = solvers.verify(claim="plane/chaplygin-ball/measure")
    >>> measure["label"], measure["verdict"], measure["mark"], float(measure["residual"]) < 1e-10
    ('eq2.17', 'verified', 'as-printed', True)
    >>> (reduction,) = solvers.verify(claim="sphere/borisov-fedorov/reduction/to-chaplygin")
    >>> reduction["label"], reduction["verdict"], reduction["qualifier"]
    ('eq3.13', 'fails', 'refuted')
    """

    cat = load_catalogue()
    ids, keep, cell_cases = resolve(cat, case, claim)
    owner = {cl.id: c for c in cat.cases() for cl in c.claims}
    raw = [r.to_json() for cid in ids for r in run_claim(cat, owner[cid], owner[cid].claim(cid))]
    return levels.finish(raw, cat, keep, cell_cases)


def resolve(cat, case: str | None, claim: str | None):
    """levels.plan with clear errors for an unknown case or record id."""

    known = [c.id for c in cat.cases()]
    if case is not None and case not in known:
        raise InputError(f"unknown case {case!r}; known cases: {', '.join(known)}")
    try:
        return levels.plan(cat, case, claim)
    except KeyError:
        where = f" in case {case!r}" if case else ""
        raise InputError(f"unknown record id {claim!r}{where}: give a claim id, "
                         "<claim>/corrected or <case>/cell/<row>") from None
