"""The catalogue (Tables 1 and 2 of Borisov & Mamaev 2002 and the claims of the text) as data.

Checks every entry, not a sample: the schema validates, the column order and rows are the
paper's, every equation label and every printed LaTeX string is found in the seed paper, every
reference resolves, and broken entries are rejected.
"""

from __future__ import annotations

import copy
import re
import shutil

import pydantic
import pytest
import yaml

from catalogue import load as catalogue_load
from catalogue.load import build, load_catalogue, read_raw
from catalogue.schema import (
    DESCRIPTIVE_ROWS,
    NEGATIVE_CHECKS,
    Catalogue,
    CheckName,
    ClaimKind,
    RowKey,
    Shade,
)

PLANE_IDS = [
    "plane/chaplygin-ball",
    "plane/unbalanced-ball",
    "plane/ellipsoid",
    "plane/body-of-revolution",
    "plane/round-disk",
    "plane/routh-ball",
    "plane/spherical-inertia",
]
SPHERE_IDS = [
    "sphere/chaplygin-ball",
    "sphere/borisov-fedorov",
    "sphere/unbalanced-ball",
    "sphere/flat-base-z0",
    "sphere/flat-base",
    "sphere/body-of-revolution",
    "sphere/round-disk",
    "sphere/routh-ball",
    "sphere/flat-base-axisymmetric",
]
ALL_ROWS = [r.value for r in RowKey]
SPHERE_ROWS = [r for r in ALL_ROWS if r != "authors"]


def _squash(text: str) -> str:
    return re.sub(r"\s+", "", text)


@pytest.fixture(scope="module")
def cat() -> Catalogue:
    return load_catalogue()


@pytest.fixture(scope="module")
def raw() -> dict:
    return read_raw()


@pytest.fixture(scope="module")
def seed(paper_text: str) -> str:
    return paper_text


@pytest.fixture(scope="module")
def seed_labels(seed: str) -> set[str]:
    labels = set(re.findall(r"\\label\{([^}]*)\}", seed))
    labels |= set(re.findall(r"\\eqc?\[([^\]]*)\]\{", seed))
    assert {"eq1.1", "eq2.1/2", "eq-d*2", "eq-***3", "2-14*"} <= labels
    return labels


@pytest.fixture(scope="module")
def seed_tables(seed: str) -> dict[str, str]:
    tables = re.findall(r"\\begin\{table\}.*?\\end\{table\}", seed, flags=re.S)
    assert len(tables) == 2
    return {"plane": _squash(tables[0]), "sphere": _squash(tables[1])}


def all_labels(cat: Catalogue) -> list[tuple[str, str]]:
    found = []
    for formula in cat.formulas:
        if formula.label:
            found.append((f"formula {formula.id}", formula.label))
    for case in cat.cases():
        found += [(f"{case.id} model", lab) for lab in case.model.equations]
        for row, cell in case.cells.items():
            found += [(f"{case.id}/{row}", lab) for lab in cell.labels]
        found += [(claim.id, claim.label) for claim in case.claims if claim.label]
    return found


# --- loading -------------------------------------------------------------------------------------


def test_catalogue_loads_once_and_validates(cat, raw):
    assert isinstance(cat, Catalogue)
    assert load_catalogue() is cat  # cached
    assert build(copy.deepcopy(raw)) == cat  # a fresh validation gives the same data


def test_case_ids_in_the_papers_column_order(cat):
    assert [c.id for c in cat.plane.cases] == PLANE_IDS
    assert [c.id for c in cat.sphere.cases] == SPHERE_IDS
    assert [c.column for c in cat.plane.cases] == list(range(1, 8))
    assert [c.column for c in cat.sphere.cases] == list(range(1, 10))


def test_every_case_has_every_row_of_its_table(cat):
    assert [r.key.value for r in cat.plane.rows] == ALL_ROWS
    assert [r.key.value for r in cat.sphere.rows] == SPHERE_ROWS
    for table in cat.tables():
        rows = {r.key for r in table.rows}
        for case in table.cases:
            assert set(case.cells) == rows, case.id
            for cell in case.cells.values():
                assert cell.printed.strip() and cell.plain.strip(), case.id


def test_header_rows_are_above_the_double_rule(cat):
    for table in cat.tables():
        assert [r.key.value for r in table.rows if r.header] == [
            "tensor_of_inertia",
            "surface",
            "restrictions",
        ]


# --- the paper: labels and printed text ----------------------------------------------------------


def test_every_cited_label_exists_in_the_seed(cat, seed_labels):
    missing = [(where, lab) for where, lab in all_labels(cat) if lab not in seed_labels]
    assert not missing


