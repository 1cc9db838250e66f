"""The teaching demos on a warm server, in a real browser (Debian chromium, software
rendering as on a laptop without a GPU driver for it): the time from a click on a scene's
Play to its first claim plot and to its 3D view, where the 3D view's time goes (the
request of POST /api/scene, its answer, the drawing), and the time from a click on a case
page's Run to its plots.

    PYTHONPATH=$PWD python bench/demos_timing.py [--repeat 3] [--scene ID] [--case ID]

"Warm": the server has answered each scene and each case's run once before (checks kept
per server process, kernels compiled); then every click is timed --repeat times and the
median printed. The breakdown comes from app/static/js/scenes.js's performance marks
(scene:play, scene:first-plot, scene:3d-request, scene:3d-data, scene:3d-drawn) and the
browser's resource timing of /api/scene.
"""

from __future__ import annotations

import argparse
import os
import statistics
import time

from playwright.sync_api import sync_playwright

from app.testing import live_server, wait_idle
from bench.scene_screens import click_to_plot
from catalogue.scenes import load_scenes

CHROMIUM = os.environ.get("ROLLING_CHROMIUM", "/usr/bin/chromium")
CASES = ["plane/chaplygin-ball", "plane/round-disk", "sphere/borisov-fedorov"]

MARKS = """() => {
  const m = Object.fromEntries(performance.getEntriesByType('mark')
    .filter((e) => e.name.startsWith('scene:')).map((e) => [e.name.slice(6), e.startTime]));
  const r = performance.getEntriesByType('resource')
    .filter((e) => e.name.endsWith('/api/scene')).pop();
  return { ...m, server: r ? r.responseStart - r.requestStart : null,
           download: r ? r.responseEnd - r.responseStart : null,
           bytes: r ? r.encodedBodySize : null };
}"""


def scene_click(page, url: str, sid: str) -> dict:
    first, shown = click_to_plot(page, url, sid, clear_timings=True)
    m = page.evaluate(MARKS)
    out = {"first plot": first, "3D shown": shown}
    if "3d-drawn" not in m:         # a page without the marks (an older scenes.js)
        return out
    return {**out, "page: first plot": (m["first-plot"] - m["play"]) / 1e3,
            "page: 3D drawn": (m["3d-drawn"] - m["play"]) / 1e3,
            "3D request after play": (m["3d-request"] - m["play"]) / 1e3,
            "server": m["server"] / 1e3, "download": m["download"] / 1e3,
            "answer": (m["3d-data"] - m["3d-request"]) / 1e3,
            "draw": (m["3d-drawn"] - max(m["3d-data"], m["first-plot"])) / 1e3,
            "kB": m["bytes"] / 1e3}


def case_run(page, url: str, case: str) -> dict:
    page.goto(f"{url}/case/{case}")
    page.wait_for_function("document.body?.dataset.ready === '1'", timeout=60_000)
    t0 = time.perf_counter()
    page.click("#run")
    page.wait_for_function("document.body.dataset.run === '1'", timeout=120_000)
    took = time.perf_counter() - t0
    m = page.evaluate("""() => Object.fromEntries(performance.getEntriesByType('mark')
        .filter((e) => e.name.startsWith('run:')).map((e) => [e.name.slice(4), e.startTime]))""")
    return {"all plots": took, "page: answer": (m["data"] - m["click"]) / 1e3,
            "page: first plot": (m["first-plot"] - m["click"]) / 1e3,
            "page: all plots": (m["plots"] - m["click"]) / 1e3}


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--scene", action="append")
    ap.add_argument("--case", action="append")
    a = ap.parse_args()
    # kernels_warm=False: a first use compiles outside the deadline, as on a real server
    with (live_server(max_steps=10**9, deadline_s=60.0, kernels_warm=False) as url,
          sync_playwright() as pw):
        wait_idle(url, timeout=600)
        browser = pw.chromium.launch(executable_path=CHROMIUM, headless=True,
                                     args=["--no-sandbox", "--disable-gpu"])
        # bypass_csp: wait_for_function evaluates its predicate, which the policy forbids
        page = browser.new_page(viewport={"width": 1280, "height": 720}, bypass_csp=True)
        print("scene: median of the clicks, s. 'first plot', '3D shown': Python's clock from "
              "the click to the claim plot's svg / to body[data-playing]; 'page: ...': the "
              "page's own marks from the click's handler; 3D request: sent after the click; "
              "server: request to first byte; answer: request to parsed JSON; draw: Plotly, "
              "from the data (and the first plot) to the 3D drawn")
        for sid in a.scene or load_scenes():
            scene_click(page, url, sid)                         # warm the server
            runs = [scene_click(page, url, sid) for _ in range(a.repeat)]
            med = {k: statistics.median(r[k] for r in runs) for k in runs[0]}
            print(f"{sid:30s} " + "  ".join(f"{k} {v:.2f}" if k != "kB" else f"{v:.0f} kB"
                                            for k, v in med.items()), flush=True)
        for case in a.case or CASES:
            case_run(page, url, case)
            runs = [case_run(page, url, case) for _ in range(a.repeat)]
            med = {k: statistics.median(r[k] for r in runs) for k in runs[0]}
            print(f"case page {case}, click on Run -> " +
                  "  ".join(f"{k} {v:.2f}" for k, v in med.items()), flush=True)
        browser.close()


if __name__ == "__main__":
    main()
