"""What one frame of a 3D scene costs chromium without a GPU, by the WebGL pixel ratio.

A scene (app/static/js/scene.js) plays by moving the body, its axes and its path with
Plotly.restyle at every frame; the WebGL view is then drawn again. Without a GPU (these
machines, CI, many school laptops) chromium rasterizes WebGL in software in its GPU
process. Plotly draws its WebGL plots at `plotGlPixelRatio` times the CSS size, 2 by
default whatever the screen; app/static/js/plots.js sets it to the screen's own
devicePixelRatio (1 here). Both are timed side by side in one browser on one server, the
old one served by rewriting plots.js in flight (Playwright's page.route), modes
interleaved, 3 rounds per scene. A round opens /scenes#ID at 1280x720 (a projector),
waits until it plays, pauses it, and then shows frames 1..40 with the scrubber, waiting
two animation frames after each (the frame drawn). Chromium's CPU per frame is summed
per kind of process from /proc (bench/cpu_by_process.py).

    PYTHONPATH=$PWD .venv/bin/python bench/scene_frame_cost.py
        -> bench/results/scene_frame_cost.txt
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
from bench.cpu_by_process import kind, snapshot  # noqa: E402
from tests.e2e.conftest import ARGS, CHROMIUM  # noqa: E402

OUT = ROOT / "bench" / "results" / "scene_frame_cost.txt"
SCENES = ["chaplygin-ball-quasiperiodic", "rolling-disk-stays-up", "rattleback-spin-reversal"]
FRAMES = 40
ROUNDS = 3
VIEW = {"viewport": {"width": 1280, "height": 720}, "device_scale_factor": 1,
        "bypass_csp": True}
PLOTS_JS = (ROOT / "app" / "static" / "js" / "plots.js").read_text()
SCREEN = "plotGlPixelRatio: Math.min(4, Math.max(1, window.devicePixelRatio || 1))"
assert SCREEN in PLOTS_JS, "plots.js no longer sets plotGlPixelRatio as this bench expects"
MODES = {"plotly default (2)": PLOTS_JS.replace(SCREEN, "plotGlPixelRatio: 2"),
         "screen's own (1)": PLOTS_JS}

STEP = """async (n) => {
  const s = document.getElementById('scrub');
  for (let f = 1; f <= n; f++) {
    s.value = String(f); s.dispatchEvent(new Event('input'));
    await new Promise((r) => requestAnimationFrame(() => requestAnimationFrame(r)));
  }
}"""


def one_round(ctx, url: str, scene: str, plots_js: str) -> dict:
    tab = ctx.new_page()
    tab.route("**/static/js/plots.js", lambda route: route.fulfill(
        status=200, content_type="text/javascript", body=plots_js))
    tab.goto(f"{url}/scenes#{scene}")
    tab.locator(f"body[data-playing='{scene}']").wait_for(state="attached", timeout=90_000)
    tab.click("#play")                       # pause: only the frames below are drawn
    tab.wait_for_timeout(500)
    c0, w0 = snapshot("chrom"), time.perf_counter()
    tab.evaluate(STEP, FRAMES)
    wall = time.perf_counter() - w0
    c1 = snapshot("chrom")
    out = {"wall": wall / FRAMES * 1e3}
    for k, v in c1.items():          # kinds read before the tab closes (its renderer exits)
        name = kind(k[0]) or "chromium other"
        out[name] = out.get(name, 0.0) + (v - c0.get(k, 0.0)) / FRAMES * 1e3
    out["chromium"] = sum(v for n, v in out.items() if n.startswith("chromium"))
    tab.close()
    return out


def main() -> None:
    head = (f"scene frame cost, {time.strftime('%Y-%m-%d %H:%M UTC', time.gmtime())}, load "
            f"average at the start {' '.join(f'{x:.2f}' for x in os.getloadavg())}")
    seen = {(s, m): [] for s in SCENES for m in MODES}
    with live_server(max_steps=10**9, deadline_s=30.0) as url, sync_playwright() as pw:
        wait_idle(url, timeout=600)
        ctx = pw.chromium.launch_persistent_context(
            tempfile.mkdtemp(), executable_path=CHROMIUM, args=ARGS, headless=True, **VIEW)
        for _ in range(ROUNDS):
            for scene in SCENES:
                for mode, js in MODES.items():
                    seen[scene, mode].append(one_round(ctx, url, scene, js))
        ctx.close()
    cols = ("chromium GPU", "chromium renderer", "chromium", "wall")
    lines = [head, f"per frame, ms, median of {ROUNDS} rounds of {FRAMES} frames (1280x720, "
             "device pixel ratio 1, no GPU)",
             f"{'scene':30s} {'WebGL pixel ratio':20s} " + " ".join(f"{c:>18s}" for c in cols)]
    for scene in SCENES:
        med = {m: {c: statistics.median(r.get(c, 0.0) for r in seen[scene, m]) for c in cols}
               for m in MODES}
        for m in MODES:
            lines.append(f"{scene:30s} {m:20s} " + " ".join(f"{med[m][c]:18.0f}" for c in cols))
        old, new = med["plotly default (2)"], med["screen's own (1)"]
        lines.append(f"{'':30s} {'ratio new/old':20s} " + " ".join(
            f"{new[c] / old[c]:18.2f}" if old[c] else f"{'-':>18s}" for c in cols))
    text = "\n".join(lines) + "\n"
    print(text, end="")
    OUT.write_text(text)


if __name__ == "__main__":
    main()
