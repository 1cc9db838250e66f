"""The layers of the code base, enforced: the import-linter contracts of pyproject.toml
([tool.importlinter]: the catalogue imports no solver and nothing of the explorer, the
solvers nothing of the explorer, no circles among the explorer's services), and, over every
module of solvers/, app/ and catalogue/ read with ast (scripts/import_report.py): no import
circle, no underscore name imported from another module, and no import inside a function
without a `# lazy:` comment saying what heavy import it keeps out of start-up."""

import shutil
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "scripts"))
import import_report as report  # noqa: E402


def test_no_file_is_over_the_line_limit():
    assert report.long_files() == []


def test_the_import_linter_contracts_are_kept():
    exe = shutil.which("lint-imports", path=str(Path(sys.executable).parent))
    if exe is None:
        pytest.fail("import-linter is a dev dependency (pyproject.toml): install it")
    out = subprocess.run([exe, "--no-cache"], cwd=ROOT, capture_output=True, text=True,
                         env={"PYTHONPATH": str(ROOT), "PATH": "/usr/bin:/bin"})
    assert out.returncode == 0, out.stdout[-3000:] + out.stderr[-2000:]
    assert " 0 broken" in out.stdout, out.stdout[-3000:]


def test_no_import_circle_among_the_modules():
    imports = report.all_imports()
    modules = {report.module_name(p) for p in report.project_files()}
    assert report.circles(report.graph(imports, modules)) == []


def test_the_circle_finder_finds_a_circle():
    edges = {"a": {"b"}, "b": {"c"}, "c": {"a"}, "d": {"a"}}
    assert report.circles(edges) == [["a", "b", "c"]]


def test_no_underscore_name_is_imported_across_modules():
    found = set(report.underscore_imports(report.all_imports()))
    assert found == set(), found


def test_the_underscore_finder_finds_one():
    imp = report.Import("a.b", "a.c", ("public", "_private", "__version__"), False, 1)
    assert report.underscore_imports([imp], attributes=False) == [("a.b", "a.c", "_private")]


def test_the_catalogue_imports_no_solver_even_inside_a_function():
    bad = [(i.source, i.target) for i in report.all_imports()
           if i.source.split(".")[0] == "catalogue" and i.target.split(".")[0] != "catalogue"]
    assert bad == []


def test_every_import_inside_a_function_says_why_it_is_lazy():
    bad = [f"{i.source}:{i.line} {i.text}" for i in report.unexplained_imports()]
    assert bad == [], f"{len(bad)} without a `# lazy:` reason:\n" + "\n".join(bad)


SYNTHETIC = """\
import json


def plain():
    import os
    return os


def explained_on_the_line():
    import scipy  # lazy: scipy, not at start-up
    return scipy


def explained_above():
    x = 1
    # lazy: sympy and heyoka, kept out of the server's start;
    # the second comment line continues the first
    import sympy
    from heyoka import taylor_adaptive as ta
    return sympy, ta, x


def the_comment_covers_only_the_block_below_it():
    # lazy: numba
    import numba
    y = 2
    import math
    return numba, math, y


def a_plain_comment_is_no_reason():
    # the math module
    import math
    return math


def an_empty_reason_is_no_reason():
    import math  # lazy:
    return math
"""


def test_the_lazy_finder_tells_explained_from_unexplained():
    found = report.function_imports_in(SYNTHETIC, "m")
    assert [(i.line, i.reason) for i in found] == [
        (5, False), (10, True), (18, True), (19, True), (25, True), (27, False), (33, False),
        (38, False)]
    assert [i.text for i in found if not i.reason] == [
        "import os", "import math", "import math", "import math  # lazy:"]
