"""The user guide: docs/ and mkdocs.yml build with `mkdocs build --strict` (a dead link, a page
missing from the navigation or an unresolved API reference fails), the guide has its sections,
no page of it reads as change notes (no dates, commit hashes or issue numbers), and the
explorer serves it at /guide/ when it is built and says how to build it when it is not
(app/api/routes/guide.py).

Nothing here skips: the two pages written elsewhere (docs/performance.md and
docs/reference/python.md) must be there, and mkdocs with them (the `docs` extra, part of `dev`).
"""

import base64
import hashlib
import os
import re
import subprocess
import sys
from pathlib import Path

import pytest
import yaml
from fastapi.testclient import TestClient

from app.main import create_app
from app.testing import settings_for_tests

pytestmark = pytest.mark.filterwarnings("ignore::DeprecationWarning")
ROOT = Path(__file__).resolve().parents[1]
DOCS = ROOT / "docs"

# what a reader looks for -> the page that answers it (the navigation's files)
SECTIONS = {
    "getting started": "getting-started.md",
    "the explorer": "explorer.md",
    "the Python API (guide)": "python.md",
    "the Python API (reference)": "reference/python.md",
    "the command line": "cli.md",
    "the REST API": "rest-api.md",
    "checking the paper": "checking.md",
    "verdict levels and marks": "verdict-levels.md",
    "exact certificates and proofs": "exact-certificates.md",
    "nonexistence proofs": "nonexistence.md",
    "Hamiltonian forms on a sphere": "hamiltonian-sphere.md",
    "misprint audit": "misprint-audit.md",
    "equation numbers": "equation-numbers.md",
    "integrators and accuracy": "integrators.md",
    "performance": "performance.md",
    "limits and reliability": "limits.md",
    "conventions": "conventions.md",
    "development": "development.md",
}
DATE = re.compile(r"\b(?:19|20)\d\d-[01]\d-[0-3]\d\b")
ISSUE = re.compile(r"\bissues?\s*#?\s*\d+", re.I)
COMMIT = re.compile(r"(?<![\w./-])(?=[0-9a-f]*\d)(?=[0-9a-f]*[a-f])[0-9a-f]{7,40}(?![\w-])")


def _nav_files(nav) -> list[tuple[str, str]]:
    out = []
    for item in nav:
        for title, target in item.items():
            out += _nav_files(target) if isinstance(target, list) else [(title, target)]
    return out


def _config() -> dict:
    return yaml.safe_load((ROOT / "mkdocs.yml").read_text())


@pytest.fixture(scope="module")
def site(tmp_path_factory) -> Path:
    out = tmp_path_factory.mktemp("guide") / "site"
    r = subprocess.run([sys.executable, "-m", "mkdocs", "build", "--strict", "-q",
                        "-f", str(ROOT / "mkdocs.yml"), "-d", str(out)],
                       cwd=ROOT, capture_output=True, text=True, timeout=600,
                       env={**os.environ, "NO_MKDOCS_2_WARNING": "1"})
    assert r.returncode == 0, f"mkdocs build --strict failed:\n{r.stdout[-3000:]}\n" \
                              f"{r.stderr[-6000:]}"
    return out


def test_the_guide_builds_strictly_into_a_site(site):
    assert (site / "index.html").is_file() and (site / "404.html").is_file()
    assert (site / "search" / "search_index.json").is_file()


def test_the_configuration_loads_nothing_from_outside():
    cfg = _config()
    assert cfg["theme"]["name"] == "material" and cfg["theme"]["font"] is False
    assert cfg["site_dir"] == "site" and "site/" in (ROOT / ".gitignore").read_text().split()
    plugins = [p if isinstance(p, str) else next(iter(p)) for p in cfg["plugins"]]
    assert "search" in plugins and "mkdocstrings" in plugins
    text = (ROOT / "mkdocs.yml").read_text()
    assert "extra_javascript" not in text and "extra_css" not in text   # nothing from a CDN
    assert "arithmatex" not in text


