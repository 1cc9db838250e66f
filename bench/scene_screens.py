"""The teaching scenes on a warm server: the time from a click on a scene's Play to its
first claim plot (and to the 3D animation playing), and screenshots of every scene and of
/poincare at 1280x720 (a projector) and at 390 px (a phone) for docs/screenshots/.

    PYTHONPATH=$PWD python bench/scene_screens.py [--out docs/screenshots] [--no-shots]

"Warm": the server has answered each scene once before (its checks are kept per server
process, its kernels compiled); the click is then timed three times and the median printed.
"""

from __future__ import annotations

import argparse
import os
import statistics
import time
from pathlib import Path

from playwright.sync_api import sync_playwright

from app.testing import live_server, wait_idle
from catalogue.scenes import load_scenes

ROOT = Path(__file__).resolve().parents[1]
CHROMIUM = os.environ.get("ROLLING_CHROMIUM", "/usr/bin/chromium")
SIZES = {"1280": (1280, 720), "390": (390, 844)}


def click_to_plot(page, url: str, sid: str, clear_timings: bool = False) -> tuple[float, float]:
    """Seconds from the click on a scene to its first claim plot and to its 3D view playing
    (clear_timings: empty the page's resource timings first, for bench/demos_timing.py)."""
    page.goto(url + "/scenes")
    page.locator(f'a[data-scene="{sid}"]').wait_for()
    if clear_timings:
        page.evaluate("performance.clearResourceTimings()")
    t0 = time.perf_counter()
    page.click(f'a[data-scene="{sid}"]')
    page.locator("[data-testid=claim-plot] .main-svg").first.wait_for(state="attached",
                                                                      timeout=120_000)
    first = time.perf_counter() - t0
    page.locator(f"body[data-playing='{sid}']").wait_for(state="attached", timeout=120_000)
    return first, time.perf_counter() - t0


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--out", type=Path, default=ROOT / "docs" / "screenshots")
    ap.add_argument("--no-shots", action="store_true")
    ap.add_argument("--no-timing", action="store_true")
    a = ap.parse_args()
    a.out.mkdir(parents=True, exist_ok=True)
    with live_server(max_steps=10**9, deadline_s=60.0) as url, sync_playwright() as pw:
        wait_idle(url, timeout=600)
        browser = pw.chromium.launch(executable_path=CHROMIUM, headless=True,
                                     args=["--no-sandbox", "--disable-gpu"])
        # bypass_csp: wait_for_function evaluates its predicate, which the policy forbids
        page = browser.new_page(viewport={"width": 1280, "height": 720}, bypass_csp=True)
        for sid in ([] if a.no_timing else load_scenes()):
            click_to_plot(page, url, sid)                     # warm the server
            runs = [click_to_plot(page, url, sid) for _ in range(3)]
            first = statistics.median(r[0] for r in runs)
            playing = statistics.median(r[1] for r in runs)
            print(f"{sid}: click -> first claim plot {first:.2f} s, -> 3D playing "
                  f"{playing:.2f} s", flush=True)
        if not a.no_shots:
            for w, (width, height) in SIZES.items():
                page.set_viewport_size({"width": width, "height": height})
                for sid in load_scenes():
                    click_to_plot(page, url, sid)
                    page.wait_for_timeout(800)
                    page.screenshot(path=str(a.out / f"scene-{sid}-{w}.png"))
                page.goto(url + "/poincare?case=plane/unbalanced-ball&energy=1&g0=0"
                          "&direction=1&trajectories=6&points=400&rtol=1e-10&seed=0&run=1")
                page.wait_for_function("document.body?.dataset.map === '1'", timeout=120_000)
                page.wait_for_timeout(800)
                page.screenshot(path=str(a.out / f"poincare-map-{w}.png"))
                print(f"screenshots at {w} px in {a.out}", flush=True)
        browser.close()


if __name__ == "__main__":
    main()
