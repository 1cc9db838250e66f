"""The pages work under the server's Content-Security-Policy (app/core/guards.py): loaded in
a browser context that enforces it, every page renders (KaTeX with its fonts, plotly.js
plots, Swagger UI) and the browser refuses nothing. Waits use selectors only (no eval)."""

import pytest

PAGES = [
    ("/", ".katex"),
    ("/case/plane/chaplygin-ball", ".katex"),
    ("/poincare", ".js-plotly-plot"),
    ("/scenes", "a[href^='/scenes#'], [data-scene], li"),
    ("/work-precision", ".js-plotly-plot"),
    ("/docs", ".swagger-ui .opblock"),
]



@pytest.mark.parametrize("path,ready", PAGES)
def test_page_renders_under_the_csp(strict, server, path, ready):
    page, refused = strict
    fonts = []
    page.on("response", lambda r: fonts.append(r.status) if r.url.endswith(".woff2") else None)
    response = page.goto(server + path)
    assert "default-src 'self'" in response.headers["content-security-policy"]
    page.wait_for_selector(ready, state="attached")
    page.wait_for_load_state("networkidle")
    assert not refused, refused
    if path in ("/", "/case/plane/chaplygin-ball"):
        assert fonts and set(fonts) == {200}, fonts    # KaTeX's fonts loaded