def test_cells_are_printed_verbatim_in_their_table(cat, seed_tables):
    missing = []
    for table in cat.tables():
        text = seed_tables[table.id.value]
        pieces = [table.caption_printed, table.remark_printed]
        pieces += [r.printed for r in table.rows] + [g.printed for g in table.column_groups]
        for case in table.cases:
            for cell in case.cells.values():
                pieces.append(cell.printed)
                if cell.subrow:
                    pieces.append(cell.subrow.printed)
        missing += [(table.id, p) for p in pieces if _squash(p) not in text]
    assert not missing


def test_claims_and_formulas_are_printed_verbatim(cat, seed):
    text = _squash(seed)
    missing = [f.id for f in cat.formulas if _squash(f.printed) not in text]
    missing += [c.id for c in cat.claims() if _squash(c.printed) not in text]
    assert not missing


def test_every_cite_key_of_the_seed_has_a_reference(cat, seed):
    cited = set()
    for group in re.findall(r"\\cite\{([^}]*)\}", seed):
        cited |= {k.strip() for k in group.split(",")}
    keys = {r.cite_key for r in cat.references if r.cite_key}
    assert cited == keys


# --- cross-references ----------------------------------------------------------------------------


def test_every_attribution_resolves(cat):
    refs = {r.id: r for r in cat.references}
    seen = 0
    for case in cat.cases():
        atts = [a for cell in case.cells.values() for a in cell.attribution]
        atts += [a for claim in case.claims for a in claim.attribution]
        for att in atts:
            assert att.ref in refs, (case.id, att.ref)
            if att.year is not None and refs[att.ref].years:
                assert att.year in refs[att.ref].years, (case.id, att.ref, att.year)
            seen += 1
    assert seen > 50


def test_every_formula_id_resolves(cat):
    ids = {f.id for f in cat.formulas}
    used = {fid for claim in cat.claims() for fid in claim.check_args.formula_ids()}
    assert used <= ids
    # the brief's named formula ids exist
    assert {
        "M2",
        "area",
        "unbalanced_F",
        "jellett",
        "routh_K1",
        "bf_integral",
        "kozlov_brun_F3",
        "markeev_F2",
    } <= ids


def test_claim_ids_are_unique_and_prefixed_by_their_case(cat):
    ids = [c.id for c in cat.claims()]
    assert len(ids) == len(set(ids))
    for case in cat.cases():
        for claim in case.claims:
            assert claim.id.startswith(case.id + "/")


def test_cell_claims_exist_in_a_spanned_case(cat):
    for table in cat.tables():
        by_id = {c.id: c for c in table.cases}
        for case in table.cases:
            for row, cell in case.cells.items():
                owners = cell.merged or [case.id]
                owned = {cl.id for o in owners for cl in by_id[o].claims}
                assert set(cell.claims) <= owned, (case.id, row)


# --- merged cells and headers --------------------------------------------------------------------


def test_merged_cells_as_in_the_paper(cat):
    plane_axial = ["plane/body-of-revolution", "plane/round-disk", "plane/routh-ball"]
    for cid in plane_axial:
        cell = cat.case(cid).cells[RowKey.HAMILTONIAN_FORM]
        assert cell.merged == plane_axial and cell.colspan == 3
    measure = cat.case("sphere/routh-ball").cells[RowKey.MEASURE]
    assert measure.merged == ["sphere/body-of-revolution", "sphere/round-disk", "sphere/routh-ball"]
    bf = cat.case("sphere/borisov-fedorov").cells[RowKey.RESTRICTIONS]
    assert bf.merged == ["sphere/chaplygin-ball", "sphere/borisov-fedorov"]
    assert bf.subrow is not None and bf.subrow.printed == "$a=2R$"
    assert cat.case("sphere/chaplygin-ball").cells[RowKey.RESTRICTIONS].subrow is None
    for table in cat.tables():
        by_id = {c.id: c for c in table.cases}
        for case in table.cases:
            for row, cell in case.cells.items():
                for partner in cell.merged:
                    other = by_id[partner].cells[row]
                    assert (other.printed, other.shade, other.merged) == (
                        cell.printed,
                        cell.shade,
                        cell.merged,
                    )


def test_column_groups_partition_the_header_rows(cat):
    for table in cat.tables():
        ids = [c.id for c in table.cases]
        for row in (RowKey.TENSOR_OF_INERTIA, RowKey.SURFACE):
            groups = [g.cases for g in table.column_groups if g.row is row]
            assert [cid for g in groups for cid in g] == ids, (table.id, row)
    tensor = [g.plain for g in cat.plane.column_groups if g.row is RowKey.TENSOR_OF_INERTIA]
    assert tensor[0].startswith("dynamically nonsymmetric") and tensor[1].startswith("axial")


