"""Browser, a projector (1280x720): /poincare in three clicks (app/static/js/poincare.js).
The form has one labelled field per parameter of the chosen case, filled with the case's
example (for the unbalanced ball its offset a1, a2, a3 too) and checked against its range
as it is typed; a partial entry (fields left empty) merges with the example; the map
comes into view drawn twice, in 3D and beside it in 2D (l, L/G), no tick label on another;
its address computes it again."""

from playwright.sync_api import expect

from tests.e2e.test_plot_layout_browser import overlap

CASE = "plane/unbalanced-ball"

# the tick labels of the 2D view, by axis
TICKS = """() => { const p = document.getElementById('map-plot-2d');
  const boxes = (sel) => [...p.querySelectorAll(sel)].map((e) => e.getBoundingClientRect())
    .filter((r) => r.width > 0).map((r) => ({ x: r.x, y: r.y, w: r.width, h: r.height }));
  return { x: boxes('.xaxislayer-above .xtick text'), y: boxes('.yaxislayer-above .ytick text'),
           traces: p.data.length, points: p.data.reduce((n, t) => n + t.x.length, 0) }; }"""


def field(page, name):
    return page.locator(f'#param-fields input[name="p.{name}"]')


def in_view(page, selector):
    box = page.locator(selector).bounding_box()
    return box is not None and box["y"] >= 0 and box["y"] + box["height"] <= 720 + 1, box


def test_unbalanced_ball_map_from_a_partial_entry(page, server, artifacts):
    page.set_viewport_size({"width": 1280, "height": 720})
    page.goto(server + "/poincare")
    page.wait_for_function("document.body?.dataset.defaults === '1'", timeout=60_000)
    # the case's form is on the first screen: the case, then Compute
    assert in_view(page, "#run")[0], in_view(page, "#run")
    page.select_option("#case", CASE)
    expect(field(page, "a1")).to_have_value("0.1")
    for name, example in (("I1", "1"), ("I3", "3"), ("m", "1"), ("R", "1"), ("a2", "0.2"),
                          ("a3", "-0.15")):
        expect(field(page, name)).to_be_visible()
        assert float(field(page, name).input_value()) == float(example), name
    expect(page.locator('#param-fields label:has(input[name="p.a3"])')).to_contain_text("a3")

    # checked as it is typed: a field with its own message
    field(page, "m").fill("-1")
    expect(field(page, "m")).to_have_attribute("aria-invalid", "true")
    expect(page.locator("#pm-m")).to_contain_text("must be positive")
    field(page, "I1").fill("9")
    expect(page.locator("#pm-I1")).to_contain_text("sum of the other two")
    field(page, "I1").fill("abc")
    expect(page.locator("#pm-I1")).to_contain_text("enter a number")

    # a partial entry: every field emptied, two typed; the rest is the case's example
    for el in page.locator("#param-fields input").all():
        el.fill("")
    expect(page.locator('#param-fields input[aria-invalid="true"]')).to_have_count(0)
    field(page, "I1").fill("1.5")
    field(page, "a1").fill("0.05")
    page.fill("input[name=trajectories]", "2")
    page.fill("input[name=points]", "60")
    page.click("#run")
    page.wait_for_function("document.body.dataset.map === '1'", timeout=180_000)
    expect(page.locator("#map-status")).to_contain_text("2 trajectories, 60 points each")
    page.wait_for_timeout(400)

    # the map in view, its 2D view beside it (same points), no tick label on another
    for sel in ("#map-plot", "#map-plot-2d"):
        ok, box = in_view(page, sel)
        assert ok, (sel, box, page.evaluate("scrollY"))
    b3, b2 = page.locator("#map-plot").bounding_box(), page.locator("#map-plot-2d").bounding_box()
    assert abs(b3["y"] - b2["y"]) < 2 and b2["x"] >= b3["x"] + b3["width"] - 1, (b3, b2)
    ticks = page.evaluate(TICKS)
    assert ticks["traces"] == 2 and ticks["points"] > 0, ticks
    assert len(ticks["x"]) >= 3 and len(ticks["y"]) >= 3, ticks
    for axis in ("x", "y"):
        boxes = ticks[axis]
        assert not [(a, b) for i, a in enumerate(boxes) for b in boxes[i + 1:]
                    if overlap(a, b) > 1], (axis, boxes)
    page.screenshot(path=str(artifacts / "poincare-unbalanced-ball-1280.png"))

    # the address reproduces it: the typed values, the empty fields (the example), run=1
    url = page.url
    assert "run=1" in url and "p.I1=1.5" in url and "p.a1=0.05" in url and "p.a3=&" in url, url
    page.goto(url)
    page.wait_for_function("document.body?.dataset.map === '1'", timeout=180_000)
    expect(field(page, "I1")).to_have_value("1.5")
    expect(field(page, "I2")).to_have_value("")
    expect(page.locator("#map-status")).to_contain_text("2 trajectories, 60 points each")
