"""Issue 10: two levels of verdicts, the new verdict kinds, the formula-free gyrostat check,
errata and findings. One full `verify` per test session (the `catalogue_records` fixture,
both cores), then pure checks on it."""

import copy
import io

import pytest

from catalogue.load import load_catalogue
from solvers.verify import errata as er
from solvers.verify import levels
from solvers.verify.checks.common import TOL

CAT = load_catalogue()
GYRO_FREE = [f"{c}/gyrostat/linear-integrals/formula-free"
             for c in ("sphere/body-of-revolution", "sphere/round-disk", "sphere/routh-ball")]


@pytest.fixture(scope="module")
def records(catalogue_records):
    return copy.deepcopy(catalogue_records)


@pytest.fixture(scope="module")
def by(records):
    return {r["claim"]: r for r in records}


def test_one_case_is_the_full_run_s(catalogue_records):
    """The modules that read one case's records from the session's full run
    (conftest.records_of) read what `verify(case=...)` gives: the same records in the same
    order, all fields equal but the time each check took."""
    from conftest import records_of

    from solvers.verify.run import verify

    case = "plane/unbalanced-ball"
    alone = verify(case=case)
    full = records_of(catalogue_records, [case])
    assert [r["claim"] for r in alone] == [r["claim"] for r in full]
    for a, b in zip(alone, full, strict=True):     # repr: a NaN residual equals itself
        assert {k: repr(v) for k, v in a.items() if k != "seconds"} == \
            {k: repr(v) for k, v in b.items() if k != "seconds"}, a["claim"]


# --- the two levels ----------------------------------------------------------------------

def test_every_record_has_a_level_and_old_ids_are_kept(records, by):
    assert {r["level"] for r in records} == {"cell", "formula"}
    for cl in CAT.claims():                        # every claim keeps its record id
        assert cl.id in by and by[cl.id]["level"] == "formula"
    cells = [r for r in records if r["level"] == "cell"]
    for r in cells:
        assert r["claim"] == levels.cell_id(r["case"], r["row"]) and r["rests_on"]
        assert all(x in by for x in r["rests_on"])


def test_no_table_cell_shows_a_cross(records):
    """Every cell property holds (or is evidence / not checkable): no ✗ in the cell
    records nor in the terminal tables."""
    from rich.console import Console

    import app.cli.checks

    failing = [r["claim"] for r in records if r["level"] == "cell" and r["verdict"] == "fails"]
    assert failing == []
    buf = io.StringIO()
    orig = Console.__init__

    def to_buffer(self, *a, **k):          # verify_tables makes its own Console
        orig(self, *a, **{**k, "file": buf})
    Console.__init__ = to_buffer
    try:
        app.cli.checks.verify_tables(records, None)
    finally:
        Console.__init__ = orig
    text = buf.getvalue()
    # the first line is the key to the marks (issue 17), which names ✗ fails itself
    legend, tables = text.split("\ncells: ")[0].split("\n", 1)
    assert legend.startswith("marks: ✓ holds as printed")
    assert "Table 1" in tables and "Table 2" in tables and "✗" not in tables
    # issue 17: the cell's mark says what was shown: after correction, with its erratum
    assert "✎ holds after correction: cell sphere/round-disk/cell/gyrostat: " in text
    # its errata: the reduced equations it now also rests on (issue 18) and the integrals
    flat = " ".join(text.split())             # the console wraps long lines
    assert "(errata: sphere/round-disk/reduction/gyrostat, " \
        "sphere/round-disk/gyrostat/linear-integrals" in flat


def test_misprints_still_fail_with_their_correction_verified(records, by):
    misprints = [r for r in records if r.get("qualifier") == "misprint"]
    assert len(misprints) >= 20
    for r in misprints:
        assert r["verdict"] == "fails" and r["residual"] > TOL
        corr = by[r["claim"] + "/corrected"]
        assert corr["verdict"] == "verified" and corr["residual"] <= TOL


