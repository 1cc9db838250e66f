"""Where the desktop page sweep's time goes (tests/e2e/test_page_sweep_browser.py, the
costliest browser test of the suite: issue 19, CI time).

Every page of the site (tests/e2e/site.py) opened as the sweep opens it, on a server as the
browser tests start it, in Debian's chromium: per page, the seconds to settle (goto, the
page's scripts, network idle, the sweep's 300 ms), to read the reader's text and inject
axe-core, axe's run, and the rest (details opened, texts read again).

    PYTHONPATH=$PWD:$PWD/tests .venv/bin/python bench/page_sweep_cost.py
        -> bench/results/page_sweep_cost.txt
"""

import itertools
import os
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path[:0] = [str(ROOT), str(ROOT / "tests")]

from playwright.sync_api import sync_playwright  # noqa: E402

from app.testing import live_server, wait_idle  # noqa: E402
from tests.e2e.conftest import ARGS, CHROMIUM  # noqa: E402
from tests.e2e.site import project_pages  # noqa: E402
from tests.e2e.test_page_sweep_browser import AXE, AXE_RUN, READER_TEXT, settle  # noqa: E402

OUT = ROOT / "bench" / "results" / "page_sweep_cost.txt"


def main() -> None:
    lines = [f"page sweep cost, {time.strftime('%Y-%m-%d %H:%M UTC', time.gmtime())}, "
             f"load average {' '.join(f'{x:.2f}' for x in os.getloadavg())}",
             f"{'page':45s} {'settle':>7s} {'text+inject':>12s} {'axe':>6s} {'rest':>6s}"]
    tot = [0.0] * 4
    with live_server(max_steps=10**9, deadline_s=30.0) as url:
        wait_idle(url, timeout=600)
        paths = project_pages(url)
        with sync_playwright() as p:
            browser = p.chromium.launch(executable_path=CHROMIUM, args=ARGS, headless=True)
            page = browser.new_context(viewport={"width": 1500, "height": 950},
                                       bypass_csp=True).new_page()
            for path in paths:
                t = [time.perf_counter()]
                settle(page, url + path, path)
                t.append(time.perf_counter())
                page.evaluate(READER_TEXT)
                page.add_script_tag(path=str(AXE))
                t.append(time.perf_counter())
                page.evaluate(AXE_RUN)
                t.append(time.perf_counter())
                page.evaluate("document.querySelectorAll('details').forEach(d => d.open = true)")
                page.locator("body").inner_text()
                page.evaluate(READER_TEXT)
                t.append(time.perf_counter())
                d = [b - a for a, b in itertools.pairwise(t)]
                tot = [x + y for x, y in zip(tot, d, strict=True)]
                lines.append(f"{path[:45]:45s} {d[0]:7.2f} {d[1]:12.2f} {d[2]:6.2f} {d[3]:6.2f}")
                print(lines[-1], flush=True)
            browser.close()
    lines.append(f"{f'total, {len(paths)} pages':45s} {tot[0]:7.2f} {tot[1]:12.2f} "
                 f"{tot[2]:6.2f} {tot[3]:6.2f}   ({sum(tot):.1f} s)")
    print(lines[-1])
    OUT.write_text("\n".join(lines) + "\n")


if __name__ == "__main__":
    main()
