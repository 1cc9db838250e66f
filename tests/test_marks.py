"""Issue 17, items 1-2 and the spherical-inertia note: one mark per meaning, computed in one
place (solvers/verify/levels.py) from one vocabulary (solvers/verify/marks.yaml), on the
real records of `rolling verify` for the cases that carry every kind of mark; the API,
/how-we-check and the CLI say the same marks."""

import copy
import html
import io
import re
import typing

import pytest
from conftest import records_of

from catalogue.load import load_catalogue
from solvers.verify import levels
from solvers.verify import marks as vocab
from solvers.verify.checks.common import TOL

CAT = load_catalogue()
# every mark but evidence-against (no record carries it today) comes out of these cases
CASES = ("plane/spherical-inertia", "plane/chaplygin-ball", "sphere/round-disk",
         "sphere/borisov-fedorov", "sphere/chaplygin-ball")


@pytest.fixture(scope="module")
def records(catalogue_records):
    return copy.deepcopy(records_of(catalogue_records, CASES))


@pytest.fixture(scope="module")
def by(records):
    return {r["claim"]: r for r in records}


# --- the vocabulary ------------------------------------------------------------------------

def test_one_vocabulary_with_distinct_shapes_and_words():
    marks = vocab.vocabulary()
    assert [m.id for m in marks] == ["as-printed", "after-correction", "under-convention",
                                     "project-formula", "fails", "evidence-for", "evidence-against",
                                     "inconclusive", "open", "not-checkable", "pending"]
    for attr in ("shape", "word", "name"):          # told apart without colour
        assert len({getattr(m, attr) for m in marks}) == len(marks), attr
    from app.schemas.verify import MarkId
    assert set(typing.get_args(MarkId)) == set(vocab.IDS)     # the API says the same ids


def test_summary_sentence():
    s = vocab.sentence({"as-printed": 3, "after-correction": 1, "open": 2}, "cell", "cells")
    assert s == ("3 cells hold as printed, 1 holds after correction and 2 are open in the "
                 "paper")
    assert vocab.sentence({"fails": 1}, "claim", "claims") == "1 claim fails"
    assert vocab.sentence({}, "cell", "cells") == ""


# --- marks on the real records -------------------------------------------------------------

def test_every_record_has_a_mark_from_the_vocabulary(records):
    seen = set()
    for r in records:
        assert r["mark"] in vocab.VERDICT_MARKS, r["claim"]
        assert isinstance(r["errata"], list)
        seen.add(r["mark"])
    assert seen == set(vocab.VERDICT_MARKS) - {"evidence-against"}, seen


def test_marks_agree_with_the_coarse_verdicts(records):
    holds = {"as-printed", "after-correction", "under-convention", "evidence-for",
             "project-formula"}
    for r in records:
        v, m = r["verdict"], r["mark"]
        if m == "as-printed":
            assert v == "verified" and r.get("qualifier") is None, r["claim"]
            if r["level"] == "formula":
                assert r["origin"] == "paper" and r["residual"] <= TOL, r["claim"]
        if m in ("inconclusive", "open", "not-checkable"):
            assert v == "unchecked", r["claim"]
        if v == "verified":
            assert m in holds, r["claim"]


def test_misprint_holds_after_correction_and_links_its_erratum(by):
    r = by["sphere/round-disk/measure"]
    assert r["verdict"] == "fails" and r["qualifier"] == "misprint"       # kept as it was
    assert r["mark"] == "after-correction" and r["errata"] == ["sphere/round-disk/measure"]
    assert by["sphere/round-disk/measure/corrected"]["verdict"] == "verified"
    assert "misprint" in r["mark_note"]
    # inherited: holds after correction of the formula it uses, both errata linked
    r = by["sphere/round-disk/gyrostat/linear-integrals"]
    assert r["qualifier"] == "inherited" and r["mark"] == "after-correction"
    assert r["errata"] == [r["claim"], r["inherits"]]


def test_the_chaplygin_convention_names_one_orientation(by):
    for cid in ("plane/chaplygin-ball/hamiltonian-after-time-change",
                "plane/chaplygin-ball/hamiltonian-after-time-change/K",
                "plane/chaplygin-ball/cell/hamiltonian_form"):
        r = by[cid]
        assert r["mark"] == "under-convention", cid
        note = r["mark_note"]
        # the convention under which it holds is dx/dtau = {H, x}; {x, H} is named only as
        # what gives the time-reversed field, and nothing is "the paper's own convention"
        assert note.startswith("the orientation dx/dτ = {H, x} of the bracket")
        assert note.index("dx/dτ = {H, x}") < note.index("dx/dτ = {x, H}")
        assert "time-reversed" in note and "own convention" not in note
    corr = by["plane/chaplygin-ball/hamiltonian-after-time-change/corrected"]
    assert "own convention" not in corr["printed"] and "{x, H}" in corr["printed"]


