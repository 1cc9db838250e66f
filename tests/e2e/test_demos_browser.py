"""Browser: every teaching scene plots its claim from the data its check measured
(GET /api/scenes/{id}/checks/{k}) before the 3D animation, and at 1280x720 (a projector)
the claim plot and the 3D view are on screen without scrolling (app/static/js/scenes.js,
issue 20)."""

import pytest
from playwright.sync_api import expect

from catalogue.scenes import load_scenes
from solvers.scenes.scene_checks import PRETTY

SCENES = load_scenes()


def claimed_names(check) -> set[str]:
    """The legend entries of the quantity the check is about."""
    if check.kind == "integrals":
        return {PRETTY[n] for n in check.names}
    if check.kind == "stays_up":
        return {"tilt"}
    if check.kind == "spin_reversal":
        return {f"spin averaged over {check.window:g}"}
    return {"returns (l, L/G)"} if check.expect == "curve" else {
        f"|x(n+{check.period}) − x(n)|"}


@pytest.mark.parametrize("scene_id", list(SCENES))
def test_every_scene_plots_its_claim_first_and_in_view(page, server, scene_id):
    s = SCENES[scene_id]
    page.set_viewport_size({"width": 1280, "height": 720})
    page.goto(f"{server}/scenes#{scene_id}")
    page.locator(f"body[data-claimed='{scene_id}']").wait_for(state="attached",
                                                               timeout=90_000)
    plots = page.locator("[data-testid=claim-plot]")
    plots.first.locator(".main-svg").first.wait_for(state="attached")
    expect(plots).to_have_count(len(s.checks), timeout=90_000)
    for k, check in enumerate(s.checks):
        el = plots.nth(k)
        el.locator(".main-svg").first.wait_for(state="attached")
        names = set(el.evaluate("e => e.data.map((t) => t.name)"))
        assert claimed_names(check) <= names, (k, names)
        # the plotted numbers are the check's own (the API answer the verdict came from)
        same = el.evaluate(f"""async (e) => {{
            const d = await (await fetch('/api/scenes/{scene_id}/checks/{k}')).json();
            const claim = d.plot.traces.filter((t) => t.role === 'claim');
            const drawn = e.data.filter((t) => claim.some((c) => c.name === t.name));
            return d.passed && drawn.length === claim.length && drawn.every((t, i) =>
                JSON.stringify(Array.from(t.y)) === JSON.stringify(claim[i].y));
        }}""")
        assert same, f"check {k} of {scene_id}: the plot is not the check's passing data"
    page.locator(f"body[data-playing='{scene_id}']").wait_for(state="attached",
                                                               timeout=90_000)
    expect(page.locator("#scene-plot .gl-container canvas").first).to_be_visible()
    # the first plot was drawn before the 3D view (scenes.js: the animation's data is asked
    # for at the click, its drawing waits for the first plot), by the page's own clock
    marks = page.evaluate("""Object.fromEntries(performance.getEntriesByType('mark')
        .map((m) => [m.name, m.startTime]))""")
    assert marks["scene:first-plot"] <= marks["scene:3d-drawn"], marks
    # a projector: the claim plot and the 3D view inside the 1280x720 viewport
    for sel in ("[data-testid=claim-plot] >> nth=0", "#scene-plot"):
        box = page.locator(sel).bounding_box()
        assert box and box["y"] >= 0 and box["y"] + box["height"] <= 720 + 1, (sel, box)
        assert box["x"] >= 0 and box["x"] + box["width"] <= 1280 + 1, (sel, box)


# Every tap target in the page's main part, links included (WCAG 2.5.8); a link inside a
# sentence is exempt (the criterion's "inline" exception): one displayed inline whose
# parent holds more text than the link itself.
SMALL = """() => [...document.querySelectorAll(
    'main a, main button, main input, main select, main summary, main [role=button]')]
  .filter((e) => e.offsetParent !== null && e.type !== 'hidden')
  .filter((e) => !(e.tagName === 'A' && getComputedStyle(e).display === 'inline' &&
      e.parentElement.textContent.trim().length > e.textContent.trim().length + 5))
  .map((e) => { const r = e.getBoundingClientRect();
    return { what: e.id || e.name || e.textContent.trim().slice(0, 30) || e.className || e.tagName,
             w: Math.round(r.width), h: Math.round(r.height) }; })
  .filter((b) => b.w < 24 || b.h < 24)"""


def test_no_control_under_24px_on_a_phone(page, server):
    page.set_viewport_size({"width": 390, "height": 844})
    page.goto(f"{server}/scenes#rolling-disk-stays-up")
    page.locator("body[data-playing='rolling-disk-stays-up']").wait_for(
        state="attached", timeout=90_000)
    small = page.evaluate(SMALL)
    assert small == [], small
    # /poincare's form, the home table and a case page (its claims, the run form, the cite
    # box), each once drawn
    for path, ready in (("/poincare", "#case option"), ("/", "#tbl-plane td"),
                        ("/case/plane/chaplygin-ball", "#claims .permalink")):
        page.goto(f"{server}{path}")
        page.locator(ready).first.wait_for(state="attached")
        small = page.evaluate(SMALL)
        assert small == [], (path, small)


# A word wider than the table cell that holds it is broken mid-word ("param eter"): the
# cell's inner width against the word's width in the cell's own font (innerText keeps the
# line breaks of <br>, so words across a break are not joined).
BROKEN_WORDS = """() => {
 const c = document.createElement('canvas').getContext('2d'); const out = [];
 for (const td of document.querySelectorAll('main td, main th')) {
   if (td.offsetParent === null) continue;
   const cs = getComputedStyle(td);
   c.font = `${cs.fontStyle} ${cs.fontWeight} ${cs.fontSize} ${cs.fontFamily}`;
   const inner = td.clientWidth - parseFloat(cs.paddingLeft) - parseFloat(cs.paddingRight);
   for (const w of td.innerText.split(/\\s+/).filter((w) => /^[A-Za-z]{4,}[,.;:]?$/.test(w)))
     if (c.measureText(w).width > inner + 1) { out.push([w, Math.round(inner)]); break; }
 } return out; }"""


def test_no_word_broken_in_a_table_on_a_wide_screen(page, server):
    page.set_viewport_size({"width": 1440, "height": 900})
    for path, ready in (("/glossary", "main table td"), ("/how-we-check", "main table td")):
        page.goto(f"{server}{path}")
        page.locator(ready).first.wait_for(state="attached")
        broken = page.evaluate(BROKEN_WORDS)
        assert broken == [], (path, broken)
