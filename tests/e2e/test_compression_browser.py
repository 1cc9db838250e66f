"""Bytes a case page moves, counted by the browser (issue 17 item 8): every request the
page makes, its headers and its body as transferred (compressed), summed once the page is
idle. Before: 5.3 MB, plotly.js sent as its 4.8 MB."""

import time

import httpx
import pytest

from app.testing import live_server, wait_idle

LIMIT = 1.5e6


@pytest.fixture(scope="module")
def compressing_server():
    with live_server(precompress=True) as url:
        wait_idle(url, timeout=600)
        # the start-up makes the Brotli forms in the background: wait for plotly.js's
        deadline = time.monotonic() + 600
        while httpx.get(f"{url}/vendor/plotly.min.js", timeout=30,
                        headers={"accept-encoding": "br"}).headers.get(
                            "content-encoding") != "br":
            assert time.monotonic() < deadline, "plotly.js never compressed"
            time.sleep(2)
        yield url


def test_a_case_page_moves_under_1_5_mb(browser, browser_context_args, compressing_server):
    # a new context, its HTTP cache empty: every byte is moved (the suite's `page` is a tab
    # of a profile that other tests fill, tests/e2e/conftest.py)
    ctx = browser.new_context(**browser_context_args)
    page = ctx.new_page()
    moved: dict[str, int] = {}
    encodings: dict[str, str] = {}

    def finished(request):
        sizes = request.sizes()
        moved[request.url] = (moved.get(request.url, 0) + sizes["responseBodySize"]
                              + sizes["responseHeadersSize"] + sizes["requestHeadersSize"]
                              + sizes["requestBodySize"])
        resp = request.response()
        if resp is not None:
            encodings[request.url] = resp.headers.get("content-encoding", "")

    page.on("requestfinished", finished)
    page.goto(f"{compressing_server}/case/plane/chaplygin-ball", wait_until="networkidle")
    page.wait_for_timeout(1000)
    total = sum(moved.values())
    plotly = next(u for u in moved if u.endswith("/vendor/plotly.min.js"))
    print(f"case page: {len(moved)} requests, {total / 1e6:.3f} MB moved; "
          f"plotly.js {moved[plotly] / 1e6:.3f} MB ({encodings[plotly]})")
    for u, n in sorted(moved.items(), key=lambda kv: -kv[1])[:8]:
        print(f"  {n:>9} {encodings.get(u) or 'identity':8} {u}")
    ctx.close()
    assert encodings[plotly] == "br"
    assert total < LIMIT, f"{total} bytes"
