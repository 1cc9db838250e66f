"""Every equation number a reader meets is the printed one (issue 17, item 3), outside the
browser: the catalogue's texts, the glossary pop-ups' data, and the CLI's text output.
(The pages themselves: tests/e2e/test_reader_pages_browser.py, with the same rule.)

The rule that makes "names the display that is meant" checkable:

1. Texts in the data never write a printed number; they write the seed's label (`eq2.17`)
   and the number a reader sees is made from it through catalogue/printed_numbers.yaml
   (which LaTeX confirms: tests/test_printed_numbers_latex.py). So a number shown for a
   label is that label's number by construction, and a label written in the data is
   checked to exist (the yaml).
2. Whatever a reader sees contains no label of the seed or of the catalogue, and every
   "(n.m)" in it is a number the paper prints (a key of the yaml's values).
3. Where a text names an unnumbered display by its place ("the unnumbered equation after
   (2.17)"), the seed has an unnumbered display right there.
"""

from __future__ import annotations

import copy
import json
import re

import pytest
import yaml
from conftest import records_of
from typer.testing import CliRunner

from catalogue.load import load_catalogue
from catalogue.numbering import _COMMENT, DATA, cite, derive, printed, printed_numbers
from tests.e2e.site import internal_label_re

INTERNAL = internal_label_re()
NUMBER = re.compile(r"\((\d+\.\d+)\)")
KNOWN = {v.strip("()") for v in printed_numbers().values() if v.startswith("(")}
CATALOGUE_YAML = ["plane.yaml", "sphere.yaml", "formulas.yaml", "corrected_forms.yaml",
                  "glossary.yaml", "scenes.yaml", "references.yaml", "notation.yaml"]


def reader_problems(text: str) -> list[str]:
    """What rule 2 finds wrong in a text a reader sees."""
    out = [f"label {x!r}" for x in INTERNAL.findall(text)]
    out += [f"no display ({n})" for n in NUMBER.findall(text) if n not in KNOWN]
    return out


def test_the_rule_finds_the_issues_examples():
    assert reader_problems("density eq2.17") == ["label 'eq2.17'"]
    assert reader_problems("sphere/flat-base: eq3.16") == ["label 'eq3.16'"]
    assert reader_problems("the Chaplygin convention (eq2b-*1)") == ["label 'eq2b-*1'"]
    assert reader_problems("see (2.43) and (4.1)") == ["no display (2.43)", "no display (4.1)"]
    assert reader_problems("density (2.24); bracket (2.25); Fig. 3; 1.5e-3; (0.5)") == \
        ["no display (0.5)"]


def _strings(x):
    if isinstance(x, dict):
        for k, v in x.items():
            yield from _strings(k)
            yield from _strings(v)
    elif isinstance(x, list):
        for v in x:
            yield from _strings(v)
    elif isinstance(x, str):
        yield x


@pytest.mark.parametrize("name", CATALOGUE_YAML)
def test_data_texts_write_labels_not_numbers(name):
    """Rule 1: a literal "(2.24)" in the data could name the wrong display unnoticed; a
    label cannot (its number comes from the yaml). Every label-like token in a text must be
    a label the yaml knows."""
    path = DATA.with_name(name)
    data = yaml.safe_load(path.read_text(encoding="utf-8"))
    for s in _strings(data):
        assert not NUMBER.search(s), (name, s)
        # what cite() makes of the text is what readers see: rule 2 holds for it
        shown = cite(s)
        # the printed LaTeX quotes keep \eqref{label} as the seed has them; cite_latex
        # turns those into numbers on the pages, and they are not prose
        shown = re.sub(r"\\(eq)?ref\s*\{[^}]*\}", " ", shown)
        assert not reader_problems(shown), (name, s, reader_problems(shown))


def _displays(seed: str) -> list[tuple[int, str | None]]:
    """(line, printed number or None) of every display of the seed, in order."""
    nums = [(n.line, n.number) for n in derive(seed) if n.kind == "equation"]
    unnumbered = [i for i, ln in enumerate(seed.splitlines(), 1)
                  if re.search(r"\\eqc?\s*\*|\$\$|\\\[|\\begin\{(equation|align|gather)\*\}",
                               _COMMENT.sub("", ln))]
    return sorted(nums + [(i, None) for i in unnumbered])


def test_an_unnumbered_display_is_named_by_where_it_stands(paper_text):
    """Rule 3: "unnumbered equation after (2.17)" must sit right after display (2.17)."""
    disp = _displays(paper_text)
    where = {d: i for i, (_, d) in enumerate(disp) if d}
    seen = 0
    for case in load_catalogue().cases():
        for c in case.claims:
            for m in re.finditer(r"unnumbered [^;]*?(after|before) \((\d+\.\d+)\)",
                                 cite(c.where) or ""):
                k = where[m[2]] + (1 if m[1] == "after" else -1)
                assert disp[k][1] is None, (c.id, m[0], disp[k])
                seen += 1
    assert seen >= 10


def test_glossary_popups_show_printed_numbers():
    """The "?" pop-up shows /api/glossary's meaning (app/static/js/glossary.js)."""
    from fastapi.testclient import TestClient

    from app.main import create_app
    from app.testing import settings_for_tests

    with TestClient(create_app(settings_for_tests(warm_workers=False))) as client:
        entries = client.get("/api/glossary").json()["entries"]
    assert entries
    by_symbol = {e["symbol"]: e for e in entries}
    # the issue's example: the pop-up for R said "the paper's eq3.12"; /glossary said (3.10)
    assert "(3.10)" in by_symbol["R"]["meaning"]
    for e in entries:
        assert not reader_problems(e["meaning"]), (e["symbol"], e["meaning"])
        assert e["paper_numbers"] == [printed(x) for x in e["paper"]]