def test_the_guide_has_its_sections_and_every_page_is_in_the_navigation(site):
    files = [f for _, f in _nav_files(_config()["nav"])]
    for what, page in SECTIONS.items():
        assert page in files, f"{what}: {page} is not in mkdocs.yml's nav"
    pages = sorted(str(p.relative_to(DOCS)) for p in DOCS.rglob("*.md"))
    assert sorted(files) == pages, "a page of docs/ outside the navigation, or the reverse"
    for page in files:
        built = site / ("index.html" if page == "index.md" else page[:-3] + "/index.html")
        assert built.is_file(), page
        assert "<h1" in built.read_text(), page


def test_no_page_reads_as_change_notes():
    for page in DOCS.rglob("*.md"):
        text = page.read_text()
        name = page.relative_to(DOCS)
        assert not DATE.findall(text), (name, DATE.findall(text))
        assert not ISSUE.findall(text), (name, ISSUE.findall(text))
        assert not COMMIT.findall(text), (name, COMMIT.findall(text))
        for phrase in ("before this branch", "this branch", "../shared/"):
            assert phrase not in text.lower(), (name, phrase)
    assert not any(p.suffix == ".py" for p in DOCS.rglob("*")), "scripts live in scripts/"


def _inline_hashes(html: str) -> set[str]:
    out = set()
    for attrs, code in re.findall(r"<script(?![^>]*\bsrc=)([^>]*)>(.*?)</script>", html, re.S):
        if "application/json" not in attrs:
            digest = base64.b64encode(hashlib.sha256(code.encode()).digest()).decode()
            out.add(f"'sha256-{digest}'")
    return out


def test_the_explorer_serves_the_built_guide(site):
    with TestClient(create_app(settings_for_tests(warm_workers=False, guide_dir=site))) as c:
        home = c.get("/guide/")
        assert home.status_code == 200 and "text/html" in home.headers["content-type"]
        assert home.text == (site / "index.html").read_text()
        csp = home.headers["content-security-policy"]
        assert "unsafe-inline" not in csp.split("script-src")[1].split(";")[0]
        assert _inline_hashes(home.text) and all(h in csp for h in _inline_hashes(home.text))
        assert "default-src 'self'" in csp and "https:" not in csp
        page = c.get("/guide/getting-started/")
        assert page.status_code == 200 and "mkdocs" not in page.url.path
        assert c.get("/guide/getting-started", follow_redirects=False).status_code == 308
        assert c.get("/guide", follow_redirects=False).headers["location"].endswith("/guide/")
        for ref in re.findall(r'(?:src|href)="([^"#?]+)"', home.text):
            if not ref.startswith(("http", "mailto:", "/", "data:")):
                assert c.get("/guide/" + ref).status_code == 200, ref
        assert c.get("/guide/search/search_index.json").status_code == 200
        assert c.get("/guide/no-such-page/").status_code == 404
        assert c.get("/guide/%2e%2e/pyproject.toml").status_code == 404


def test_without_the_built_guide_it_says_how_to_build_it(tmp_path):
    with TestClient(create_app(settings_for_tests(warm_workers=False,
                                                  guide_dir=tmp_path / "nothing"))) as c:
        r = c.get("/guide/")
        assert r.status_code == 200 and "text/html" in r.headers["content-type"]
        assert "mkdocs build" in r.text and "docs/" in r.text
        assert '<a href="/guide/" aria-current="page">Guide</a>' in r.text
        assert c.get("/guide/explorer/").status_code == 404


def test_every_page_of_the_explorer_links_the_guide():
    with TestClient(create_app(settings_for_tests(warm_workers=False))) as c:
        for path in ("/", "/errata", "/glossary", "/case/plane/chaplygin-ball"):
            nav = c.get(path).text.split('<nav aria-label="Site">')[1].split("</nav>")[0]
            assert '<a href="/guide/">Guide</a>' in nav, path
