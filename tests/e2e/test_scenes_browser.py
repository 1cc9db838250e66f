"""Browser: every teaching scene, opened once at 1280x720 (a projector) from its link on the
home page, and everything issue 20 asks of it checked on that one opening (before, four
modules opened every scene once each: the 3D view in software WebGL is most of a browser
test's cost, and issue 19 asks for CI under 12 minutes):

  * it opens from the home page and plays (the clock of the animation advances);
  * it plots its claim from the data its check measured (GET /api/scenes/{id}/checks/{k}),
    the claimed quantity named in the legend, and the check passes on those numbers;
  * the first claim plot is drawn before the 3D view (the page's own performance marks);
  * the claim plot and the 3D view are inside the 1280x720 viewport, without scrolling;
  * no axis title, legend, plot title or toolbar of any plot overlaps another or is cut
    off (tests/e2e/test_plot_layout_browser.py's rule; that module keeps the 390 px pass
    and the other pages);
  * last, since it pauses the animation and hides all but the body: the 3D view frames the
    body (app/static/js/scene.js; before: a small ball under 200-300 px of empty space).
    The body alone is drawn again with the view's own camera (Plotly's toImage) and the
    box of its pixels is measured against the plot's."""

import pytest
from playwright.sync_api import expect

from solvers.scenes.scene_checks import PRETTY
from solvers.scenes.teaching import load_scenes
from tests.e2e.test_plot_layout_browser import problems

SCENES = load_scenes()

# Pause, keep only the body, draw the view as a PNG and find the box of the pixels that
# are not the white background. Returns that box and the plot's size, in px.
BODY_BOX = """async (sel) => {
  const el = document.querySelector(sel);
  // the first frame, paused (the scrubber's own input): the same pose on every run.
  // Paused wherever the animation happened to be, the spinning rattleback was measured
  // end-on in some runs (0.14 x 0.30 of the view, under the 0.35 asked) and side-on in
  // others; at the first frame it spans 0.38 x 0.20
  const scrub = document.getElementById('scrub');
  scrub.value = '0';
  scrub.dispatchEvent(new Event('input'));
  const body = el.data.findIndex((t) => t.type === 'mesh3d' && t.name === 'body');
  await Plotly.restyle(el, { visible: el.data.map((_, i) => i === body) });
  await Plotly.relayout(el, { showlegend: false, 'scene.xaxis.visible': false,
    'scene.yaxis.visible': false, 'scene.zaxis.visible': false });
  const W = el.clientWidth, H = el.clientHeight;
  const img = new Image();
  img.src = await Plotly.toImage(el, { format: 'png', width: W, height: H });
  await img.decode();
  const c = document.createElement('canvas');
  c.width = W; c.height = H;
  const g = c.getContext('2d');
  g.drawImage(img, 0, 0);
  const px = g.getImageData(0, 0, W, H).data;
  let x0 = W, y0 = H, x1 = -1, y1 = -1;
  for (let y = 0; y < H; y++) for (let x = 0; x < W; x++) {
    const o = 4 * (y * W + x);
    if (px[o + 3] > 0 && Math.min(px[o], px[o + 1], px[o + 2]) < 235) {
      x0 = Math.min(x0, x); x1 = Math.max(x1, x); y0 = Math.min(y0, y); y1 = Math.max(y1, y);
    }
  }
  return { W, H, x0, y0, x1, y1, body };
}"""


def claimed_names(check, scene) -> set[str]:
    """The legend entries of the quantity the check is about."""
    if check.kind in ("integrals", "conserved"):
        return {PRETTY[n] for n in check.names}
    if check.kind == "stays_up":
        return {"tilt"}
    if check.kind == "spin_reversal":
        return {f"spin averaged over {check.window:g}"}
    if check.kind == "no_spin":
        return {scene.beside.label, scene.beside.main_label}
    return {"returns (l, L/G)"} if check.expect == "curve" else {
        f"|x(n+{check.period}) − x(n)|"}


def opens_from_home_and_plays(page, server, scene_id):
    page.goto(server + "/")
    link = page.locator(f'#scene-links a[href="/scenes#{scene_id}"]')
    expect(link).to_be_visible()
    link.click()
    page.wait_for_url(f"**/scenes#{scene_id}")


