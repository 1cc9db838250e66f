"""The built user guide under the explorer's Content-Security-Policy (app/api/routes/guide.py:
each page allows its own inline scripts by hash, nothing else): built with mkdocs into a
temporary directory and served at /guide/ by a server pointed at it (ROLLING_GUIDE_DIR), it
renders, navigates and searches in a context that enforces the policy, and the browser
refuses nothing. Waits use selectors and key presses only (no eval before the page runs)."""

import os
import subprocess
import sys
from pathlib import Path

import pytest

from app.testing import live_server

ROOT = Path(__file__).resolve().parents[2]


@pytest.fixture(scope="module")
def guide_server(tmp_path_factory):
    site = tmp_path_factory.mktemp("guide") / "site"
    r = subprocess.run([sys.executable, "-m", "mkdocs", "build", "-q", "-f",
                        str(ROOT / "mkdocs.yml"), "-d", str(site)], cwd=ROOT,
                       capture_output=True, text=True, timeout=600,
                       env={**os.environ, "NO_MKDOCS_2_WARNING": "1"})
    assert r.returncode == 0, r.stderr[-4000:]
    with live_server(guide_dir=str(site), warm_workers=False) as url:
        yield url



def test_the_guide_renders_navigates_and_searches_under_the_csp(strict, guide_server):
    page, refused = strict
    response = page.goto(guide_server + "/guide/")
    csp = response.headers["content-security-policy"]
    assert "default-src 'self'" in csp and "'sha256-" in csp and "unsafe-inline" not in \
        csp.split("script-src")[1].split(";")[0]
    page.wait_for_selector("nav.md-nav", state="attached")
    page.wait_for_load_state("networkidle")
    # the theme's own script ran: its navigation and search are there
    page.click("nav.md-nav--primary >> text=Integrators and accuracy")
    page.wait_for_url("**/guide/integrators/")
    page.wait_for_selector("h1:has-text('Integrators and accuracy')")
    # search: the worker and the index come from this server
    page.click("input.md-search__input")
    page.keyboard.type("guarantees", delay=30)
    page.wait_for_selector(".md-search-result__item")
    assert not refused, refused
