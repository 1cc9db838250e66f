"""/notation defines every symbol that a typeset formula on a case page uses, and each case
page links each of its symbols to its definition."""

import json
import os
import re
import shutil
import subprocess
from html import escape
from pathlib import Path

import pytest
from fastapi.testclient import TestClient

from app.main import create_app
from app.services import views
from app.services.notation_page import case_formulas, usage
from app.testing import settings_for_tests
from catalogue.load import load_catalogue, load_corrected_forms
from catalogue.notation import entry_for, load_notation
from catalogue.numbering import printed
from catalogue.symbols import is_prose, symbols, symbols_of_math

pytestmark = pytest.mark.filterwarnings("ignore::DeprecationWarning")


@pytest.fixture(scope="module")
def client():
    with TestClient(create_app(settings_for_tests(warm_workers=False))) as c:
        yield c


# --- the tokenizer over LaTeX -----------------------------------------------------------

@pytest.mark.parametrize("tex, expected", [
    (r"\rho_0 = \bigl(I_1I_3 + m(\bs r,{\bf I}\br)\bigr)^{-1/2}",
     [r"\rho_{0}", "I_{1}", "I_{3}", "m", r"\mathbf{r}", r"\mathbf{I}"]),
    (r"F=(\bM,\ol{\bf A}\bs\gam)", ["F", r"\mathbf{M}", r"\bar{\mathbf{A}}", r"\mathbf{\gamma}"]),
    (r"\rho=\frac{1}{\sqrt{1-D({\bs\gamma},\,{\bf A}{\bs \gamma})}}",
     [r"\rho", "D", r"\mathbf{\gamma}", r"\mathbf{A}"]),
    (r"f_1=\frac{R}{\sqrt{1-\gam^2_3}}, \qq f_2=a", ["f_{1}", "R", r"\gamma_{3}", "f_{2}", "a"]),
    (r"\dot\br = \frac{1}{1-kR}(\br-\ba)\x \bs\omega",
     [r"\mathbf{r}", "k", "R", r"\mathbf{a}", r"\mathbf{\omega}"]),
    (r"K_1^{(part)}=\frac{sz}{I_1-I_3}", ["K_{1}^{(part)}", "s", "z", "I_{1}", "I_{3}"]),
    (r"\{M_i,M_j\}=\eps_{ijk}\rho^{-1}\gamma_k", ["M_{i}", "M_{j}", r"\varepsilon_{ijk}",
                                                  r"\rho", r"\gamma_{k}"]),
    (r"\frac{dx_i}{d\tau}={J_\lambda}_{ij}\pt{H}{x_j},\ {\bf J}_\lambda^{\text{T}}",
     ["d", "x_{i}", r"\tau", r"J_{\lambda}", "H", "x_{j}", r"\mathbf{J}_{\lambda}"]),
    (r"\sum_{(i,j,k)\ \text{cyclic}} I_i\,(b_j - b_k) = 0", ["I_{i}", "b_{j}", "b_{k}"]),
    (r"\omega_3 + \frac{s}{2\mu} = \mathrm{const}", [r"\omega_{3}", "s", r"\mu"]),
])
def test_the_tokenizer_reads_one_token_per_symbol(tex, expected):
    assert symbols_of_math(tex) == expected


def test_words_are_no_symbols():
    """Prose and words in \\text are not typeset as math: no symbols (latex.js isProse)."""
    for src in ("unknown", "not found", r"S.\,A.\,Chaplygin (1897)",
                r"measure~\eqref{eq3.18} is preserved"):
        assert is_prose(src) and symbols(src) == []
    assert symbols(r"the zero level $(\bK, \bs\gamma)=0$ of~\eqref{eq2b-*3}") == \
        [r"\mathbf{K}", r"\mathbf{\gamma}"]
    assert symbols("the center of mass is situated on the contact plane $(z=0)$",
                   text=True) == ["z"]


# --- every symbol on a case page is defined ----------------------------------------------

def _case_tokens(case) -> set[str]:
    return {t for tex, text in case_formulas(case) for t in symbols(tex, text)}


def test_every_symbol_of_every_case_page_has_a_notation_entry():
    missing = {}
    for case in load_catalogue().cases():
        for t in _case_tokens(case):
            if entry_for(t) is None:
                missing.setdefault(t, case.id)
    assert missing == {}, f"symbols without a definition in catalogue/notation.yaml: {missing}"


def test_the_formulas_read_include_corrected_forms_and_cells():
    case = load_catalogue().case("sphere/body-of-revolution")
    texts = [t for t, _ in case_formulas(case)]
    assert load_corrected_forms()["sphere_revolution_density"].latex in texts
    assert r"\rho_{0}" in _case_tokens(case)


def test_every_entry_says_where_the_paper_defines_it():
    n = load_notation()
    for e in n.entries:
        assert e.defined and all(printed(lab) for d in e.defined for lab in d.labels), e.id
    # one symbol, several definitions by section: said, not hidden
    assert {d.section for d in n.get("A").defined} == {"1", "2"}
    assert {d.section for d in n.get("lambda").defined} == {"2", "3"}
    assert len(n.get("lambda").defined) >= 3 and len(n.get("k").defined) >= 3
    assert any("eq3.13" in d.labels for d in n.get("A-bar").defined)
    assert any("eq3.2" in d.labels for d in n.get("rho0").defined)
    # every entry is used on some case page (no orphan definitions)
    assert {e.id for e in n.entries} == set(usage())


