"""Browser: the marble-against-rubber teaching scene on /scenes, at 1280x720 (a projector).

  * the claim plot comes first: (omega, gamma) of both balls, the rubber ball's at zero and
    the marble's away from it, measured here on the traces as drawn; then the marble's and
    the rubber ball's invariants, each a passing `conserved` check read off its plot;
  * two 3D views side by side, labelled, move together with the plots' time cursors while
    the scene plays, stand still when paused, and step one frame on together;
  * presentation mode: tick labels of 18 px or more, the sentence alone, both views drawn
    with thick paths, all in the projector's screen;
  * the slider (I3) runs both balls again from the same start kept on the rubber manifold,
    and the claim still holds on the new plotted numbers;
  * the list shows the scene's thumbnail: two balls.
Screenshots: test-artifacts/e2e/scene-marble-rubber-1280.png and
scene-marble-rubber-present-1280.png (and ROLLING_DOC_SHOTS/, when set, for
docs/screenshots/)."""


import numpy as np
from playwright.sync_api import expect

from solvers.scenes.teaching import load_scenes
from tests.e2e.figures import drawn, shot_dirs

SID = "marble-against-rubber"
SCENE = load_scenes()[SID]
W, H = 1280, 720


def in_view(locator, what):
    box = locator.bounding_box()
    assert box, what
    assert box["x"] >= 0 and box["x"] + box["width"] <= W + 1, (what, box)
    assert box["y"] >= 0 and box["y"] + box["height"] <= H + 1, (what, box)


def plotted(page, k):
    return page.locator("[data-testid=claim-plot]").nth(k).evaluate(
        "e => e.data.map((t) => ({ name: t.name, y: Array.from(t.y) }))")


def views(page):
    """Frame shown by each 3D view: the body's first vertex (x, y, z) as drawn."""
    return page.evaluate("""[...document.querySelectorAll('#scene-plot .pair-view')]
        .map((e) => { const b = e.data.find((t) => t.name === 'body');
                      return [b.x[0], b.y[0], b.z[0]]; })""")


def cursors(page):
    return page.evaluate("""[...document.querySelectorAll('[data-testid=time-cursor]')]
        .map((e) => Number(e.dataset.t))""")


def claim_holds(page):
    """The no-spin claim and both conserved checks, on the numbers drawn."""
    spin = {t["name"]: drawn(t["y"]) for t in plotted(page, 0)}
    b = SCENE.beside
    no_spin, marble = spin[b.label], spin[b.main_label]
    assert np.nanmax(np.abs(no_spin)) <= SCENE.checks[0].tol, np.nanmax(np.abs(no_spin))
    assert np.nanmax(np.abs(marble)) >= SCENE.checks[0].marble_min
    for k in (1, 2):
        check = SCENE.checks[k]
        lines = {t["name"]: drawn(t["y"]) for t in plotted(page, k)}
        assert len(lines) == len(check.names) + 1          # and gamma3, for contrast
        for name, v in lines.items():
            change = np.nanmax(np.abs(v - v[0])) / max(abs(v[0]), 1.0)
            if name.startswith("γ₃"):
                assert change > 1e-3, name
            else:
                assert change <= check.tol, (name, change)


def test_marble_against_rubber_for_a_class(page, server, artifacts):
    page.set_viewport_size({"width": W, "height": H})
    page.goto(f"{server}/scenes#{SID}")
    page.locator(f"body[data-playing='{SID}']").wait_for(state="attached", timeout=240_000)
    expect(page.locator("[data-testid=claim-plot]")).to_have_count(3, timeout=120_000)
    expect(page.locator("[data-testid=verdict]")).to_have_count(3)
    for k in range(3):
        expect(page.locator("[data-testid=verdict]").nth(k)).to_contain_text("✓")
    claim_holds(page)
    labels = page.locator("[data-testid=pair-label]")
    expect(labels).to_have_text([SCENE.beside.main_label, SCENE.beside.label])
    in_view(page.locator("[data-testid=claim-plot]").first, "claim plot")
    in_view(page.locator("#scene-plot"), "3D views")
    # both views and every cursor move while it plays, and stand still when paused
    page.wait_for_timeout(300)
    v0, c0 = views(page), cursors(page)
    page.wait_for_timeout(1500)
    v1, c1 = views(page), cursors(page)
    assert all(a != b for a, b in zip(v0, v1, strict=True)), (v0, v1)
    assert all(b > a for a, b in zip(c0, c1, strict=True)), (c0, c1)
    page.locator("#play").click()
    expect(page.locator("#play")).to_have_text("Play")
    page.wait_for_timeout(200)
    v2 = views(page)
    page.wait_for_timeout(800)
    assert views(page) == v2
    page.locator("#step").click()
    assert all(a != b for a, b in zip(v2, views(page), strict=True))
    for d in shot_dirs(artifacts):
        page.screenshot(path=str(d / "scene-marble-rubber-1280.png"))
    # presentation
    page.locator("#present").click()
    page.locator("body[data-present='1']").wait_for(state="attached")
    page.wait_for_timeout(800)
    ticks = page.evaluate("""[...document.querySelectorAll(
        '[data-testid=claim-plot] .xtick text, [data-testid=claim-plot] .ytick text')]
        .filter((t) => t.textContent.trim() !== '')
        .map((t) => parseFloat(getComputedStyle(t).fontSize))""")
    assert ticks and min(ticks) >= 18, ticks
    expect(page.locator("#scene-sentence")).to_have_text(" ".join(SCENE.sentence.split()))
    widths = page.evaluate("""[...document.querySelectorAll('#scene-plot .pair-view')]
        .map((e) => e.data.find((t) => t.name === 'contact path').line.width)""")
    assert len(widths) == 2 and min(widths) >= 6, widths
    in_view(page.locator("[data-testid=claim-plot]").first, "claim plot")
    in_view(page.locator("#scene-plot"), "3D views")
    for d in shot_dirs(artifacts):
        page.screenshot(path=str(d / "scene-marble-rubber-present-1280.png"))
    page.locator("#present").click()
    page.locator("body[data-present='0']").wait_for(state="attached")
    # the slider: both balls again from the start kept on the rubber manifold
    before = plotted(page, 0)
    page.evaluate("""() => {
        const el = document.querySelector('#scene-sliders input[name=I3]');
        el.value = '2.4'; el.dispatchEvent(new Event('input'));
        el.dispatchEvent(new Event('change')); }""")
    page.locator("body[data-rerun]").wait_for(state="attached", timeout=240_000)
    page.locator(f"body[data-playing='{SID}']").wait_for(state="attached", timeout=240_000)
    after = plotted(page, 0)
    assert [list(t["y"][:50]) for t in after] != [list(t["y"][:50]) for t in before]
    claim_holds(page)


def test_the_list_shows_two_balls(page, server):
    page.set_viewport_size({"width": W, "height": H})
    page.goto(f"{server}/scenes")
    thumb = page.locator(f"#card-{SID} [data-testid=scene-thumb]")
    expect(thumb).to_have_count(1)
    assert thumb.locator("circle").count() == 2
    assert "beside" in thumb.get_attribute("aria-label")
