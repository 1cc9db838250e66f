"""The rubber cells typeset: every cell of catalogue/rubber_plane.yaml and rubber_sphere.yaml
has its statement in plain text and in LaTeX (`statement_tex`), the two name the same
symbols (catalogue/rubber_tex.py), every LaTeX form typesets with the page's own latex.js
and the vendored KaTeX, and the home page carries both forms."""

import json
import os
import shutil
import subprocess
from collections import Counter
from html import escape
from pathlib import Path

import pytest
from fastapi.testclient import TestClient
from pydantic import ValidationError

from app.main import create_app
from app.testing import settings_for_tests
from catalogue.load import load_rubber, read_rubber_raw
from catalogue.rubber_tex import mismatch, plain_symbols, tex_symbols
from catalogue.schema import MarkedCell, RubberTables

pytestmark = pytest.mark.filterwarnings("ignore::DeprecationWarning")
STATIC = Path(__file__).resolve().parents[1] / "app" / "static"
CELLS = {f"{case.id}/{row.value}": cell for case in load_rubber().cases()
         for row, cell in case.cells.items()}


def test_every_cell_has_both_forms_naming_the_same_symbols():
    assert len(CELLS) == 66
    for cid, cell in CELLS.items():
        assert cell.statement.strip() and cell.statement_tex.strip(), cid
        assert mismatch(cell.statement, cell.statement_tex) is None, cid
        if plain_symbols(cell.statement):      # a formula: typeset, in $...$
            assert "$" in cell.statement_tex, cid
        else:                                  # words only: the same words
            assert cell.statement_tex == cell.statement, cid
    # the reading is not empty: the Chaplygin ball's measure names what it should
    measure = CELLS["rubber-plane/chaplygin-ball/measure"]
    assert plain_symbols(measure.statement) == tex_symbols(measure.statement_tex) == {
        "Q", "omega", "gamma", "det", "I~", "M"}


CLAIM = dict(source="derived-here", place="x", access="derived-here", says="x", agreement="n/a",
             check="tests/x.py::y", level="exact")
GOOD = dict(mark="project-formula", statement="F = |M x gamma|^2 and Q^(1/2)",
            statement_tex=r"$F = |\bM\times\bs\gamma|^2$ and $Q^{1/2}$", claims=[CLAIM])


@pytest.mark.parametrize("tex, why", [
    (r"$F = |\bS\times\bs\gamma|^2$ and $Q^{1/2}$",                      # a symbol swapped
     r"only in the plain form: \['M'\]; only in the LaTeX: \['S'\]"),
    (r"$F = |\bM\times\bs\gamma|^2$", r"only in the plain form: \['Q'\]"),  # dropped
    (r"$F = |\bM\times\bs\gamma|^2$ and $Q^{1/2} H$", r"only in the LaTeX: \['H'\]"),
    (r"$F = |\bM\times\bs\gamma|^2$ and $Q^(1/2)$",                      # ASCII in the TeX
     r"plain-ASCII formula left in the LaTeX: \['\^\('\]"),
    (r"$F = |M x gamma|^2$ and $Q^{1/2}$", "plain-ASCII formula left in the LaTeX"),
    ("F = |M x gamma|^2 and Q^(1/2)", r"sets them in \$\.\.\.\$"),       # not typeset
    ("", "in plain text and in LaTeX"),                                # no LaTeX
])
def test_a_cell_whose_two_forms_differ_is_refused(tex, why):
    MarkedCell(**GOOD)
    with pytest.raises(ValidationError, match=why):
        MarkedCell(**{**GOOD, "statement_tex": tex})
    bad = {k: v for k, v in GOOD.items() if k != "statement_tex"}
    with pytest.raises(ValidationError, match="statement_tex"):
        MarkedCell(**bad)


