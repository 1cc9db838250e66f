"""Browser: /scenes for a class, at 1280x720 (a projector), every scene:

  * the claim's plot (first), its time cursor and the 3D view are in the viewport;
  * the cursors move while the scene plays, stop when it is paused, and stand at the
    animation's own time;
  * the bar under the animation steps one frame on;
  * in presentation mode every tick label of every plot measures at least 18 px (its
    computed font size and its rendered box), the titles at least 24 px, the claim is one
    sentence, the contact path and body axes are drawn thick; a screenshot of it goes to
    /work/wt/shots/scenes/ (outside the repository) for the closing note;
  * a slider's change runs the scene again (POST /api/scenes/{id}/run): the plotted data
    change, and the claim's check, computed here from the plotted numbers themselves,
    passes; "Open in the simulator" carries the moved parameters;
and the list of scenes shows a thumbnail per scene with the first Play in view."""

import math
import os
from pathlib import Path
from urllib.parse import parse_qs, urlparse

import numpy as np
import pytest
from playwright.sync_api import expect

from solvers.scenes.teaching import load_scenes

SCENES = load_scenes()
SHOTS = Path(os.environ.get("ROLLING_SCENE_SHOTS", "/work/wt/shots/scenes"))
W, H = 1280, 720

# a value of each scene's first slider, away from the preset, where the claim still holds
# (solvers/scenes/rerun.py runs it; a slow coin or an unturned stone would fail, as
# tests/test_scene_rerun_api.py shows)
MOVE = {"chaplygin-ball-quasiperiodic": 2.5, "rolling-disk-stays-up": 4.0,
        "routh-ball-jellett-routh": 0.45, "unbalanced-ball-asymptotic": -0.6,
        "borisov-fedorov-ball": 2.5, "rattleback-spin-reversal": 1.5}


def in_view(page, locator, what):
    box = locator.bounding_box()
    assert box, what
    assert box["x"] >= 0 and box["x"] + box["width"] <= W + 1, (what, box)
    assert box["y"] >= 0 and box["y"] + box["height"] <= H + 1, (what, box)


def cursor_state(page):
    return page.evaluate("""[...document.querySelectorAll('[data-testid=time-cursor]')]
        .map((e) => ({ t: Number(e.dataset.t), x: e.getBoundingClientRect().x,
                       y: e.getBoundingClientRect().y, hidden: e.hidden }))""")


def plotted(page, k=0):
    """The traces of claim plot k as drawn (Plotly's own data of the element)."""
    return page.locator("[data-testid=claim-plot]").nth(k).evaluate(
        "e => e.data.map((t) => ({ name: t.name, x: Array.from(t.x), y: Array.from(t.y) }))")


def claim_holds_on(check, traces, api_plot):
    """The check's verdict, computed from the plotted numbers (traces named as the API's
    plot names them, roles taken from that plot)."""
    role = {t["name"]: t["role"] for t in api_plot["traces"]}
    claim = [t for t in traces if role.get(t["name"]) == "claim"]
    assert claim, traces
    y0 = np.array([np.nan if v is None else v for v in claim[0]["y"]], dtype=float)
    if check.kind in ("conserved", "integrals"):
        worst = 0.0
        for t in claim:
            v = np.array(t["y"], dtype=float)
            d = (np.abs(v[1:] - v[0]) / max(abs(v[0]), 1.0) if check.kind == "conserved"
                 else v)
            worst = max(worst, float(np.nanmax(d)))
        return worst <= check.tol, worst
    if check.kind == "stays_up":
        bound = math.degrees(math.acos(check.min_tilt))
        return float(np.nanmax(y0)) <= bound, float(np.nanmax(y0))
    if check.kind == "spin_reversal":
        from solvers.models.observables import spin_reversals

        raw = next(t for t in traces if role.get(t["name"]) == "raw")
        times = spin_reversals(raw["x"], np.array(raw["y"], dtype=float), check.window)
        return bool(times) and times[0] <= check.before, times[:1]
    if check.expect == "condenses":
        ratio = float(np.median(y0[:100]) / np.median(y0[-100:]))
        return ratio >= check.factor, ratio
    from solvers.maps.map_analysis import correlation_dimension

    # the plotted returns (l across, L/G up), measured as a set of points in the plane
    P = np.c_[claim[0]["y"], np.zeros(len(claim[0]["y"])), claim[0]["x"]]
    d = correlation_dimension(P, 0.01, 0.1)
    return abs(d - 1.0) <= check.dim_tol, d


def opens_and_plays(page, server, sid):
    page.goto(f"{server}/scenes#{sid}")
    page.locator(f"body[data-playing='{sid}']").wait_for(state="attached", timeout=120_000)
    n = len(SCENES[sid].checks)
    expect(page.locator("[data-testid=claim-plot]")).to_have_count(n, timeout=120_000)
    expect(page.locator("[data-testid=time-cursor]")).to_have_count(n, timeout=60_000)


