"""The public face of the package (solvers/__init__.py): every name of `solvers.__all__`
resolves, is documented in numpydoc style with the sections a reader looks for, and the
examples in its docstring run and give what they show (doctests, with NORMALIZE_WHITESPACE
and ELLIPSIS). The package stays cheap to import: its names load on first use."""

import doctest
import inspect
import re
import subprocess
import sys
from pathlib import Path

import pytest

import solvers

NAMES = list(solvers.__all__)
FLAGS = doctest.NORMALIZE_WHITESPACE | doctest.ELLIPSIS


def _documented(name):
    """The object whose docstring documents the name: the function behind a callable
    submodule (solvers.simulate, solvers.verify), else the object itself."""
    return inspect.unwrap(getattr(solvers, name))


def _sections(doc: str) -> dict[str, str]:
    """numpydoc sections: a title line underlined by dashes -> the text below it."""
    lines = doc.splitlines()
    heads = [i for i in range(len(lines) - 1)
             if lines[i].strip() and re.fullmatch(r"-{3,}", lines[i + 1].strip())
             and len(lines[i + 1].strip()) == len(lines[i].strip())]
    out = {}
    for k, i in enumerate(heads):
        end = heads[k + 1] if k + 1 < len(heads) else len(lines)
        out[lines[i].strip()] = "\n".join(lines[i + 2:end])
    return out


def test_every_public_name_resolves_and_is_listed_by_dir():
    assert len(set(NAMES)) == len(NAMES)
    assert set(NAMES) == set(solvers._HOME)
    for name in NAMES:
        obj = getattr(solvers, name)
        assert obj is not None, name
        assert name in dir(solvers)
    ns = {}
    exec(f"from solvers import {', '.join(NAMES)}", ns)
    assert all(ns[n] is getattr(solvers, n) for n in NAMES)
    with pytest.raises(AttributeError):
        solvers.no_such_name   # noqa: B018


@pytest.mark.parametrize("name", NAMES)
def test_numpydoc_sections(name):
    obj = _documented(name)
    doc = inspect.getdoc(obj)
    assert doc, f"{name}: no docstring"
    sec = _sections(doc)
    if inspect.isclass(obj):
        need = ["Attributes", "Examples"]
    else:
        need = ["Returns", "Examples"]
        if inspect.signature(obj).parameters:
            need.insert(0, "Parameters")
    missing = [s for s in need if s not in sec]
    assert not missing, f"{name}: docstring lacks {missing} (has {list(sec)})"
    assert ">>> " in sec["Examples"], f"{name}: Examples without a doctest"
    assert "issue" not in doc.lower(), f"{name}: the docstring cites an issue"


def _run_doctests(obj, name):
    tests = doctest.DocTestFinder(recurse=False).find(obj, name, globs={})
    assert any(t.examples for t in tests), f"{name}: no doctest found"
    runner = doctest.DocTestRunner(optionflags=FLAGS)
    report = []
    for t in tests:
        runner.run(t, out=report.append)
    result = runner.summarize(verbose=False)
    assert result.failed == 0, "".join(report)


@pytest.mark.parametrize("name", NAMES)
def test_doctests_of_public_names(name):
    _run_doctests(_documented(name), f"solvers.{name}")


def test_doctest_of_the_package():
    _run_doctests(solvers, "solvers")


def test_the_reference_page_documents_every_public_name():
    """docs/reference/python.md has a mkdocstrings directive for every public name, at
    the module that defines it (where griffe finds its docstring)."""
    page = (Path(__file__).resolve().parents[1] / "docs" / "reference" / "python.md")
    directives = set(re.findall(r"^::: (\S+)$", page.read_text(), flags=re.M))
    want = {f"{solvers._CALLABLE.get(n, solvers._HOME[n])}.{n}" for n in NAMES}
    assert want <= directives, sorted(want - directives)


def test_light_modules_import_no_solver():
    """`import solvers.errors` (and the package itself) loads neither numba nor the
    integrators: the web app imports light modules at start-up."""
    code = ("import sys, solvers.errors, solvers; "
            "heavy = [m for m in ('numba', 'scipy', 'solvers.simulate', 'solvers.verify', "
            "'solvers.maps.poincare', 'dask') if m in sys.modules]; print(heavy)")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                         check=True).stdout
    assert out.strip() == "[]"


def test_submodules_named_like_their_function_stay_modules_and_are_callable():
    """solvers.simulate and solvers.verify are submodules too: `from solvers import
    simulate as sim; sim.simulate(...)` and `import solvers.verify.params as p` keep
    working, and calling them calls the function (looked up at each call)."""
    import solvers.verify.params as params_mod
    from solvers import simulate as sim
    from solvers.verify.run import verify as run_verify

    assert sim is sys.modules["solvers.simulate"] and callable(sim)
    assert solvers.verify is sys.modules["solvers.verify"] and callable(solvers.verify)
    assert params_mod is sys.modules["solvers.verify.params"]
    assert inspect.unwrap(solvers.verify) is run_verify
    assert inspect.signature(solvers.simulate) == inspect.signature(sim.simulate)
    calls = []
    real = sim.simulate
    try:
        sim.simulate = lambda *a, **kw: calls.append((a, kw)) or "patched"
        assert solvers.simulate("case", None, [], 1.0, samples=3) == "patched"
    finally:
        sim.simulate = real
    assert calls == [(("case", None, [], 1.0), {"samples": 3})]