# --- the CLI's text output -------------------------------------------------------------

CLI_CASES = ("sphere/flat-base", "plane/round-disk", "plane/unbalanced-ball")


@pytest.fixture(scope="module")
def records(catalogue_records):
    """Real verdict records of three cases (the flat base and the unbalanced ball: the
    issue's "eq3.16" and "density eq2.17"; the disk: the misprints of (2.17)) on which
    `rolling verify` and `rolling errata` print their text."""
    return copy.deepcopy(records_of(catalogue_records, CLI_CASES))


def _run(args, monkeypatch=None, records=None) -> str:
    from app import cli

    if records is not None:
        import solvers.verify.parallel as par

        monkeypatch.setattr(par, "verify_parallel",
                            lambda case=None, claim=None, workers=0: [
                                r for r in records if case in (None, r["case"])])
    res = CliRunner().invoke(cli.cli, args, env={"COLUMNS": "200"})
    assert res.exit_code == 0, res.output
    return res.output


def test_cli_lists_show_printed_numbers():
    for args in (["cases"], ["methods"]):
        out = _run(args)
        assert not reader_problems(out), (args, reader_problems(out))
    assert "(2.40" in _run(["cases"])      # the ellipsoid's I = mu E + lambda m B


@pytest.mark.parametrize("args", [["verify", "--case", c] for c in CLI_CASES] + [["errata"]])
def test_cli_reports_show_printed_numbers(args, records, monkeypatch):
    out = _run(args, monkeypatch, records)
    assert len(out) > 200
    assert not reader_problems(out), (args, reader_problems(out))


def test_records_json_keeps_labels_as_data(records, monkeypatch):
    """--json is data for programs: labels stay there (the `label` field)."""
    out = json.loads(_run(["verify", "--case", CLI_CASES[0], "--json"], monkeypatch, records))
    assert any(r.get("label") for r in out)


# --- what the pages show once verdicts exist ---------------------------------------------

# data fields of the case and table records (ids, labels, check names); everything else in
# them is text a page shows, in the open or behind a Details toggle
DATA_KEYS = {"id", "label", "labels", "claim", "claims", "case", "rests_on", "merged",
             "subrow_case", "check", "href", "row", "key", "corrects", "origin", "exact",
             "conditions", "check_args", "version", "computed_at", "surface", "body",
             "variables", "shade", "level", "qualifier", "verdict", "mark", "ref",
             "equations", "runnable", "model"}


def _shown(x, out: list[str]) -> list[str]:
    if isinstance(x, dict):
        for k, v in x.items():
            # a data key names data when it holds a value; a record under it ("verdict":
            # {"message": ...}) holds text again
            if k not in DATA_KEYS or isinstance(v, dict):
                _shown(v, out)
    elif isinstance(x, list):
        for v in x:
            _shown(v, out)
    elif isinstance(x, str):
        out.append(x)
    return out


def test_case_and_table_records_with_real_verdicts_show_printed_numbers(records):
    """The issue's examples live in verdict texts (a cell's note: "density eq2.17",
    "eq3.16"), which the test server's pages have not computed: here the case and table
    records are built from real verdicts of three cases, as the pages receive them."""
    from app.services import views

    by_claim = {r["claim"]: r for r in records}
    corrections: dict[str, list[dict]] = {}
    for r in records:
        if r.get("corrects"):
            corrections.setdefault(r["corrects"], []).append(r)
    texts = []
    for cid in CLI_CASES:
        d = views.case_detail(cid, by_claim, corrections, "done")
        texts += _shown(d, [])
        # the model's conditions as the page shows them, in words
        texts += d["model"]["conditions_text"]
    for table in ("plane", "sphere"):
        texts += _shown(views.table(table, by_claim), [])
    joined = "\n".join(texts)
    # LaTeX quotes keep \eqref{number} / \ref{n}: numbers, which rule 2 reads as such
    joined = re.sub(r"\\(eq)?ref\s*\{([^}]*)\}", r"(\2)", joined)
    # the issue's examples: the flat base's density (3.18) and the Chaplygin ball's (2.24),
    # named in the measure cells' messages of the flat base and of the unbalanced ball
    assert "density (I3 + m r^2)^-1/2, (3.18)" in joined
    assert "the Chaplygin ball, density (2.24)" in joined
    assert not reader_problems(joined), sorted(set(reader_problems(joined)))


def test_a_convention_mark_names_the_printed_number():
    """The issue's example: the Chaplygin ball's convention sentence (shown beside its mark)
    named "eq2b-*1". The record is built as solvers/verify/levels.py builds it, from the
    claim's own `holds_under` text in the catalogue."""
    from app.services import views

    claim = load_catalogue().claim("plane/chaplygin-ball/hamiltonian-after-time-change")
    # the catalogue's text cites the displays by their labels (after eq2b-*3 / eq2-*3)
    assert claim.holds_under and "eq2b-*" in claim.holds_under
    rec = {"claim": claim.id, "verdict": "verified", "qualifier": "convention",
           "convention": claim.holds_under, "message": f"holds under the convention: "
           f"{claim.holds_under}", "finding": "as eq2b-*1 says", "notes": ["see eq2.17"]}
    out = views.record(rec)
    shown = " ".join([out["convention"], out["message"], out["finding"], *out["notes"]])
    assert "(2.27)" in out["convention"] and "(2.8)" in out["convention"]
    assert not reader_problems(shown), reader_problems(shown)
