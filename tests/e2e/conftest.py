"""Browser tests: a real uvicorn on a free loopback port and Debian's chromium driven by
Playwright (never a downloaded browser build: no `playwright install`)."""

import os
import shutil
from pathlib import Path

import pytest

from app.testing import live_server, wait_idle

CHROMIUM = os.environ.get("ROLLING_CHROMIUM", "/usr/bin/chromium")
ARGS = ["--no-sandbox", "--headless", "--disable-gpu", "--disable-background-networking",
        "--disable-component-update", "--disable-sync", "--no-first-run"]
ARTIFACTS = Path(__file__).resolve().parents[2] / "test-artifacts" / "e2e"


def pytest_collection_modifyitems(config, items):
    if Path(CHROMIUM).exists() or shutil.which("chromium"):
        return
    if os.environ.get("CI"):
        return  # on CI a missing browser must fail loudly, not skip
    skip = pytest.mark.skip(reason=f"{CHROMIUM} not installed (./dev test installs it)")
    for item in items:
        if "e2e" in str(item.fspath):
            item.add_marker(skip)


@pytest.fixture(scope="session")
def browser_type_launch_args(browser_type_launch_args):
    return {**browser_type_launch_args, "executable_path": CHROMIUM, "args": ARGS,
            "headless": True}


@pytest.fixture(scope="session")
def browser_context_args(browser_context_args):
    # bypass_csp: Playwright's wait_for_function evaluates its predicates with eval() in
    # the page, which the server's policy forbids; the policy itself is exercised, with
    # no bypass, by tests/e2e/test_csp_browser.py
    return {**browser_context_args, "viewport": {"width": 1500, "height": 950},
            "device_scale_factor": 1, "bypass_csp": True}


@pytest.fixture(scope="session")
def server():
    with live_server(max_steps=10**9, deadline_s=30.0) as url:
        wait_idle(url, timeout=600)
        yield url


@pytest.fixture(scope="session")
def artifacts():
    ARTIFACTS.mkdir(parents=True, exist_ok=True)
    return ARTIFACTS


@pytest.fixture(scope="session")
def _profile_context(browser_type, browser_type_launch_args, browser_context_args,
                     tmp_path_factory):
    """One chromium profile on disk per test worker, which every test's `page` opens a tab
    in. Playwright's own `context` is a new off-the-record profile per test, which keeps no
    compiled-code cache: each test's first page then compiled plotly.js again (chromium's
    CPU for a case page in a new tab of a new context 4.3-5.0 s, in a new tab of this
    profile 1.8-2.0 s, medians: docs/performance.md), for ~60 tests (issue
    19: CI time). The app stores
    nothing in the browser (no cookie, no web storage), so the tabs share only the HTTP
    cache of static files. A test that needs a clean profile (the CSP, the bytes a page
    moves, a phone) makes its own context from `browser`."""
    ctx = browser_type.launch_persistent_context(
        str(tmp_path_factory.mktemp("chromium-profile")),
        **browser_type_launch_args, **browser_context_args)
    yield ctx
    ctx.close()


@pytest.fixture
def context(_profile_context):
    """The worker's profile (above); every tab a test opens in it is closed after it."""
    before = set(_profile_context.pages)
    yield _profile_context
    for p in _profile_context.pages:
        if p not in before:
            p.close()


@pytest.fixture
def page(context):
    """A new tab of the worker's profile, failing the test on any script error in the page
    and on anything the server's Content-Security-Policy refused (a script, a style, a
    font)."""
    page = context.new_page()
    errors = []
    page.on("pageerror", lambda e: errors.append(str(e)))
    page.on("console", lambda m: errors.append(m.text)
            if "Content Security Policy" in m.text else None)
    page.set_default_timeout(30_000)
    yield page
    assert not errors, f"errors in the page: {errors}"


@pytest.fixture
def strict(browser):
    """A context without the suite's bypass_csp, collecting what the policy refuses."""
    context = browser.new_context(viewport={"width": 1500, "height": 950})
    page = context.new_page()
    page.set_default_timeout(30_000)
    refused: list[str] = []
    page.on("console", lambda m: refused.append(m.text)
            if "Content Security Policy" in m.text else None)
    page.on("pageerror", lambda e: refused.append(str(e)))
    yield page, refused
    context.close()
