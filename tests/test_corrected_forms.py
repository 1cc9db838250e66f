"""The project's corrected forms are shown as formulas: every registered correction has a
TeX form in catalogue/corrected_forms.yaml, and a correction record carries it."""

import solvers.verify.formulas  # noqa: F401  (registers the corrections)
from app.services.views import corrected_forms, record
from solvers.verify.registry import CORRECTION_NOTES


def test_every_correction_has_a_formula():
    assert set(corrected_forms()) == set(CORRECTION_NOTES)
    assert all(tex.strip() for tex in corrected_forms().values())


def test_a_correction_record_carries_its_formula_and_its_note_in_words():
    rec = {"claim": "plane/x/corrected", "verdict": "verified", "origin": "project-correction",
           "printed": f"[project's correction of routh_K1] {CORRECTION_NOTES['routh_K1']}"}
    out = record(rec)
    assert out["printed_tex"].startswith("K_1 = ")
    assert not out["printed"].startswith("[project's")
    assert "eq2.4" not in out["printed"] and "(2.5)" in out["printed"]
