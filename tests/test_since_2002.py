"""What is known since 2002 (issue 38, item 5): every open cell, open claim, refuted
conjecture and non-existence result of the catalogue carries a note
(catalogue/since_2002.yaml) whose references resolve to complete entries, shown in the case
JSON, on the case page beside its claim or cell, and on /bibliography."""

import copy
import html

import pytest
import yaml
from fastapi.testclient import TestClient

from app.main import create_app
from app.testing import settings_for_tests
from catalogue.load import load_catalogue
from catalogue.since_2002 import FILE, build, load_since_2002, reference

pytestmark = pytest.mark.filterwarnings("ignore::DeprecationWarning")

NONEXISTENCE_CHECKS = ("no_measure", "negative_measure")


@pytest.fixture(scope="module")
def client():
    with TestClient(create_app(settings_for_tests(warm_workers=False))) as c:
        yield c


def _own_claims(case, cell) -> list[str]:
    # the claims a cell's mark rests on (solvers.verify.levels._cell_claims)
    own = [c for c in cell.claims if c.startswith(case.id + "/")]
    return own or list(cell.claims)


def expected_records() -> dict[str, tuple[str, ...]]:
    """The records that need a note, from the catalogue: claims checked `open_problem`
    (mark open), claims whose check proves or refutes a non-existence (non-existence
    results and the refuted conjectures), and cells all of whose claims are open."""
    cat = load_catalogue()
    checks = {cl.id: cl.check.value for cl in cat.claims()}
    out: dict[str, tuple[str, ...]] = {}
    for cid, check in checks.items():
        if check == "open_problem":
            out[cid] = ("open claim",)
        elif check in NONEXISTENCE_CHECKS:
            out[cid] = ("non-existence", "refuted conjecture")
    for case in cat.cases():
        for row, cell in case.cells.items():
            own = _own_claims(case, cell)
            if own and all(checks[c] == "open_problem" for c in own):
                out[f"{case.id}/cell/{row.value}"] = ("open cell",)
    return out


def test_every_open_refuted_and_nonexistence_record_has_a_note():
    notes = {n.record: n for n in load_since_2002().notes}
    expected = expected_records()
    assert len(expected) == 21
    for rid, kinds in expected.items():
        assert rid in notes, f"no since-2002 note for {rid}"
        assert notes[rid].kind in kinds, rid
    # the two refuted conjectures the project answers (solvers.verify.levels qualifier)
    for rid in ("plane/ellipsoid/negative/general-measure",
                "plane/spherical-inertia/negative/sphere-generalization"):
        assert notes[rid].kind == "refuted conjecture", rid


def test_note_references_resolve_to_complete_entries_read_somewhere():
    data = load_since_2002()
    for n in data.notes:
        assert n.note.strip()
        for rid in n.references:
            r = reference(rid)
            assert r.status == "complete" and r.checked_in, (n.record, rid)
        if not n.found_later:
            assert "no later result found in the sources checked" in n.note.lower()
        assert (n.access == "none") == (not n.references), n.record
    for r in data.literature:
        assert r.status == "complete" and r.year and r.checked_in
        assert all(c.access in ("full", "abstract", "snippet") for c in r.checked_in)


def test_the_ellipsoid_notes_name_the_later_proof_and_the_project_scope():
    notes = {n.record: n for n in load_since_2002().notes}
    n = notes["plane/ellipsoid/negative/general-measure"]
    assert n.found_later and "garcia-naranjo-marrero-2013" in n.references
    assert "λ = −1/5" in n.note
    # the homogeneity argument excludes C¹ positive densities near M = 0, not every density
    assert "C¹ and positive" in n.project and "not every density" in n.project


def test_a_note_citing_an_unresolved_entry_is_refused():
    raw = yaml.safe_load(FILE.read_text(encoding="utf-8"))
    bad = copy.deepcopy(raw)
    bad["notes"][0]["references"] = ["yaroshuk"]          # unresolved in references.yaml
    with pytest.raises(ValueError, match="unresolved"):
        build(bad)
    bad = copy.deepcopy(raw)
    bad["notes"][0]["record"] = "plane/no-such-case/claim"
    with pytest.raises(ValueError, match="unknown claim or cell"):
        build(bad)
    bad = copy.deepcopy(raw)
    bad["notes"][-1]["note"] = "Nothing is known."                  # found_later: false
    with pytest.raises(ValueError, match="no later result found"):
        build(bad)


def test_case_json_and_page_show_each_note_beside_its_record(client):
    notes = load_since_2002().notes
    for case_id in sorted({"/".join(n.record.split("/")[:2]) for n in notes}):
        mine = [n for n in notes if n.record.startswith(case_id + "/")]
        d = client.get(f"/api/cases/{case_id}").json()
        assert [x["record"] for x in d["since_2002"]] == [n.record for n in mine]
        for x in d["since_2002"]:
            for r in x["references"]:
                assert r["href"] == f"/bibliography#ref-{r['id']}" and r["citation"]
        page = client.get(f"/case/{case_id}").text
        for n in mine:
            assert f'class="since-2002" data-record="{html.escape(n.record)}"' in page, n.record


def test_bibliography_lists_the_later_works_and_every_note(client):
    page = client.get("/bibliography").text
    data = load_since_2002()
    assert 'id="since-2002"' in page
    for r in data.literature:
        assert f'<li id="ref-{r.id}" data-status="complete">' in page, r.id
        for c in r.checked_in:
            assert f'href="{html.escape(c.url)}"' in page, r.id
    for n in data.notes:
        assert f'<li class="since-note" data-record="{html.escape(n.record)}">' in page
