"""Comments that stay true: the code's text says what and why, not when or after which
ticket. No file under solvers/, app/ (vendored libraries aside) or catalogue/ holds a
calendar date (YYYY-MM-DD) or an "issue N" reference, whose tracker a reader does not have,
and no file of the repository outside tests/ names the folder beside the clone (../shared):
only the tests that read the paper's text look there (tests/conftest.py)."""

from __future__ import annotations

import re
import subprocess
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
SCANNED = ("solvers", "app", "catalogue")
SKIPPED = (ROOT / "app" / "static" / "vendor",)
SUFFIXES = {".py", ".js", ".html", ".css", ".yaml", ".yml", ".md", ".txt", ".toml", ".cfg"}

# A full calendar date; a year alone (a publication's) is fine.
DATE = re.compile(r"\b(?:19|20)\d\d-(?:0[1-9]|1[0-2])-(?:0[1-9]|[12]\d|3[01])\b")
# "issue 19", "issues 17", "Issue #10", "(issue 18, item 3)": a tracker's number.
ISSUE = re.compile(r"\bissues? #?\d+", re.IGNORECASE)
# the same broken over two lines of a comment or docstring: "(issue\n# 17: ...)"
ISSUE_SPLIT = re.compile(r"\bissues?[ \t]*\n[ \t]*(?:#|//|/?\*)?[ \t]*#?\d+", re.IGNORECASE)
SHARED = re.compile(r"\.\./shared|shared/seeds")


def _files(top: Path):
    for p in sorted(top.rglob("*")):
        if not p.is_file() or p.suffix not in SUFFIXES or "__pycache__" in p.parts:
            continue
        if any(p.is_relative_to(s) for s in SKIPPED):
            continue
        yield p


def _hits(paths, patterns) -> list[str]:
    out = []
    for p in paths:
        try:
            text = p.read_text(encoding="utf-8")
        except UnicodeDecodeError:
            continue
        for n, line in enumerate(text.splitlines(), 1):
            for name, rx in patterns:
                m = rx.search(line)
                if m:
                    out.append(f"{p.relative_to(ROOT)}:{n}: {name} {m.group(0)!r}")
        if any(rx is ISSUE for _, rx in patterns):
            for m in ISSUE_SPLIT.finditer(text):
                n = text.count("\n", 0, m.start()) + 1
                out.append(f"{p.relative_to(ROOT)}:{n}: issue {m.group(0)!r}")
    return out


def test_no_dates_or_issue_numbers_in_code_comments():
    paths = [p for top in SCANNED for p in _files(ROOT / top)]
    assert len(paths) > 50
    hits = _hits(paths, [("date", DATE), ("issue", ISSUE), ("../shared", SHARED)])
    assert not hits, "\n".join(hits)


def _repository_files() -> list[Path]:
    try:
        names = subprocess.run(["git", "ls-files", "-z"], cwd=ROOT, capture_output=True,
                               check=True, timeout=60).stdout.decode().split("\0")
        paths = [ROOT / n for n in names if n]
    except (OSError, subprocess.SubprocessError):
        skip = {".git", ".venv", "__pycache__", "node_modules"}
        paths = [p for p in ROOT.rglob("*") if not skip & set(p.relative_to(ROOT).parts)]
    return [p for p in paths if p.is_file()]


def test_only_the_tests_refer_to_the_folder_beside_the_clone():
    paths = []
    for p in _repository_files():
        rel = p.relative_to(ROOT).as_posix()
        if rel.startswith("tests/"):
            continue
        if any(p.is_relative_to(s) for s in SKIPPED) or p.stat().st_size > 2_000_000:
            continue
        paths.append(p)
    assert paths
    hits = _hits(paths, [("../shared", SHARED)])
    assert not hits, "\n".join(hits)


def test_the_patterns_flag_what_they_mean_and_nothing_else():
    flagged = ["(issue 19: no compile)", "marks (issue\n# 17: one mark)", "(issue\n17)",
               "Issue 10, item 2.", "issue 18's audit",
               "issues 17 and 18", "see issue #12", "dropped on 2026-11-27, README",
               "ROLLING_SEED or ../shared/seeds"]
    clean = ["Regular and Chaotic Dynamics 7(2), 177-200 (2002)", "published 2002",
             "the issue's flood", "eq2.17 is printed (2.17)", "tissue 12", "2x3 matrix",
             "1e-12", "Table 2", "the shared cache",
             "JSON Schema 2020-12", "the issue\nof the journal"]
    rx = (DATE, ISSUE, ISSUE_SPLIT, SHARED)
    assert all(any(r.search(s) for r in rx) for s in flagged)
    assert not [s for s in clean if any(r.search(s) for r in rx)]