def test_no_corrected_form_leaves_the_reader_an_ellipsis():
    for fid, cf in load_corrected_forms().items():
        assert r"\ldots" not in cf.latex and "..." not in cf.latex, fid
    assert load_corrected_forms()["sphere_revolution_density"].latex.count("mI_3f_2^2") == 1


@pytest.mark.parametrize("case", [c.id for c in load_catalogue().cases()])
def test_each_case_page_links_each_of_its_symbols_to_its_definition(client, case):
    """The page as served (no script run) links every symbol of its formulas to
    /notation#sym-<id>; the API gives each formula its own list (the script draws it)."""
    html = client.get(f"/case/{case}").text
    ids = {entry_for(t).id for t in _case_tokens(load_catalogue().case(case))}
    box = html.split('id="symbollist"')[1].split("</section>")[0]
    for sid in ids:
        assert f'href="/notation#sym-{sid}"' in box, (case, sid)
    detail = client.get(f"/api/cases/{case}").json()
    assert {s["id"] for s in detail["notation"]} == ids
    on_api = {s["id"] for x in detail["cells"] + detail["claims"] for s in x["symbols"]}
    assert on_api <= ids and all(s["href"] == f"/notation#sym-{s['id']}"
                                 for s in detail["notation"])


def test_a_correction_record_lists_the_symbols_of_its_formula():
    import solvers.verify.formulas  # noqa: F401  (registers the corrections)
    from solvers.verify.registry import CORRECTION_NOTES

    rec = {"claim": "sphere/body-of-revolution/measure/corrected", "verdict": "verified",
           "origin": "project-correction", "mark": "after-correction",
           "printed": "[project's correction of sphere_revolution_density] "
                      + CORRECTION_NOTES["sphere_revolution_density"]}
    out = views.record(rec)
    ids = [s["id"] for s in out["symbols"]]
    assert out["change"].startswith("exponent 1 on (1 − k f₁)")
    assert "rho0" in ids and "f" in ids and "k" in ids and "I" in ids


# --- /notation and /api/notation ---------------------------------------------------------

def test_the_notation_page_defines_every_entry(client):
    r = client.get("/notation")
    assert r.status_code == 200
    html = r.text
    assert '<a href="/notation" aria-current="page">Notation</a>' in html
    for e in load_notation().entries:
        assert f'id="sym-{e.id}"' in html
        for d in e.defined:
            for lab in d.labels:
                assert escape(printed(lab)) in html
    # one symbol, two definitions: A of (1.6) and of (2.24), each with its section
    a = html.split('id="sym-A"')[1].split("</section>")[0]
    assert "(1.6), section 1" in a and "(2.24), section 2" in a and "2 definitions" in a
    assert 'href="/case/plane/chaplygin-ball"' in a


def test_the_notation_api(client):
    r = client.get("/api/notation")
    assert r.status_code == 200
    entries = {e["id"]: e for e in r.json()["entries"]}
    assert entries["rho0"]["defined"][0]["numbers"] == ["(3.2)"]
    assert entries["rho0"]["href"] == "/notation#sym-rho0"
    assert any(c["id"] == "sphere/body-of-revolution" for c in entries["rho0"]["cases"])


def test_every_page_links_to_notation(client):
    assert 'href="/notation"' in client.get("/glossary").text


# --- the page's prose rule and the tokenizer's agree --------------------------------------

PROSE = r"""
globalThis.window = {};
const { isProse } = await import(process.argv[2]);
const srcs = JSON.parse(process.argv[3]);
console.log(JSON.stringify(srcs.map((s) => isProse(s))));
"""


def test_the_page_typesets_as_math_what_the_tokenizer_reads(tmp_path):
    node = shutil.which("node") or shutil.which("nodejs")
    if node is None:
        if os.environ.get("CI"):
            pytest.fail("node is needed to compare latex.js isProse")
        pytest.skip("node not installed")
    srcs = [c.printed for case in load_catalogue().cases() for c in case.claims
            if "$" not in c.printed]
    script = tmp_path / "prose.mjs"
    script.write_text(PROSE)
    latex = Path(__file__).resolve().parents[1] / "app" / "static" / "js" / "latex.js"
    out = subprocess.run([node, str(script), latex.as_uri(), json.dumps(srcs)],
                         capture_output=True, text=True, timeout=60, check=True)
    assert json.loads(out.stdout.strip().splitlines()[-1]) == [is_prose(s) for s in srcs]
    assert re.search("unknown", " ".join(s for s in srcs if is_prose(s)))


def test_a_symbol_link_has_a_name_in_plain_letters():
    from catalogue.symbols import plain

    assert [plain(t) for t in (r"\rho_{0}", r"\bar{\mathbf{A}}", r"K_{1}^{(part)}",
                               r"\mathbf{\gamma}")] == ["ρ0", "A\u0304", "K1(part)", "γ"]
    s = views.symbol_refs(r"\rho_0 = (I_1I_3)^{-1/2}")[0]
    assert s["text"] == "ρ0" and s["id"] == "rho0"
