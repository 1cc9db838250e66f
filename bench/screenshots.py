"""Screenshots of the explorer at 1400 px and at 390 px (a phone) for docs/screenshots/:
the home page, a case page and the Poincaré page (and /errata when the server has it).

    PYTHONPATH=$PWD python bench/screenshots.py [--out docs/screenshots] [--case ID]

A real uvicorn (app.testing.live_server) with the verdicts computed (or read from the
verdict store in the usual cache directory), driven by Debian's chromium through Playwright.
"""

from __future__ import annotations

import argparse
import os
import time
from pathlib import Path

import httpx
from playwright.sync_api import sync_playwright

from app.core.config import Settings
from app.testing import live_server, wait_idle

ROOT = Path(__file__).resolve().parents[1]
CHROMIUM = os.environ.get("ROLLING_CHROMIUM", "/usr/bin/chromium")
WIDTHS = {"1400": (1400, 1000), "390": (390, 844)}
MAX_HEIGHT = 3200          # a long page is cut here: the top is what a reader sees first


def wait_verdicts(url: str, timeout: float) -> dict:
    deadline = time.monotonic() + timeout
    while True:
        v = httpx.get(f"{url}/api/health", timeout=5).json()["verification"]
        if v["state"] != "running" or time.monotonic() > deadline:
            return v
        time.sleep(1.0)


def shoot(page, url: str, path: str, out: Path, name: str, width: str) -> Path:
    page.goto(url + path)
    if path == "/" or path.startswith("/case/"):
        page.wait_for_function("document.body?.dataset.ready === '1'", timeout=60_000)
    else:
        page.wait_for_load_state("networkidle")
    if path.startswith("/case/"):          # a case page with a run: its plots shown
        page.fill("#f-t_end", "60")
        page.click("#run")
        page.wait_for_function("document.body.dataset.run === '1'", timeout=120_000)
        page.evaluate("window.scrollTo(0, 0)")
    page.wait_for_timeout(1500)            # plots and KaTeX settle
    h = min(MAX_HEIGHT, page.evaluate("document.scrollingElement.scrollHeight"))
    w = WIDTHS[width][0]
    f = out / f"{name}-{width}.png"
    page.screenshot(path=str(f), full_page=True, clip={"x": 0, "y": 0, "width": w, "height": h})
    return f


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--out", type=Path, default=ROOT / "docs" / "screenshots")
    ap.add_argument("--case", default="plane/chaplygin-ball")
    ap.add_argument("--verify-timeout", type=float, default=900.0)
    args = ap.parse_args()
    args.out.mkdir(parents=True, exist_ok=True)
    with live_server(timeout=120, verify_on_start=True, use_verdict_cache=True,
                     cache_dir=Settings().cache_dir) as url:
        wait_idle(url, timeout=120)
        v = wait_verdicts(url, args.verify_timeout)
        print(f"verdicts: {v['cases_done']} of {v['cases_total']} cases ({v['state']})")
        pages = {"home": "/", "case": f"/case/{args.case}", "poincare": "/poincare"}
        if httpx.get(f"{url}/errata", timeout=10).status_code == 200:
            pages["errata"] = "/errata"
        with sync_playwright() as pw:
            browser = pw.chromium.launch(executable_path=CHROMIUM, headless=True,
                                         args=["--no-sandbox", "--disable-gpu"])
            for width, (w, h) in WIDTHS.items():
                # bypass_csp: wait_for_function evaluates its predicate with eval(),
                # which the pages' Content-Security-Policy forbids
                ctx = browser.new_context(viewport={"width": w, "height": h},
                                          device_scale_factor=1, bypass_csp=True)
                page = ctx.new_page()
                for name, path in pages.items():
                    print(shoot(page, url, path, args.out, name, width).resolve().relative_to(ROOT))
                ctx.close()
            browser.close()


if __name__ == "__main__":
    main()