def test_a_table_without_a_cell_s_latex_is_refused_and_left_as_it_was():
    raw = read_rubber_raw()
    cell = raw["plane"]["cases"][0]["cells"]["measure"]
    before = repr(cell)
    stripped = {k: v for k, v in cell.items() if k != "statement_tex"}
    bad = {**raw, "plane": {**raw["plane"], "cases": [
        {**raw["plane"]["cases"][0], "cells": {**raw["plane"]["cases"][0]["cells"],
                                               "measure": stripped}},
        *raw["plane"]["cases"][1:]]}}
    with pytest.raises(ValidationError, match="statement_tex"):
        RubberTables.model_validate(bad)
    assert repr(cell) == before


# the page's own textHtml (latex.js: the paper's macros, throwOnError) with the vendored
# KaTeX, in node, as tests/test_corrected_forms.py renders the corrected forms
RENDER = r"""
import { createRequire } from "module";
const require = createRequire(import.meta.url);
globalThis.window = { katex: require(process.argv[2]) };
const { textHtml } = await import(process.argv[3]);
const cells = JSON.parse(process.argv[4]);
const out = {};
for (const [id, tex] of Object.entries(cells)) {
  const html = textHtml(tex);
  out[id] = { fallback: html.includes("tex-fallback"),
              katex: (html.match(/class="katex"/g) || []).length };
}
console.log(JSON.stringify(out));
"""


def test_every_cell_typesets_with_the_vendored_katex(tmp_path):
    node = shutil.which("node") or shutil.which("nodejs")
    if node is None:
        if os.environ.get("CI"):
            pytest.fail("node is needed to render the rubber cells with KaTeX")
        pytest.skip("node not installed (Debian: apt-get install nodejs)")
    script = tmp_path / "render.mjs"
    script.write_text(RENDER)
    forms = {cid: c.statement_tex for cid, c in CELLS.items()}
    run = subprocess.run(
        [node, str(script), str(STATIC / "vendor" / "katex" / "katex.min.js"),
         (STATIC / "js" / "latex.js").as_uri(), json.dumps(forms)],
        capture_output=True, text=True, timeout=60, check=True)
    out = json.loads(run.stdout.strip().splitlines()[-1])
    assert set(out) == set(forms)
    for cid, tex in forms.items():
        assert not out[cid]["fallback"], (cid, tex)
        assert out[cid]["katex"] == tex.count("$") // 2, (cid, tex)   # one per $...$
    assert sum(r["katex"] for r in out.values()) > 60


@pytest.fixture(scope="module")
def client():
    with TestClient(create_app(settings_for_tests(warm_workers=False))) as c:
        yield c


def test_the_home_page_carries_both_forms_of_every_cell(client):
    """Drawn by the server: each rubber cell (and its claims below the tables) in plain text,
    for scripts off and screen readers before any script runs, with its LaTeX for the script
    to typeset."""
    html = client.get("/").text
    same = Counter((c.statement_tex, c.statement) for c in CELLS.values())
    for (tex, plain), n in same.items():
        # each cell twice: in its table and in its claims' entry below the tables
        assert html.count(f'data-tex="{escape(tex)}">{escape(plain)}</') == 2 * n, plain
    assert sum(same.values()) == 66


def test_a_rubber_case_carries_both_forms_and_says_where_its_symbols_are_defined(client):
    """GET /api/cases/{id}: a rubber case's cells with both forms, as the catalogue has them
    (the page typesets statement_tex); its page's symbol list sends the reader to the guide,
    where the rubber cells' symbols are defined, not to a list of none."""
    case = "rubber-plane/chaplygin-ball"
    cells = client.get(f"/api/cases/{case}").json()["rubber"]["cells"]
    assert len(cells) == 6
    for c in cells:
        cell = CELLS[f"{case}/{c['row']}"]
        assert (c["statement"], c["statement_tex"]) == (cell.statement, cell.statement_tex)
    html = client.get(f"/case/{case}").text
    box = html.split('id="symbollist"')[1].split("</section>")[0]
    assert "No typeset formula" not in box
    assert 'href="/guide/rubber/#the-rubber-tables"' in box and "Q and N" in box
