"""Compressed answers (issue 17 item 8, app/core/compress.py): static files and plotly.js
as Brotli or gzip made once, route answers through gzip, the Poincaré stream left as a
stream. (Before: plotly.min.js went out as its 4.8 MB.)"""

import gzip
import json

import pytest
from fastapi.testclient import TestClient

from app.api.routes.pages import plotly_js
from app.core import compress
from app.main import create_app
from app.testing import settings_for_tests

pytestmark = pytest.mark.filterwarnings("ignore::DeprecationWarning")


@pytest.fixture(scope="module")
def client(tmp_path_factory):
    s = settings_for_tests(warm_workers=False, cache_dir=tmp_path_factory.mktemp("cache"))
    with TestClient(create_app(s)) as c:
        yield c


def _raw(client, path, enc):
    """The bytes on the wire (TestClient would decode them)."""
    with client.stream("GET", path, headers={"accept-encoding": enc}) as r:
        return r, b"".join(r.iter_raw())


def test_plotly_goes_out_gzip_and_brotli(client):
    r, body = _raw(client, "/vendor/plotly.min.js", "gzip")
    plain = plotly_js()
    size = plain.stat().st_size
    assert r.headers["content-encoding"] == "gzip"
    assert "accept-encoding" in r.headers["vary"].lower()
    assert int(r.headers["content-length"]) == len(body) < size / 3
    assert gzip.decompress(body) == plain.read_bytes()
    assert r.headers["content-type"].startswith("text/javascript")
    assert r.headers["x-content-type-options"] == "nosniff"
    if compress.brotli is None:
        pytest.skip("brotli not installed")
    client.app.state.assets.make(plain, "br")        # what the start-up does
    r, body = _raw(client, "/vendor/plotly.min.js", "gzip, deflate, br")
    assert r.headers["content-encoding"] == "br"
    assert compress.brotli.decompress(body) == plain.read_bytes() and len(body) < size / 3.5


def test_static_files_and_json_are_compressed_when_accepted_only(client):
    for path in ("/static/js/case.js", "/api/cases/plane/chaplygin-ball",
                 "/case/plane/chaplygin-ball"):
        r, body = _raw(client, path, "gzip")
        assert r.headers.get("content-encoding") == "gzip", path
        text = gzip.decompress(body)
        r2, body2 = _raw(client, path, "identity")
        assert "content-encoding" not in r2.headers and body2 == text, path
        assert len(body) < len(text) / 2, path


def test_a_range_request_gets_the_plain_bytes(client):
    r = client.get("/static/js/case.js", headers={"accept-encoding": "gzip",
                                                  "range": "bytes=0-99"})
    assert r.status_code == 206 and "content-encoding" not in r.headers
    assert len(r.content) == 100


def test_q_zero_refuses_an_encoding():
    from starlette.datastructures import Headers

    assert compress.accepted(Headers({"accept-encoding": "gzip;q=0, br;q=0"})) == []
    assert compress.accepted(Headers({"accept-encoding": "gzip"})) == ["gzip"]


def test_the_poincare_stream_is_not_compressed(client):
    body = {"case": "plane/chaplygin-ball", "example": True, "energy": 1.0,
            "section": "g=0", "trajectories": 2, "points": 3}
    with client.stream("POST", "/api/poincare", params={"stream": True}, json=body,
                       headers={"accept-encoding": "gzip, br"}) as r:
        assert r.status_code == 200
        assert "content-encoding" not in r.headers
        lines = [json.loads(x) for x in r.iter_lines() if x]
    # the stream opens with its estimate (issue 20), then progress on every trajectory
    assert lines[0]["event"] == "estimate"
    assert {"event": "progress", "done": 0, "total": 2} in lines
    assert lines[-1]["event"] == "result" and len(lines[-1]["result"]["trajectories"]) == 2
