"""Browser layout test (issue 20): in every Plotly plot of /scenes (every scene), /poincare,
/work-precision and a case page (its run and its 3D view), no axis title, legend, plot
title or toolbar (modebar) overlaps another, no legend covers an x axis' tick labels, and
none is cut off by the plot's own box, at 1280 px and at 390 px (the scenes at 1280 px on
their one opening in tests/e2e/test_scenes_browser.py, which uses `problems` from here)."""

from functools import partial

import pytest

from solvers.scenes.teaching import load_scenes
from tests.e2e.test_maps_and_scenes_browser import draw_every_figure

# the parts of a plot a reader must be able to read, by Plotly's class names
BOXES = """(root) => [...document.querySelectorAll('.js-plotly-plot')].map((p) => {
  const r0 = p.getBoundingClientRect();
  const pick = (sel, kind) => [...p.querySelectorAll(sel)].map((e) => {
    const r = e.getBoundingClientRect();
    return { kind, x: r.x, y: r.y, w: r.width, h: r.height };
  }).filter((b) => b.w > 0 && b.h > 0);
  return { id: p.id || p.dataset.testid || p.className.split(' ')[0],
    box: { x: r0.x, y: r0.y, w: r0.width, h: r0.height },
    items: [...pick('.gtitle', 'title'), ...pick('.g-xtitle', 'x title'),
      ...pick('.g-ytitle', 'y title'), ...pick('.g-y2title', 'y2 title'),
      ...pick('.legend .bg', 'legend'), ...pick('.modebar', 'toolbar')],
    // the x axes' tick labels (2D plots), which a legend under the plot must clear
    ticks: pick('.xaxislayer-above text, .xaxislayer-below text', 'x tick labels') };
})"""


def overlap(a, b) -> float:
    w = min(a["x"] + a["w"], b["x"] + b["w"]) - max(a["x"], b["x"])
    h = min(a["y"] + a["h"], b["y"] + b["h"]) - max(a["y"], b["y"])
    return max(w, 0) * max(h, 0)


def problems(page) -> list[str]:
    out = []
    for plot in page.evaluate(BOXES):
        box, items = plot["box"], plot["items"]
        for i, a in enumerate(items):
            for b in items[i + 1:]:
                if overlap(a, b) > 4:          # px^2: touching is fine, covering is not
                    out.append(f"{plot['id']}: {a['kind']} overlaps {b['kind']} ({a}, {b})")
            if a["kind"] == "legend":
                out += [f"{plot['id']}: legend overlaps an x tick label ({a}, {t})"
                        for t in plot["ticks"] if overlap(a, t) > 4]
            inside = overlap(a, box) / (a["w"] * a["h"])
            if inside < 0.98:
                out.append(f"{plot['id']}: {a['kind']} cut off by the plot's box ({a}, {box})")
    return out


def case_page(page, server):
    page.goto(server + "/case/plane/chaplygin-ball")
    page.wait_for_function("document.body?.dataset.ready === '1'", timeout=60_000)
    page.click("#run")
    page.wait_for_function("document.body.dataset.run === '1'", timeout=120_000)
    # and its 3D view (app/static/js/scene.js), whose legend shares the plot with the body
    page.click("#scene-btn")
    page.wait_for_function("document.body.dataset.scene === '1'", timeout=120_000)


def scenes(page, server, sid):
    page.goto(f"{server}/scenes#{sid}")
    page.locator(f"body[data-playing='{sid}']").wait_for(state="attached", timeout=120_000)


def poincare(page, server):
    page.goto(server + "/poincare")
    draw_every_figure(page, timeout=90_000)
    page.fill("input[name=trajectories]", "2")
    page.fill("input[name=points]", "40")
    page.click("#run")
    page.wait_for_function("document.body.dataset.map === '1'", timeout=90_000)


def work_precision(page, server):
    page.goto(server + "/work-precision")
    page.locator(".wp-plot .main-svg").first.wait_for(state="attached", timeout=30_000)
    page.wait_for_timeout(500)


# every scene (its claim plots and its 3D view); the home page draws no plot
PAGES = {
    **{f"scenes-{sid}": partial(scenes, sid=sid) for sid in load_scenes()},
    "poincare": poincare,
    "work-precision": work_precision,
    "case": case_page,
}


# at 1280 px the scenes are checked on their one opening in tests/e2e/test_scenes_browser.py
CASES = [(name, 390) for name in PAGES] + [(name, 1280) for name in PAGES
                                            if not name.startswith("scenes-")]


@pytest.mark.parametrize(("name", "width"), CASES)
def test_no_plot_element_covers_another(page, server, name, width):
    page.set_viewport_size({"width": width, "height": 720 if width > 400 else 844})
    PAGES[name](page, server)
    page.wait_for_timeout(300)               # a responsive relayout after the first draw
    found = problems(page)
    assert page.evaluate(BOXES), "no plot on the page"
    assert not found, "\n".join(found[:12])
