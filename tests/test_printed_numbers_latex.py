"""The printed numbers confirmed by LaTeX itself, not only by the emulation.

The seed is compiled with Debian's texlive (pdflatex; texlive-latex-base and
texlive-latex-recommended, which `./dev test` installs) against a stand-in for the journal's
class rcdj, which is not public: tests/latex/rcdj.cls, article + amsmath with the class
macros defined as the seed uses them. The assumptions about the real class (each marked
ASSUMPTION in the stand-in; docs/equation-numbers.md) are:

1. equations are numbered "(section.n)", the counter reset by each \\section;
2. \\eq[label]{...} is one numbered display, \\eq*{...} an unnumbered one;
3. \\eqc[label]{a \\\\ b} is a multi-line display with one number for all its lines;
4. \\fig and \\wfig each step one figure counter for the whole paper, captioned or not;
   a \\label in the caption takes that number;
5. \\cfig (the picture in a corner of the rotated Tables 1, 2) takes no number;
6. the environments rem* and teo* take no number.

Everything else (align with \\notag and \\span, equation with gathered/aligned/pmatrix
inside, \\section*, tables, itemize) is numbered by LaTeX and amsmath themselves. What this
shows: under those assumptions, every label's number in the .aux equals the number in
catalogue/printed_numbers.yaml. It is not a comparison with a printed copy, and the page
numbers of the stand-in's layout are not the journal's (so none is used)."""

from __future__ import annotations

import os
import re
import shutil
import subprocess
from pathlib import Path

import pytest
import yaml

from catalogue.numbering import DATA, derive, name_uncaptioned

STANDIN = Path(__file__).with_name("latex") / "rcdj.cls"


def _need_pdflatex() -> str:
    exe = shutil.which("pdflatex")
    if exe is None:
        why = ("pdflatex not installed (apt-get install texlive-latex-base "
               "texlive-latex-recommended; ./dev test installs them)")
        if os.environ.get("ROLLING_REQUIRE_SEED") == "1" or os.environ.get("CI"):
            pytest.fail(f"{why}: required in CI")
        pytest.skip(why)
    return exe


@pytest.fixture(scope="module")
def compiled(paper_text, tmp_path_factory):
    """(labels -> number from the .aux, seed text); one pdflatex run: the .aux of a single
    pass already holds every \\newlabel."""
    exe = _need_pdflatex()
    d = tmp_path_factory.mktemp("latex")
    shutil.copy(STANDIN, d / "rcdj.cls")
    (d / "seed.tex").write_text(paper_text, encoding="utf-8")
    run = subprocess.run([exe, "-interaction=nonstopmode", "-halt-on-error", "seed.tex"],
                         cwd=d, capture_output=True, text=True, timeout=300)
    log = (d / "seed.log").read_text(encoding="latin-1")
    assert run.returncode == 0, log[-3000:]
    # a clean compile: no TeX error, no label defined twice
    assert not re.search(r"^! ", log, re.M), log[-3000:]
    assert "multiply defined" not in log
    aux = (d / "seed.aux").read_text(encoding="latin-1")
    labels = dict(re.findall(r"\\newlabel\{([^}]*)\}\{\{([^}]*)\}", aux))
    return labels, paper_text


def _committed() -> dict:
    return yaml.safe_load(DATA.read_text(encoding="utf-8"))


def test_every_equation_number_is_the_one_latex_gives(compiled):
    labels, _ = compiled
    latex = {k: f"({v})" for k, v in labels.items() if "." in v}   # (section.n)
    yml = _committed()["equations"]
    diff = {k: (yml.get(k), latex.get(k)) for k in set(latex) | set(yml)
            if yml.get(k) != latex.get(k)}
    assert not diff, f"label: (yaml, LaTeX) {diff}"
    assert len(yml) == 75


def test_every_captioned_figure_number_is_the_one_latex_gives(compiled):
    labels, _ = compiled
    yml = _committed()["figures"]
    assert yml, "no captioned figure in the yaml"
    for label, printed in yml.items():
        assert f"Fig. {labels.get(label)}" == printed, label


def test_each_figure_position_has_the_number_latex_gives(compiled):
    """The uncaptioned figures have no label in the seed (their file names, which the
    text cites, are lost): the yaml's `figures_inferred` pairs a cited name with a figure
    by proximity, which LaTeX cannot confirm. LaTeX does confirm the number of the figure
    at each position, and that there are as many figures as the emulation counts."""
    labels, text = compiled
    at_line = sorted((int(k.split(":")[1]), v) for k, v in labels.items()
                     if k.startswith("seedfig:"))
    figs = [n for n in name_uncaptioned(text, derive(text)) if n.kind == "figure"]
    assert len(at_line) == len(figs) == 11
    for n in figs:
        # the stand-in labels a figure by the line where its call ends: the first such
        # line at or after the line where the emulation saw it start
        end_line, number = next((ln, v) for ln, v in at_line if ln >= n.line)
        assert number == n.number, (n, end_line)
    yml = _committed()
    by_label = {n.label: n.printed for n in figs if n.label}
    for label, printed in {**yml["figures"], **yml["figures_inferred"]}.items():
        assert by_label[label] == printed, label
