"""Server-rendered pages are built once per state of the verdicts (app/services/page_cache.py):
asked again they are a lookup; a verdict computed, a check started or finished, or the
template edited makes the next request build them again, with the new content."""

import os

import pytest
from fastapi.testclient import TestClient

from app.main import create_app
from app.testing import settings_for_tests
from catalogue.load import load_catalogue

pytestmark = pytest.mark.filterwarnings("ignore::DeprecationWarning")
CASE = "sphere/borisov-fedorov"


def test_pages_are_cached_until_the_verdicts_change(tmp_path):
    app = create_app(settings_for_tests(warm_workers=False, cache_dir=tmp_path))
    with TestClient(app) as client:
        pages, store = app.state.pages, app.state.verdicts
        home = client.get("/").text
        case = client.get(f"/case/{CASE}").text
        built = pages.renders
        assert built == 2
        assert client.get("/").text == home and client.get(f"/case/{CASE}").text == case
        assert pages.renders == built                     # served from the cache
        # issue 17: the marks (shape and name) instead of the coarse verdict's words
        assert "— not checkable" in case and "✗ fails" not in case
        # a verdict is computed: both pages are built again and show it
        claim = load_catalogue().case(CASE).claims[0].id
        store.put(CASE, [{"claim": claim, "verdict": "fails", "residual": 0.5,
                          "message": "a test verdict"}])
        case2 = client.get(f"/case/{CASE}").text
        assert pages.renders == built + 1 and "✗ fails" in case2
        client.get("/")
        assert pages.renders == built + 2
        # a check starts (a fresh server's background verification): built again
        store.state = "running"
        assert 'class="badge pending"' in client.get("/case/plane/chaplygin-ball").text
        store.state = "done"
        assert 'class="badge pending"' not in client.get("/case/plane/chaplygin-ball").text
        # the template changes on disk (a developer editing case.html): built again
        n = pages.renders
        path = app.state.settings.static_dir / "case.html"
        st = path.stat()
        os.utime(path, ns=(st.st_atime_ns, st.st_mtime_ns + 1_000_000))
        try:
            client.get(f"/case/{CASE}")
            assert pages.renders == n + 1
        finally:
            os.utime(path, ns=(st.st_atime_ns, st.st_mtime_ns))
