"""Chromium's CPU for one opening of a page, by where the tab lives (issue 19, CI time).

The browser tests open their pages in tabs; what a tab costs depends on its profile:
  new-context  a new tab of a new off-the-record context (Playwright's `context` fixture,
               the suite's `page` before 2026-11-27): no compiled-code cache survives it;
  profile-tab  a new tab of one on-disk profile (`launch_persistent_context`), the suite's
               `page` since (tests/e2e/conftest.py);
  same-tab     the next page in the same tab (what the page sweep does).
Each mode opens the same pages in turn (two case pages, /scenes, /poincare, a text page),
three rounds, the modes interleaved; an opening is goto, network idle and 300 ms, as the
tests settle a page. Chromium's CPU is summed over its processes from /proc (user +
system), per process, so it counts the renderer, the GPU process and the browser process.

    PYTHONPATH=$PWD .venv/bin/python bench/browser_tab_cost.py
        -> bench/results/browser_tab_cost.txt
"""

import os
import statistics
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path[:0] = [str(ROOT)]

from playwright.sync_api import sync_playwright  # noqa: E402

from app.testing import live_server, wait_idle  # noqa: E402
from bench.cpu_by_process import snapshot  # noqa: E402
from tests.e2e.conftest import ARGS, CHROMIUM  # noqa: E402

OUT = ROOT / "bench" / "results" / "browser_tab_cost.txt"
PAGES = ["/case/plane/ellipsoid", "/case/sphere/routh-ball", "/scenes", "/poincare",
         "/how-we-check"]
MODES = ("new-context", "profile-tab", "same-tab")
ROUNDS = 3
VIEW = {"viewport": {"width": 1500, "height": 950}, "device_scale_factor": 1,
        "bypass_csp": True}


def opening(page, url: str) -> float:
    """Chromium's CPU over one opening: the processes alive at its end, each counted from
    its value at the start (or from 0 if it started since). A process that exits meanwhile
    (a closed tab's renderer) is left out, not subtracted."""
    time.sleep(0.5)                 # the previous tab's processes exit first
    c0 = snapshot("chrom")
    page.goto(url)
    page.wait_for_load_state("networkidle")
    page.wait_for_timeout(300)
    return sum(v - c0.get(k, 0.0) for k, v in snapshot("chrom").items())


def main() -> None:
    seen: dict = {(m, p): [] for m in MODES for p in PAGES}
    head = (f"browser tab cost, {time.strftime('%Y-%m-%d %H:%M UTC', time.gmtime())}, load "
            f"average at the start {' '.join(f'{x:.2f}' for x in os.getloadavg())}")
    with live_server(max_steps=10**9, deadline_s=30.0) as url, sync_playwright() as pw:
        wait_idle(url, timeout=600)
        launch = {"executable_path": CHROMIUM, "args": ARGS, "headless": True}
        browser = pw.chromium.launch(**launch)
        profile = pw.chromium.launch_persistent_context(tempfile.mkdtemp(), **launch, **VIEW)
        same = browser.new_context(**VIEW).new_page()
        for _ in range(ROUNDS):
            for path in PAGES:
                for mode in MODES:
                    if mode == "new-context":
                        ctx = browser.new_context(**VIEW)
                        seen[mode, path].append(opening(ctx.new_page(), url + path))
                        ctx.close()
                    elif mode == "profile-tab":
                        tab = profile.new_page()
                        seen[mode, path].append(opening(tab, url + path))
                        tab.close()
                    else:
                        seen[mode, path].append(opening(same, url + path))
        profile.close()
        browser.close()
    lines = [head, "chromium CPU seconds per opening, median (min-max) of "
             f"{ROUNDS} rounds; the first round includes each mode's first compile",
             f"{'page':26s}" + "".join(f"{m:>22s}" for m in MODES)]
    for path in PAGES:
        cells = []
        for m in MODES:
            v = seen[m, path]
            cells.append(f"{statistics.median(v):6.2f} ({min(v):.2f}-{max(v):.2f})")
        lines.append(f"{path:26s}" + "".join(f"{c:>22s}" for c in cells))
    tot = {m: sum(sum(seen[m, p]) for p in PAGES) for m in MODES}
    lines.append(f"{'all openings, total':26s}" + "".join(f"{tot[m]:22.1f}" for m in MODES))
    lines.append(f"load average at the end {' '.join(f'{x:.2f}' for x in os.getloadavg())}")
    text = "\n".join(lines) + "\n"
    OUT.write_text(text)
    print(text, end="")


if __name__ == "__main__":
    main()