def test_cells_over_misprints_are_verified_with_the_note(by):
    for case in ("sphere/body-of-revolution", "sphere/round-disk", "sphere/routh-ball"):
        for row in ("measure", "gyrostat"):
            cell = by[f"{case}/cell/{row}"]
            assert cell["verdict"] == "verified", cell
            if (case, row) == ("sphere/routh-ball", "measure"):
                # issue 18 audit: Table 2's density holds for the ball in the table's own
                # notation r3 = gamma3 f2 (holds_under), no longer a misprint
                assert levels.CELL_NOTE["convention"] in cell["notes"]
                continue
            assert "holds; printed formula corrected" in cell["notes"]
        assert by[f"{case}/cell/gyrostat"]["evidence"]["basis"][
            f"{case}/gyrostat/linear-integrals"] == "corrected"
        assert f"{case}/gyrostat/linear-integrals/formula-free" in \
            by[f"{case}/cell/gyrostat"]["rests_on"]
    cid = "plane/routh-ball/cell/gyrostat"
    assert by[cid]["verdict"] == "verified" and by[cid]["notes"] == [
        "holds; printed formula corrected"]
    # issue 17: the spherical-inertia measure cell rests on Table 1's printed formula, which
    # holds as printed (only the text's display drops m); it no longer needs a correction
    cid = "plane/spherical-inertia/cell/measure"
    assert by[cid]["verdict"] == "verified" and by[cid]["notes"] == []
    assert by[cid]["mark"] == "as-printed"
    ham = by["plane/chaplygin-ball/cell/hamiltonian_form"]
    assert ham["verdict"] == "verified" and ham["evidence"]["basis"][
        "plane/chaplygin-ball/hamiltonian-after-time-change"] == "convention"


# --- the new verdict kinds: where they must and must not come out --------------------------

def test_convention_comes_out_only_where_declared(by):
    for cid in ("plane/chaplygin-ball/hamiltonian-after-time-change",
                "plane/chaplygin-ball/hamiltonian-after-time-change/K"):
        r = by[cid]
        assert r["verdict"] == "verified" and r["qualifier"] == "convention"
        assert "{H, x}" in r["convention"] and r["residual"] <= TOL
        assert r["evidence"]["residual read with the project's convention"] > 1
    # a failing bracket check with no convention declared stays a misprint
    assert by["plane/body-of-revolution/poisson/antigradient"]["qualifier"] == "misprint"
    assert by["plane/body-of-revolution/poisson/antigradient"]["verdict"] == "fails"


def test_convention_needs_the_convention_reading_to_hold():
    recs = [{"claim": "plane/chaplygin-ball/hamiltonian-after-time-change", "verdict": "fails",
             "residual": 2.0, "message": "m", "check": "hamiltonian_field", "evidence": None},
            {"claim": "plane/chaplygin-ball/hamiltonian-after-time-change/corrected",
             "verdict": "fails", "residual": 0.5, "message": "m", "check": "x",
             "origin": "project-correction"}]
    levels.annotate(recs, CAT)
    assert recs[0]["verdict"] == "fails" and recs[0]["qualifier"] == "refuted"


def test_inherited_failures(by):
    r = by["sphere/flat-base-axisymmetric/reduction/solution"]
    assert r["qualifier"] == "inherited" and r["verdict"] == "fails"
    assert r["inherits"] == "sphere/flat-base-axisymmetric/reduction/linear"
    assert r["evidence"]["printed solution, corrected ODE"] <= TOL   # only the ODE is wrong
    assert by["sphere/flat-base-axisymmetric/gyrostat/quadratic"]["inherits"] == \
        "sphere/flat-base-axisymmetric/gyrostat/particular"
    # the source itself is a misprint, not inherited
    src = by["sphere/flat-base-axisymmetric/reduction/linear"]
    assert src["qualifier"] == "misprint" and src["inherits"] is None


def test_inherited_needs_the_source_to_fail(records):
    recs = copy.deepcopy([r for r in records if r["case"] == "sphere/flat-base-axisymmetric"
                          and r["level"] == "formula"])
    for r in recs:
        r["qualifier"] = r["inherits"] = None
        if r["claim"] == "sphere/flat-base-axisymmetric/reduction/linear":
            r["verdict"] = "verified"           # pretend the linear system held
    levels.annotate(recs, CAT)
    sol = next(r for r in recs if r["claim"] == "sphere/flat-base-axisymmetric/reduction/solution")
    assert sol["qualifier"] == "misprint" and sol["inherits"] is None