def test_fails_open_and_not_checkable(by):
    assert by["sphere/borisov-fedorov/reduction/to-chaplygin"]["mark"] == "fails"
    r = by["plane/spherical-inertia/negative/sphere-generalization"]
    assert r["qualifier"] == "refuted-conjecture" and r["mark"] == "fails"
    assert by["plane/spherical-inertia/negative/hamiltonian"]["mark"] == "open"
    assert by["sphere/borisov-fedorov/hamiltonian-after-time-change"]["mark"] == \
        "not-checkable"
    # its cell: the project's bracket holds on the level F = 0 only and two attempts over
    # the whole phase space decide nothing (issue 18 item 4): inconclusive, not "nothing ran"
    assert by["sphere/borisov-fedorov/cell/hamiltonian_form"]["mark"] == "inconclusive"


def test_an_inconclusive_check_says_what_it_found(by):
    r = by["sphere/chaplygin-ball/negative/third-integral"]
    assert r["verdict"] == "unchecked" and r["mark"] == "inconclusive"
    assert "orbits" in r["mark_note"] and r["residual"] is not None


def test_evidence_and_inconclusive_notes_speak_plain_words(records, by):
    """Issue 17: the note beside "evidence for", "evidence against" and "inconclusive" is
    written for a reader (solvers/verify/plain_notes.py), as the pages show it (printed
    numbers, views.record); the checking code's message, with its program words, stays in
    the record for the JSON and the Details toggle."""
    from app.services.views import record
    from tests.e2e.test_reader_pages_browser import developer_words

    noted = [r for r in records if r["mark"] in ("evidence-for", "evidence-against",
                                                 "inconclusive")]
    # formula and cell records, evidence for and inconclusive, among the real records (a
    # cell that is inconclusive: the ellipsoid's, test_the_ellipsoid_no_further_integral...)
    assert {(r["level"], r["mark"]) for r in noted} >= {
        ("formula", "evidence-for"), ("formula", "inconclusive"), ("cell", "evidence-for")}
    problems = {r["claim"]: developer_words(record(r)["mark_note"]) for r in noted}
    assert not {k: v for k, v in problems.items() if v}, problems
    assert all(record(r)["mark_note"] for r in noted)
    # the note says what the check found: its numbers, not a stock sentence
    r = by["sphere/chaplygin-ball/negative/third-integral"]
    note = record(r)["mark_note"]
    assert "Poincaré map" in note and f"{r['evidence']['orbits']} orbits" in note
    assert re.search(r"s\d/s\d", r["message"]) and not re.search(r"s\d/s\d", note)
    r = by["sphere/round-disk/gyrostat/linear-integrals/formula-free"]
    assert f"each of {r['evidence']['crossings']} crossings" in r["mark_note"]


def test_formula_free_tests_are_evidence_and_support_their_cell(by):
    r = by["sphere/round-disk/gyrostat/linear-integrals/formula-free"]
    assert r["verdict"] == "verified" and r["mark"] == "evidence-for"
    # the cell holds after correction: the supporting test does not weaken its mark
    cell = by["sphere/round-disk/cell/gyrostat"]
    assert cell["mark"] == "after-correction" and cell["verdict"] == "verified"
    assert "sphere/round-disk/reduction/gyrostat" in cell["errata"]


def test_spherical_inertia_measure_rests_on_table_1_as_printed(by):
    """Table 1's (μ + m r²)^{3/2} is right as printed; only the text's display drops m."""
    cell = by["plane/spherical-inertia/cell/measure"]
    assert cell["mark"] == "as-printed" and cell["errata"] == []
    assert cell["rests_on"] == ["plane/spherical-inertia/measure/omega/table"]
    table = by["plane/spherical-inertia/measure/omega/table"]
    assert table["mark"] == "as-printed" and table["residual"] <= TOL
    assert (table.get("exact") or {}).get("holds") is True
    text = by["plane/spherical-inertia/measure/omega"]             # keeps its misprint
    assert text["qualifier"] == "misprint" and text["mark"] == "after-correction"
    tab = CAT.case("plane/spherical-inertia").cells
    from catalogue.schema import RowKey
    printed = CAT.case("plane/spherical-inertia").claim(
        "plane/spherical-inertia/measure/omega/table").printed
    assert printed in tab[RowKey("measure")].printed


