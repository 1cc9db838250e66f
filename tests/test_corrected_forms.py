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


# --- every corrected form typesets (issue 17, item 4) --------------------------------------

RENDER = r"""
import { createRequire } from "module";
const require = createRequire(import.meta.url);
globalThis.window = { katex: require(process.argv[2]) };
const { mathHtml } = await import(process.argv[3]);
const forms = JSON.parse(process.argv[4]);
const bad = {};
for (const [fid, tex] of Object.entries(forms)) {
  const html = mathHtml(tex, true);
  const ok = !html.includes("tex-fallback") && html.includes('class="katex');
  if (!ok) bad[fid] = html.slice(0, 300);
}
console.log(JSON.stringify(bad));
"""


def test_every_corrected_form_renders_with_the_vendored_katex(tmp_path):
    """Each corrected form through the page's own mathHtml (latex.js: the paper's macros,
    throwOnError) and the vendored KaTeX, in node: no form falls back to its raw TeX."""
    import json
    import os
    import shutil
    import subprocess
    from pathlib import Path

    import pytest

    node = shutil.which("node") or shutil.which("nodejs")
    if node is None:
        if os.environ.get("CI"):
            pytest.fail("node is needed to render the corrected forms with KaTeX")
        pytest.skip("node not installed (Debian: apt-get install nodejs)")
    static = Path(__file__).resolve().parents[1] / "app" / "static"
    script = tmp_path / "render.mjs"
    script.write_text(RENDER)
    out = subprocess.run(
        [node, str(script), str(static / "vendor" / "katex" / "katex.min.js"),
         (static / "js" / "latex.js").as_uri(), json.dumps(corrected_forms())],
        capture_output=True, text=True, timeout=60, check=True)
    bad = json.loads(out.stdout.strip().splitlines()[-1])
    assert bad == {}, bad


def test_corrected_forms_name_their_change_and_an_existing_display():
    from catalogue.load import load_catalogue, load_corrected_forms

    cat = load_catalogue()
    for fid, cf in load_corrected_forms().items():
        assert cf.change.strip(), fid
        f = cat.formula(cf.display or fid)
        assert f.label or f.where, fid
    # the misprint in u of (2.10) is corrected in (2.10), not in the (2.9) or (2.12) it spoils
    forms = load_corrected_forms()
    assert forms["antigradient_form"].display == forms["conformal_field"].display == \
        "antigradient_J"