def cursors_follow_the_animation(page):
    page.wait_for_timeout(300)
    a = cursor_state(page)
    page.wait_for_timeout(1200)
    b = cursor_state(page)
    pairs = list(zip(a, b, strict=True))
    assert all(q["t"] > p["t"] for p, q in pairs), (a, b)                  # time goes on
    # the time plots' line moves across (a map's return counter may sit still a while)
    assert any(abs(q["x"] - p["x"]) + abs(q["y"] - p["y"]) > 0.5 for p, q in pairs), (a, b)
    page.locator("#play").click()
    expect(page.locator("#play")).to_have_text("Play")
    page.wait_for_timeout(200)
    c = cursor_state(page)
    page.wait_for_timeout(1000)
    d = cursor_state(page)
    assert c == d, (c, d)                                             # paused: still
    shown = float(page.locator("#scene-time").inner_text().split("=")[1])
    assert all(abs(x["t"] - shown) <= 0.051 for x in d), (d, shown)   # at the view's time
    page.locator("#step").click()
    e = cursor_state(page)
    assert all(q["t"] > p["t"] for p, q in zip(d, e, strict=True)), (d, e)         # one frame on


def presentation(page, sid):
    page.locator("#present").click()
    page.locator("body[data-present='1']").wait_for(state="attached")
    page.wait_for_timeout(800)                       # the plots' resize after the fonts
    assert "present=1" in page.url
    ticks = page.evaluate("""[...document.querySelectorAll(
        '[data-testid=claim-plot] .xtick text, [data-testid=claim-plot] .ytick text')]
        .filter((t) => t.textContent.trim() !== '')
        .map((t) => ({ text: t.textContent, size: parseFloat(getComputedStyle(t).fontSize),
                       h: t.getBoundingClientRect().height }))""")
    assert len(ticks) >= 4 * len(SCENES[sid].checks), ticks
    small = [t for t in ticks if t["size"] < 18 or t["h"] < 18]
    assert not small, small[:5]
    titles = page.evaluate("""[document.getElementById('h-player'),
        ...document.querySelectorAll('.claim-title')]
        .map((e) => parseFloat(getComputedStyle(e).fontSize))""")
    assert min(titles) >= 24, titles
    sentence = page.locator("#scene-sentence")
    expect(sentence).to_be_visible()
    text = sentence.inner_text().strip()
    assert text == " ".join(SCENES[sid].sentence.split()) and text.count(". ") == 0, text
    lines = page.locator("#scene-plot").evaluate(
        "e => e.data.map((t) => [t.name, t.line ? t.line.width : null])")
    width = dict(lines)
    assert width["contact path"] >= 6 and width["e₁"] >= 10, lines
    # the claim, its cursor and the 3D view stay on the projector's screen
    in_view(page, page.locator("[data-testid=claim-plot]").first, "claim plot")
    in_view(page, page.locator("[data-testid=time-cursor]").first, "time cursor")
    in_view(page, page.locator("#scene-plot"), "3D view")
    SHOTS.mkdir(parents=True, exist_ok=True)
    page.screenshot(path=str(SHOTS / f"{sid}.png"))
    page.locator("#present").click()
    page.locator("body[data-present='0']").wait_for(state="attached")


def slider_reruns(page, sid):
    s = SCENES[sid]
    sl = s.sliders[0]
    before = plotted(page)
    v = MOVE[sid]
    page.evaluate("""([name, v]) => {
        const el = document.querySelector(`#scene-sliders input[name=${name}]`);
        el.value = String(v); el.dispatchEvent(new Event('input'));
        el.dispatchEvent(new Event('change')); }""", [sl.name, v])
    page.locator("body[data-rerun]").wait_for(state="attached", timeout=120_000)
    page.locator(f"body[data-playing='{sid}']").wait_for(state="attached", timeout=120_000)
    out = page.locator("[data-testid=slider-value]").first.inner_text()
    assert out.endswith(sl.units) and float(out.split()[0]) == pytest.approx(v), out
    after = plotted(page)
    assert [t["y"] for t in after] != [t["y"] for t in before]     # a new run is plotted
    # the claim's check, on the numbers now plotted
    api_plot = page.evaluate(
        f"""async () => (await (await fetch('/api/scenes/{sid}/run', {{ method: 'POST',
        headers: {{ 'Content-Type': 'application/json' }},
        body: JSON.stringify({{ values: {{ {sl.name}: {v} }} }}) }})).json()).checks[0].plot""")
    ok, value = claim_holds_on(s.checks[0], after, api_plot)
    assert ok, (sid, value)
    expect(page.locator("[data-testid=verdict]").first).to_contain_text("✓")
    # the simulator gets the moved run
    href = page.locator("#open-sim").get_attribute("href")
    u = urlparse(href)
    q = parse_qs(u.query)
    assert u.path == f"/case/{s.scene.case}" and q["run"] == ["1"], href
    if sl.param:
        assert float(q[f"p.{sl.param}"][0]) == pytest.approx(v * sl.factor), href
    else:
        assert float(q["state"][0].split(",")[sl.state]) == pytest.approx(v * sl.factor), href
    assert float(q["t_end"][0]) == s.scene.t_end