# --- shading -------------------------------------------------------------------------------------


def test_shading_follows_the_cell_content(cat):
    for case in cat.cases():
        for row, cell in case.cells.items():
            text = cell.plain.lower()
            if row in DESCRIPTIVE_ROWS or text in {"unknown", "—", "not found"}:
                assert cell.shade is Shade.NONE, (case.id, row)
            if "two integrals" in text and row is RowKey.INTEGRALS:
                assert cell.shade is Shade.FULL, (case.id, row)
            if "one integral" in text and row is RowKey.INTEGRALS:
                assert cell.shade is Shade.PARTIAL, (case.id, row)
            if cell.shade is not Shade.NONE:
                assert cell.claims, f"{case.id}/{row}: a gray cell must link a checkable claim"
    assert cat.case("plane/unbalanced-ball").cells[RowKey.MEASURE].shade is Shade.NONE
    assert cat.case("plane/chaplygin-ball").cells[RowKey.INTEGRALS].shade is Shade.FULL


def test_unknown_cells_link_a_negative_claim(cat):
    for case in cat.cases():
        for row, cell in case.cells.items():
            if cell.plain in {"unknown", "not found"} and row is not RowKey.GYROSTAT:
                kinds = {case.claim(c).kind for c in cell.claims}
                assert kinds == {ClaimKind.NEGATIVE}, (case.id, row)


# --- claims: coverage of the text ----------------------------------------------------------------


REQUIRED_LABELS = {
    # gyrostats, Brun, Poisson structures, Jellett/Routh
    "eq2.20",
    "eq2.24",
    "eq2.25",
    "eq2.26",
    "eq2.27",
    "eq2-25",
    "eq2-*3",
    "eq2b-*1",
    "eq2b-*3",
    "eq2.15",
    "eq2.2",
    "eq2.14",
    "eq2.19",
    "eq2.29",
    "eq2.30",
    # sphere
    "eq3.2",
    "eq3.8",
    "eq3-8",
    "eq3.9",
    "eq3.13",
    "eq*",
    "eq-**",
    "eq-***",
    "eq3.16",
    "eq3.17",
    "eq3.18",
    "eq-d*2",
    "eq-d*-2",
}
REDUCTION_LABELS = {
    "eq2-*1",
    "eq2.5",
    "eq2.8",
    "eq2.9",
    "eq2.20",
    "eq2.21",
    "eq3.3",
    "eq3.4",
    "eq3.7",
    "eq3.10",
    "eq3.11",
    "eq3.19",
    "eq3.21",
}


def test_claims_cover_the_labelled_statements_of_the_text(cat):
    labels = {c.label for c in cat.claims()}
    assert REQUIRED_LABELS <= labels
    reductions = {c.label for c in cat.claims() if c.kind is ClaimKind.REDUCTION}
    assert REDUCTION_LABELS <= reductions


def test_unnumbered_statements_are_claimed(cat):
    where = {c.id: c for c in cat.claims()}
    assert where["plane/chaplygin-ball/brun/kozlov-F3"].check_args.formula == "kozlov_brun_F3"
    assert where["plane/routh-ball/gyrostat/bobylev"].label is None
    assert where["sphere/round-disk/measure"].check_args.formula == "sphere_disk_density"
    # eq3.2 and the Table 2 cell are recorded as separate claims
    rev = cat.case("sphere/body-of-revolution")
    assert rev.claim("sphere/body-of-revolution/measure").label == "eq3.2"
    assert (
        rev.claim("sphere/body-of-revolution/measure/table-form").check_args.formula
        == "sphere_revolution_density_table"
    )
    # the ellipsoid measure is claimed at lambda = 1 and lambda = 0 and refuted elsewhere
    ell = {
        c.conditions.lambda_
        for c in cat.case("plane/ellipsoid").claims
        if c.check_args.formula == "ellipsoid_density"
    }
    assert {"0", "1", "not 0 or 1"} <= ell


def test_every_case_claims_its_energy_integral(cat):
    for case in cat.cases():
        energy = [c for c in case.claims if c.check_args.formula in {"energy", "markeev_energy"}]
        assert energy, case.id


def test_negative_checks_only_on_negative_claims(cat):
    for claim in cat.claims():
        if claim.check in NEGATIVE_CHECKS:
            assert claim.kind is ClaimKind.NEGATIVE, claim.id
    used = {c.check for c in cat.claims()}
    assert {
        CheckName.INTEGRAL,
        CheckName.MEASURE,
        CheckName.JACOBI,
        CheckName.REDUCED_AGREES,
        CheckName.NEGATIVE_MEASURE,
    } <= used