def plots_its_claim(page, scene_id):
    s = SCENES[scene_id]
    page.locator(f"body[data-claimed='{scene_id}']").wait_for(state="attached",
                                                               timeout=90_000)
    plots = page.locator("[data-testid=claim-plot]")
    plots.first.locator(".main-svg").first.wait_for(state="attached")
    expect(plots).to_have_count(len(s.checks), timeout=90_000)
    for k, check in enumerate(s.checks):
        el = plots.nth(k)
        el.locator(".main-svg").first.wait_for(state="attached")
        names = set(el.evaluate("e => e.data.map((t) => t.name)"))
        assert claimed_names(check, s) <= names, (k, names)
        # the plotted numbers are the check's own (the API answer the verdict came from)
        same = el.evaluate(f"""async (e) => {{
            const d = await (await fetch('/api/scenes/{scene_id}/checks/{k}')).json();
            const claim = d.plot.traces.filter((t) => t.role === 'claim');
            const drawn = e.data.filter((t) => claim.some((c) => c.name === t.name));
            return d.passed && drawn.length === claim.length && drawn.every((t, i) =>
                JSON.stringify(Array.from(t.y)) === JSON.stringify(claim[i].y));
        }}""")
        assert same, f"check {k} of {scene_id}: the plot is not the check's passing data"


def plays_after_the_first_plot(page, scene_id):
    page.locator(f"body[data-playing='{scene_id}']").wait_for(state="attached",
                                                               timeout=90_000)
    expect(page.locator("#scene-plot .gl-container canvas").first).to_be_visible()
    first = page.locator("#scene-time").inner_text()
    page.wait_for_timeout(600)
    assert page.locator("#scene-time").inner_text() != first      # it plays
    # the first plot was drawn before the 3D view (scenes.js: the animation's data is asked
    # for at the click, its drawing waits for the first plot), by the page's own clock
    marks = page.evaluate("""Object.fromEntries(performance.getEntriesByType('mark')
        .map((m) => [m.name, m.startTime]))""")
    assert marks["scene:first-plot"] <= marks["scene:3d-drawn"], marks


def in_the_projectors_view(page):
    for sel in ("[data-testid=claim-plot] >> nth=0", "#scene-plot"):
        box = page.locator(sel).bounding_box()
        assert box and box["y"] >= 0 and box["y"] + box["height"] <= 720 + 1, (sel, box)
        assert box["x"] >= 0 and box["x"] + box["width"] <= 1280 + 1, (sel, box)


def frames_the_body(page, scene_id):
    # two bodies side by side (a scene with `beside`): the first view
    pair = SCENES[scene_id].beside is not None
    b = page.evaluate(BODY_BOX, "#scene-plot .pair-view" if pair else "#scene-plot")
    assert b["body"] >= 0 and b["x1"] > b["x0"] and b["y1"] > b["y0"], b
    w, h = (b["x1"] - b["x0"]) / b["W"], (b["y1"] - b["y0"]) / b["H"]
    # the body spans a good part of the view one way or the other (a long stone lies
    # flat: its width counts)
    assert max(w, h) >= 0.35, (scene_id, round(w, 2), round(h, 2), b)
    # within the view: not cut off at an edge
    assert b["x0"] > 0 and b["y0"] > 0 and b["x1"] < b["W"] - 1, b


@pytest.mark.parametrize("scene_id", list(SCENES))
def test_every_scene_on_a_projector(page, server, scene_id):
    page.set_viewport_size({"width": 1280, "height": 720})
    opens_from_home_and_plays(page, server, scene_id)
    plots_its_claim(page, scene_id)
    plays_after_the_first_plot(page, scene_id)
    in_the_projectors_view(page)
    page.wait_for_timeout(300)               # a responsive relayout after the first draw
    assert page.evaluate("document.querySelectorAll('.js-plotly-plot').length") > 0
    found = problems(page)
    assert not found, "\n".join(found[:12])
    frames_the_body(page, scene_id)