def test_refuted_conjecture(by):
    r = by["plane/spherical-inertia/negative/sphere-generalization"]
    assert r["qualifier"] == "refuted-conjecture" and "det(E - k J)" in r["finding"]
    # hedged claims the project only gathers evidence for are not refuted conjectures
    hedged = {cl.id for cl in CAT.claims() if cl.hedged}
    assert len(hedged) >= 10
    # (issue 18: the absence of a measure is now proved exactly, check no_measure)
    assert by["plane/unbalanced-ball/negative/measure"]["verdict"] == "verified"
    assert by["plane/unbalanced-ball/negative/measure"]["qualifier"] is None
    for rid, rec in by.items():
        if rec.get("qualifier") == "refuted-conjecture":
            assert rid in hedged
    assert by["sphere/borisov-fedorov/reduction/to-chaplygin"]["qualifier"] == "refuted"
    # refuted only where no correction holds
    for rid, rec in by.items():
        if rec.get("qualifier") == "refuted":
            assert by.get(rid + "/corrected", {}).get("verdict") != "verified"


def test_refuted_conjecture_needs_a_failure():
    recs = [{"claim": "plane/spherical-inertia/negative/sphere-generalization",
             "verdict": "evidence", "residual": 0.1, "message": "m", "check": "negative_measure",
             "evidence": {}}]
    levels.annotate(recs, CAT)
    assert recs[0]["qualifier"] is None and recs[0]["finding"] is None


# --- formula-free existence check ------------------------------------------------------------

def test_formula_free_gyrostat_checks_hold_and_their_control_breaks(by):
    for cid in GYRO_FREE:
        r = by[cid]
        assert r["verdict"] == "verified" and r["qualifier"] == "formula-free", r
        ev = r["evidence"]
        assert ev["max spread of (M, gamma), M3 at crossings / scale"] <= TOL
        assert ev["control: max spread"] > 1e3 * TOL and ev["crossings"] >= 20


def test_formula_free_check_fails_off_axis():
    """The same check with the gyrostat off the axis: the returns break, so the check can
    fail (run here directly on the control's parameters)."""
    from solvers.verify.checks.formula_free import CONTROL_BREAKS, return_spreads

    case = CAT.case("sphere/routh-ball")
    claim = case.claim(GYRO_FREE[2])
    spread, n, runs = return_spreads(case, claim, control=True)
    assert runs > 0 and n > 0 and spread > CONTROL_BREAKS


def test_cell_rescued_only_by_a_verified_formula_free_test(records):
    recs = copy.deepcopy([r for r in records if r["case"] == "sphere/round-disk"
                          and r["level"] == "formula"])
    for r in recs:
        if r["claim"] == "sphere/round-disk/gyrostat/linear-integrals/corrected":
            r["verdict"] = "fails"                 # without the correction ...
    cell = next(c for c in levels.cell_records(recs, CAT, {"sphere/round-disk"})
                if c["row"] == "gyrostat")
    assert cell["verdict"] == "verified" and levels.CELL_NOTE["formula-free"] in cell["notes"]
    # (issue 18: the cell also rests on the exact reduced equations eq3.10, corrected, so the
    # "corrected" note stays; the linear integrals themselves rest on the formula-free test)
    assert cell["evidence"]["basis"]["sphere/round-disk/gyrostat/linear-integrals"] == \
        "formula-free"
    for r in recs:
        if r["claim"] == GYRO_FREE[1]:
            r["verdict"] = "fails"                 # ... and without the formula-free test
    cell = next(c for c in levels.cell_records(recs, CAT, {"sphere/round-disk"})
                if c["row"] == "gyrostat")
    assert cell["verdict"] == "fails"


# --- any record id reproduces ---------------------------------------------------------------

def test_claim_option_takes_any_record_id():
    from solvers.errors import InputError
    from solvers.verify import verify

    recs = verify(claim="sphere/routh-ball/cell/gyrostat")
    assert recs[-1]["claim"] == "sphere/routh-ball/cell/gyrostat"
    assert recs[-1]["verdict"] == "verified"
    (corr,) = verify(claim="plane/routh-ball/gyrostat/bobylev/corrected")
    assert corr["verdict"] == "verified" and corr["origin"] == "project-correction"
    (conv, _) = verify(claim="plane/chaplygin-ball/hamiltonian-after-time-change")
    assert conv["qualifier"] == "convention"
    with pytest.raises(InputError, match="unknown record id"):
        verify(claim="plane/ball/cell/nope")