@pytest.mark.slow
def test_the_ellipsoid_no_further_integral_cell_is_inconclusive():
    from solvers.verify.parallel import verify_parallel
    recs = verify_parallel(claim="plane/ellipsoid/cell/integrals", workers=2)
    cell = next(r for r in recs if r["claim"] == "plane/ellipsoid/cell/integrals")
    assert cell["verdict"] == "unchecked" and cell["mark"] == "inconclusive"
    note = cell["mark_note"]            # what the check found, not the word again
    # in plain words (issue 17): the message keeps the statistic's name, the note does not
    assert "orbits of the Poincaré map" in note and "no chaotic layer was found" in note
    assert not note.startswith("inconclusive") and "s3/s1" not in note
    assert "s3/s1" in cell["message"]
    from app.services.views import record
    from tests.e2e.test_reader_pages_browser import developer_words
    assert not developer_words(record(cell)["mark_note"])


def test_cell_mark_order():
    assert levels.combine(["as-printed", "open"]) == "as-printed"
    assert levels.combine(["as-printed", "after-correction"]) == "after-correction"
    assert levels.combine(["after-correction", "inconclusive"]) == "inconclusive"
    assert levels.combine(["open", "not-checkable"]) == "open"
    assert levels.combine([]) == "not-checkable"


# --- the same marks in the CLI, the API and /how-we-check ----------------------------------

def test_cli_prints_shapes_words_and_counts_by_mark(records):
    from rich.console import Console

    import app.cli as cli

    buf = io.StringIO()
    orig = Console.__init__

    def to_buffer(self, *a, **k):          # verify_tables makes its own Console
        orig(self, *a, **{**k, "file": buf, "width": 200})
    Console.__init__ = to_buffer
    try:
        cli.verify_tables(records, "plane/spherical-inertia")
    finally:
        Console.__init__ = orig
    text = buf.getvalue()
    for m in vocab.vocabulary():
        if m.id != "pending":
            assert f"{m.shape} {m.name}" in text.splitlines()[0]
    assert "✓ as printed: (μ + m r²)^(3/2)" in text
    cells = [r for r in records if r["level"] == "cell"]
    n = sum(r["mark"] == "as-printed" for r in cells)
    assert f"cells: {len(cells)} (properties of table cells): {n} cells hold as printed" in text
    assert "verified:" not in text


def test_how_we_check_defines_exactly_the_vocabulary(client):
    from html import escape

    page = client.get("/how-we-check").text
    api = client.get("/api/how-we-check").json()
    assert api["marks"] == [m.model_dump() for m in vocab.vocabulary()]
    for m in vocab.vocabulary():
        assert f'id="mark-{m.id}"' in page
        assert f'{m.shape}</span> {escape(m.name)}</dt><dd>{escape(m.definition)}</dd>' in page
    assert client.get("/api/marks").json()["marks"] == api["marks"]


def test_api_records_carry_marks(records, client):
    """Every cell and claim record in /api/cases/{id}, /api/tables and /api/verdicts carries
    a mark from the vocabulary, with the case summary counted by mark."""
    store = client.app.state.verdicts
    for c in CASES:
        store.put(c, [r for r in records if r["case"] == c])
    try:
        for c in CASES:
            d = client.get(f"/api/cases/{c}").json()
            for cl in d["claims"]:
                assert cl["verdict"]["mark"] in vocab.VERDICT_MARKS
                for corr in cl["corrections"]:
                    assert corr["mark"] in vocab.VERDICT_MARKS
            for cell in d["cells"]:
                if cell["verdict"]:
                    assert cell["verdict"]["mark"] in vocab.IDS
                    assert all(m["mark"] in vocab.IDS for m in cell["verdict"]["marks"])
            assert sum(d["cell_marks"].values()) == sum(1 for x in d["cells"] if x["verdict"])
            assert d["summary"].startswith("Of its ") and "verified" not in d["summary"]
        d = client.get("/api/cases/plane/spherical-inertia").json()
        assert "as printed" in d["summary"]
        for tid in ("plane", "sphere"):
            t = client.get(f"/api/tables/{tid}").json()
            assert t["mark_counts"] and "verified" not in t["summary"]
            for row in t["grid"]:
                for cell in row["cells"]:
                    if cell["verdict"]:
                        assert cell["verdict"]["mark"] in vocab.IDS
        for r in client.get("/api/verdicts").json():
            assert r["mark"] in vocab.VERDICT_MARKS
        o = client.get("/api/marks").json()
        assert o["cells_total"] == sum(o["cells"].values()) and o["summary"].startswith(
            f"Of the {o['cells_total']} table cells")
        home = client.get("/").text
        # the page escapes its text (a mark's name may hold an apostrophe)
        assert "cases verified" not in home and html.escape(o["summary"]) in home
        for m in vocab.vocabulary():            # the legend: shape and name of every mark
            assert f'{m.shape}</span>{html.escape(m.name)}</span>' in home
    finally:
        for c in CASES:
            store.records.pop(c, None)


@pytest.fixture(scope="module")
def client():
    from fastapi.testclient import TestClient

    from app.main import create_app
    from app.testing import settings_for_tests

    with TestClient(create_app(settings_for_tests(warm_workers=False))) as c:
        yield c
