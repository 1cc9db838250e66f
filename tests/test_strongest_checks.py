"""Issue 18, items 5 and 6: every cell rests on the strongest check the project has, listed
in that order, and the misprint verdicts read in the notation of their own section."""

from pathlib import Path

import pytest

from catalogue.load import load_catalogue
from solvers.verify import levels
from solvers.verify.run import verify

CAT = load_catalogue()
ROOT = Path(__file__).resolve().parents[1]
CHECK = {cl.id: cl.check.value for cl in CAT.claims()}


def test_strength_order():
    proof = {"check": "no_measure", "exact": None}
    witness = {"check": "integral_fails",
               "exact": {"holds": False, "negative": True, "witness": {"point": {}}}}
    cert = {"check": "integral", "exact": {"holds": True, "negative": False}}
    pointwise = {"check": "integral", "exact": None}
    traj = {"check": "linear_integrals", "exact": None}
    assert [levels.strength(r) for r in (proof, witness, cert, pointwise, traj)] == \
        [0, 0, 1, 2, 3]


def test_cell_rests_on_lists_the_strongest_first():
    """plane/body-of-revolution integrals: the exact reduced equations eq2.5 before the
    trajectory check of the two linear integrals, whatever the order of the records."""
    case = "plane/body-of-revolution"
    recs = [{"claim": f"{case}/integral/linear-pair", "verdict": "verified",
             "check": "linear_integrals", "exact": None, "qualifier": None},
            {"claim": f"{case}/reduction/linear", "verdict": "verified",
             "check": "reduced_agrees", "exact": {"holds": True, "negative": False},
             "qualifier": None}]
    for r in recs:      # the marks annotate() gives formula records (issue 17)
        r["mark"], r["mark_note"], r["errata"] = levels.formula_mark(r, None, {})
    cells = {r["row"]: r for r in levels.cell_records(recs, CAT, {case})}
    assert cells["integrals"]["rests_on"] == [f"{case}/reduction/linear",
                                              f"{case}/integral/linear-pair"]
    assert cells["integrals"]["verdict"] == "verified"


def test_cells_on_trajectory_checks_also_rest_on_exact_reduced_equations():
    """A cell with a linear-integrals trajectory check lists its case's reduced equations
    (reduced_agrees or solves_ode, which have exact certificates) as well."""
    for table in CAT.tables():
        for case in table.cases:
            for row, cell in case.cells.items():
                own = [c for c in cell.claims if c.startswith(case.id + "/")]
                if any(CHECK.get(c) == "linear_integrals" for c in own):
                    assert any(CHECK.get(c) in ("reduced_agrees", "solves_ode") for c in own), \
                        (case.id, row.value)


def test_generalizations_cells_cover_their_whole_statement():
    """'preserving one integral and measure': the integral is checked too (Kozlov's F3 holds
    on a sphere); 'one quadratic integral dependent on two linear ones': the dependence too."""
    gen = CAT.case("sphere/chaplygin-ball").cells
    ids = [c for row, cell in gen.items() if row.value == "generalizations" for c in cell.claims]
    # the paper prints no formula; the project's claim (branch hamsphere) carries the check
    assert "sphere/chaplygin-ball/brun/integral/project" in ids
    assert CHECK["sphere/chaplygin-ball/brun/integral/project"] == "integral"
    routh = [c for row, cell in CAT.case("sphere/routh-ball").cells.items()
             if row.value == "generalizations" for c in cell.claims]
    assert "sphere/routh-ball/identity/F2F3" in routh
    recs = verify(claim="sphere/chaplygin-ball/brun/integral/project")
    assert recs[0]["verdict"] == "verified" and recs[0]["exact"]["holds"] is True


@pytest.mark.parametrize("claim_id", [
    "plane/round-disk/reduction/linear-theta",          # eq2.8: K1 = w3/rho labels (eq2.15)
    "sphere/body-of-revolution/identity/rho0-forms",    # eq3.2: r3 = g3 f2 (Table 2)
    "sphere/routh-ball/measure/table-form",             # Table 2: r3 = g3 f2, f1 = R
])
def test_audited_misprints_hold_in_their_sections_notation(claim_id):
    recs = {r["claim"]: r for r in verify(claim=claim_id)}
    r = recs[claim_id]
    assert r["verdict"] == "verified" and r["qualifier"] == "convention", r["message"]
    assert r["evidence"]["residual read with the project's convention"] > 1e-3
    assert CAT.claim(claim_id).holds_under


def test_audit_table_lists_every_record():
    text = (ROOT / "docs" / "misprint-audit.md").read_text()
    for cid in ("plane/round-disk/reduction/linear-theta",
                "sphere/body-of-revolution/identity/rho0-forms",
                "sphere/routh-ball/measure/table-form",
                "sphere/body-of-revolution/measure", "plane/ellipsoid/stationary/karapetyan"):
        assert f"`{cid}`" in text
    from catalogue.numbering import cite
    assert cite("eq2.8") in text and "eq2.8" not in text