# a scene with a body beside (two 3D views) has its own test: tests/e2e/test_rubber_scene_browser.py
@pytest.mark.parametrize("sid", [sid for sid, s in SCENES.items() if s.beside is None])
def test_a_scene_for_a_class(page, server, sid):
    page.set_viewport_size({"width": W, "height": H})
    opens_and_plays(page, server, sid)
    in_view(page, page.locator("[data-testid=claim-plot]").first, "claim plot")
    in_view(page, page.locator("[data-testid=time-cursor]").first, "time cursor")
    in_view(page, page.locator("#scene-plot"), "3D view")
    cursors_follow_the_animation(page)
    presentation(page, sid)
    slider_reruns(page, sid)


def test_the_list_has_thumbnails_and_the_first_play_in_view(page, server):
    page.set_viewport_size({"width": W, "height": H})
    page.goto(f"{server}/scenes")
    expect(page.locator(".scene-card")).to_have_count(len(SCENES))
    thumbs = page.locator(".scene-card [data-testid=scene-thumb]")
    expect(thumbs).to_have_count(len(SCENES))
    for i in range(len(SCENES)):
        # drawn from the scene's data: shapes, no image file
        assert thumbs.nth(i).locator("circle, ellipse, path").count() >= 2
    assert page.locator(".scene-card img").count() == 0
    in_view(page, page.locator(".scene-card a.play-link").first, "first Play")
    page.locator(".scene-card a.play-link").first.click()
    first = next(iter(SCENES))
    page.locator(f"body[data-claimed='{first}']").wait_for(state="attached", timeout=120_000)
    # the status says what runs, not how many frames
    page.locator(f"body[data-drawn='{first}']").wait_for(state="attached", timeout=120_000)
    assert "frames" not in page.locator("#scene-status").inner_text()


def test_presentation_from_the_address(page, server):
    page.set_viewport_size({"width": W, "height": H})
    sid = "rolling-disk-stays-up"
    page.goto(f"{server}/scenes?present=1#{sid}")
    page.locator(f"body[data-playing='{sid}']").wait_for(state="attached", timeout=120_000)
    assert page.evaluate("document.body.classList.contains('present')")
    expect(page.locator("header.site")).to_be_hidden()
    size = page.locator("[data-testid=claim-plot] .xtick text").first.evaluate(
        "t => parseFloat(getComputedStyle(t).fontSize)")
    assert size >= 18
    # full screen: the player itself (the Fullscreen API)
    page.locator("#fullscreen").click()
    page.wait_for_function(
        "document.fullscreenElement && document.fullscreenElement.id === 'player'",
        timeout=10_000)
    page.evaluate("document.exitFullscreen()")


def test_a_scene_under_the_csp(strict, server):
    """Cursors, sliders with typeset symbols, presentation: nothing the policy refuses."""
    page, refused = strict
    sid = "routh-ball-jellett-routh"
    page.goto(f"{server}/scenes?present=1#{sid}")
    page.locator(f"body[data-playing='{sid}']").wait_for(state="attached", timeout=120_000)
    page.locator("#scene-sliders .katex").first.wait_for(state="attached")
    page.locator("[data-testid=time-cursor]").first.wait_for(state="attached")
    page.locator("#step").click()
    assert not refused, refused


def test_open_in_the_simulator_carries_the_moved_run(page, server):
    """The case page opens from the scene's link with the slider's value, the other
    parameters and the start of the scene, and runs it."""
    page.set_viewport_size({"width": W, "height": H})
    sid = "rattleback-spin-reversal"
    s = SCENES[sid]
    page.goto(f"{server}/scenes?v.delta=1.5#{sid}")
    page.locator("body[data-rerun]").wait_for(state="attached", timeout=120_000)
    page.locator("#open-sim").click()
    page.wait_for_url(f"**/case/{s.scene.case}?*")
    page.locator("body[data-run]").wait_for(state="attached", timeout=120_000)
    value = lambda group, name: float(page.locator(  # noqa: E731
        f'input[data-group="{group}"][data-name="{name}"]').input_value())
    assert value("p", "delta") == pytest.approx(math.radians(1.5))
    for k, v in s.scene.params.items():
        if k != "delta":
            assert value("p", k) == pytest.approx(v), k
    state = [float(el.input_value()) for el in page.locator('input[data-group="s"]').all()]
    assert state == pytest.approx(s.scene.state)
    assert float(page.locator("#f-t_end").input_value()) == s.scene.t_end
