"""The README is a user's page: short, without history, its links resolve, and its Python
quick start runs as written (doctest)."""

import doctest
import re
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
README = ROOT / "README.md"


def _text() -> str:
    return README.read_text(encoding="utf-8")


def test_readme_is_short():
    assert len(_text().splitlines()) <= 200


def test_readme_holds_no_history():
    text = _text()
    assert not re.findall(r"\b20\d\d-[01]\d-[0-3]\d\b", text), "a date"
    assert not re.findall(r"\bissues? #?\d+", text, re.IGNORECASE), "an issue number"
    assert not re.findall(r"git show|\b[0-9a-f]{7,40}:", text), "a commit reference"
    assert "../shared" not in text


def test_readme_commands_are_the_ones_ci_runs():
    text = _text()
    assert "./dev serve" in text and "./dev test" in text
    ci = (ROOT / ".ci" / "run").read_text(encoding="utf-8")
    assert "./dev test" in ci


def test_readme_links_resolve():
    for target in re.findall(r"\]\(([^)#]+)(?:#[^)]*)?\)", _text()):
        if "://" in target:
            continue
        assert (ROOT / target).exists(), f"README links to {target}, which does not exist"


def test_readme_quick_start_runs():
    text = _text()
    block = next(m for m in re.finditer(r"```python\n(.*?)```", text, re.S) if ">>>" in m[1])
    session, line = block[1], text[:block.start(1)].count("\n")
    assert session.count(">>>") >= 3, "the quick start is a doctest session"
    test = doctest.DocTestParser().get_doctest(session, {}, "README.md", str(README), line)
    runner = doctest.DocTestRunner(optionflags=doctest.NORMALIZE_WHITESPACE | doctest.ELLIPSIS)
    runner.run(test)
    result = runner.summarize(verbose=False)
    assert result.attempted >= 3 and result.failed == 0