def test_convention_notes_where_the_brief_requires_them(cat):
    notes = {f.id: f.convention_note for f in cat.formulas}
    for fid in (
        "sphere_kinematics_signed",
        "flat_kinematics",
        "sphere_chaplygin_system",
        "kozlov_brun_F3",
        "brun_potential",
    ):
        assert notes[fid], fid


# --- broken entries are rejected -----------------------------------------------------------------


def _first_claim(raw):
    return raw["plane"]["cases"][0]["claims"][0]


def _extra_key(raw):
    _first_claim(raw)["colour"] = "red"


def _extra_key_in_cell(raw):
    raw["sphere"]["cases"][2]["cells"]["measure"]["footnote"] = "x"


def _unknown_check(raw):
    _first_claim(raw)["check"] = "looks_fine"


def _unknown_kind(raw):
    _first_claim(raw)["kind"] = "folklore"


def _dangling_reference(raw):
    _first_claim(raw)["attribution"] = [{"ref": "nobody-1900"}]


def _wrong_year(raw):
    _first_claim(raw)["attribution"] = [{"ref": "chaplygin1", "year": 1904}]


def _dangling_formula(raw):
    _first_claim(raw)["check_args"] = {"formula": "no_such_formula"}


def _formula_in_wrong_slot(raw):
    claim = next(c for c in raw["plane"]["cases"][0]["claims"] if c["check"] == "integral")
    claim["check_args"] = {"formula": "chaplygin_density"}


def _missing_check_arg(raw):
    claim = next(c for c in raw["plane"]["cases"][0]["claims"] if c["check"] == "measure")
    claim["check_args"] = {}


def _negative_check_on_positive_claim(raw):
    claim = next(c for c in raw["plane"]["cases"][0]["claims"] if c["check"] == "integral")
    claim["check"] = "integral_fails"


def _unprefixed_claim_id(raw):
    _first_claim(raw)["id"] = "plane/unbalanced-ball/integral/stolen"


def _duplicate_claim_id(raw):
    claims = raw["plane"]["cases"][0]["claims"]
    claims[1]["id"] = claims[0]["id"]


def _missing_row(raw):
    del raw["sphere"]["cases"][0]["cells"]["generalizations"]


def _dangling_merge(raw):
    cell = copy.deepcopy(raw["plane"]["cases"][3]["cells"]["hamiltonian_form"])
    cell["merged"] = [*cell["merged"], "plane/no-such-case"]
    cell["colspan"] = 4
    raw["plane"]["cases"][3]["cells"]["hamiltonian_form"] = cell


def _merged_cell_differs(raw):
    cell = copy.deepcopy(raw["plane"]["cases"][4]["cells"]["hamiltonian_form"])
    cell["printed"] = "something else"
    raw["plane"]["cases"][4]["cells"]["hamiltonian_form"] = cell


def _dangling_cell_claim(raw):
    raw["plane"]["cases"][0]["cells"]["measure"]["claims"] = ["plane/chaplygin-ball/nope"]


def _bad_shade(raw):
    raw["plane"]["cases"][0]["cells"]["measure"]["shade"] = "grey"


def _shaded_header(raw):
    raw["plane"]["cases"][2]["cells"]["surface"]["shade"] = "full"


def _columns_out_of_order(raw):
    cases = raw["sphere"]["cases"]
    cases[0], cases[1] = cases[1], cases[0]


@pytest.mark.parametrize(
    "breakage",
    [
        _extra_key,
        _extra_key_in_cell,
        _unknown_check,
        _unknown_kind,
        _dangling_reference,
        _wrong_year,
        _dangling_formula,
        _formula_in_wrong_slot,
        _missing_check_arg,
        _negative_check_on_positive_claim,
        _unprefixed_claim_id,
        _duplicate_claim_id,
        _missing_row,
        _dangling_merge,
        _merged_cell_differs,
        _dangling_cell_claim,
        _bad_shade,
        _shaded_header,
        _columns_out_of_order,
    ],
)
def test_broken_entry_is_rejected(breakage, raw):
    broken = copy.deepcopy(raw)
    build(broken)  # the unbroken copy is valid
    breakage(broken)
    with pytest.raises(pydantic.ValidationError):
        build(broken)


def test_duplicate_yaml_key_is_rejected(tmp_path):
    for name in catalogue_load.FILES.values():
        shutil.copy(catalogue_load.DATA_DIR / name, tmp_path / name)
    text = (tmp_path / "formulas.yaml").read_text(encoding="utf-8")
    text = text.replace("- id: energy\n", "- id: energy\n  id: energy\n", 1)
    (tmp_path / "formulas.yaml").write_text(text, encoding="utf-8")
    with pytest.raises(yaml.constructor.ConstructorError):
        read_raw(tmp_path)