# --- errata and findings ----------------------------------------------------------------------

def test_errata_and_findings(records, by):
    ers = er.errata(records, CAT)
    assert {e["claim"] for e in ers} == {r["claim"] for r in records
                                         if r.get("qualifier") in ("misprint", "inherited")}
    for e in ers:
        assert e["printed"] and e["corrected"] and e["corrected_verdict"] == "verified"
        assert e["residual_printed"] > TOL >= e["residual_corrected"]
        assert e["reproduce"] == f"rolling verify --claim {e['claim']} --json"
        assert e["label"] or e["where"]
    f = {e["claim"]: e for e in er.findings(records, CAT)}
    refuted = {c for c, e in f.items() if e["kind"] != "inconclusive"}
    assert refuted == {"plane/spherical-inertia/negative/sphere-generalization",
                       "sphere/borisov-fedorov/reduction/to-chaplygin",
                       # issue 18: no smooth measure for the general ellipsoid, proved
                       "plane/ellipsoid/negative/general-measure"}
    # issue 17: the negative checks that ran and could not decide are findings too
    assert set(f) - refuted == {r["claim"] for r in records if er.is_inconclusive(r)}
    assert all(f[c]["leans"] == "against the paper" for c in set(f) - refuted)
    assert "det(E - k J)" in f["plane/spherical-inertia/negative/sphere-generalization"][
        "finding"]
    assert f["sphere/borisov-fedorov/reduction/to-chaplygin"]["evidence"]["rate |M~|^2"] > 1e-3
    conv = er.conventions(records, CAT)
    # the bracket orientation (2) and, from the issue 18 audit, eq2.8's labels, the second
    # form of rho0 in eq3.2 and the Routh ball's Table 2 density (r3 = gamma3 f2)
    assert len(conv) == 5 and all(c["residual_under_convention"] <= TOL for c in conv)


def test_api_errata_tables_and_page(records):
    from fastapi.testclient import TestClient

    from app.main import create_app
    from app.testing import settings_for_tests

    app = create_app(settings_for_tests(verify_on_start=False))
    with TestClient(app) as client:
        store = app.state.verdicts
        for cid in store.case_ids:
            store.records[cid] = [r for r in records if r["case"] == cid]
        errata = client.get("/api/errata").json()
        assert errata and all({"claim", "printed", "corrected"} <= set(e) for e in errata)
        found = client.get("/api/findings").json()
        # + the ellipsoid (issue 18)
        assert len([e for e in found if e["kind"] in ("refuted", "refuted-conjecture")]) == 3
        assert "figure/ris-4" in {e["claim"] for e in found}        # Fig. 7's caption
        for tid in ("plane", "sphere"):
            t = client.get(f"/api/tables/{tid}").json()
            for row in t["grid"]:
                for cell in row["cells"]:
                    v = cell["verdict"]
                    if v is None:
                        continue
                    assert v["mark"] != "fails" and v["verdict"] != "fails"
                    assert [m["case"] for m in v["marks"]] == cell["merged"]
                    assert all(m["mark"] != "fails" for m in v["marks"])
        case = client.get("/api/cases/sphere/round-disk").json()
        claims = {c["id"]: c for c in case["claims"]}
        assert claims[GYRO_FREE[1]]["verdict"]["qualifier"] == "formula-free"
        gyro = next(c for c in case["cells"] if c["row"] == "gyrostat")
        assert gyro["verdict"]["marks"][0]["verdict"] == "verified"
        assert gyro["verdict"]["marks"][0]["mark"] == "after-correction"
        page = client.get("/errata")
        assert page.status_code == 200 and "errata.js" in page.text
        assert "/api/errata" in client.get("/openapi.json").json()["paths"]
        assert 'href="/errata"' in client.get("/").text
        assert 'href="/errata"' in client.get("/case/sphere/round-disk").text
