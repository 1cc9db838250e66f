"""Browser: a rubber case's page (/case/rubber-plane/chaplygin-ball, beyond the 2002 paper).

  * the page says the case is beyond the 2002 paper and links to the guide's rubber
    equations and to its cells in the rubber tables of the home page;
  * its cells in the rubber tables are listed with their marks, their statements typeset;
  * a run draws, besides the state, drift and gamma plots, the constraint (omega, gamma)
    and |gamma| - 1, and the energy with the case's integral F = |M x gamma|^2, all against
    time; the plotted numbers hold: the constraint and |gamma| - 1 at zero, F and the energy
    constant (measured here on the traces as drawn); the drift plot's legend names the
    constraint and F typeset, not by their code names;
  * the 3D view animates the rubber ball.
Screenshot: test-artifacts/e2e/rubber-case-1280.png (and ROLLING_DOC_SHOTS/, when set, for
docs/screenshots/)."""


import numpy as np
from playwright.sync_api import expect

from tests.e2e.figures import drawn, shot_dirs

CASE = "rubber-plane/chaplygin-ball"


def traces(page, sel):
    return page.locator(sel).evaluate(
        "e => e.data.map((t) => ({ name: t.name, y: Array.from(t.y) }))")


def test_a_rubber_case_page_runs_and_plots_its_constraint_and_integrals(page, server, artifacts):
    page.set_viewport_size({"width": 1280, "height": 900})
    page.goto(f"{server}/case/{CASE}")
    page.locator("body[data-ready='1']").wait_for(state="attached")
    box = page.locator("[data-testid=beyond-paper]")
    expect(box).to_contain_text("Beyond the 2002 paper")
    assert page.locator("#rubber-equations").get_attribute("href") == "/guide/rubber/#equations"
    assert page.locator("#rubber-table").get_attribute("href") == "/#tbl-rubber-plane"
    home = page.request.get(server + "/").text()
    assert 'id="tbl-rubber-plane"' in home     # the link lands on the home page's table
    cells = page.locator("[data-testid=rubber-cell]")
    # measure, integrals, gyrostat, Brun field, Hamiltonian form, integrability
    expect(cells).to_have_count(6)
    hrefs = [cells.nth(i).get_attribute("href") for i in range(6)]
    assert all(h.startswith("/#claim-rubber-plane_chaplygin-ball_cell_") for h in hrefs), hrefs
    # the cells' statements typeset from their LaTeX, as on the home page: M × γ in KaTeX
    listed = page.locator("table[data-testid=rubber-cells]")
    expect(listed.locator(".cell-statement .katex").first).to_be_visible()
    assert listed.locator(".tex-fallback").count() == 0
    seen = listed.evaluate("""t => { const c = t.cloneNode(true);
        c.querySelectorAll('.katex-mathml').forEach(m => m.remove()); return c.textContent; }""")
    assert "M×γ" in seen.replace(" ", "") and "^(" not in seen and "gamma" not in seen, seen
    # a run, as the example fills the form
    expect(page.locator("#formmsg")).to_contain_text("valid", timeout=60_000)
    page.fill("#f-t_end", "60")
    page.click("#run")
    page.locator("body[data-rubber-plots='1']").wait_for(state="attached", timeout=180_000)
    expect(page.locator("#runinfo")).to_contain_text("ok")
    c = {t["name"]: drawn(t["y"]) for t in traces(page, "#plot-constraint")}
    assert set(c) == {"(ω, γ), the spin about the normal", "|γ| − 1"}, c.keys()
    assert all(len(v) > 100 and np.nanmax(np.abs(v)) < 1e-8 for v in c.values()), \
        {k: np.nanmax(np.abs(v)) for k, v in c.items()}
    i = {t["name"]: drawn(t["y"]) for t in traces(page, "#plot-integrals")}
    assert set(i) == {"energy H = (M, ω)/2 + U", "F = |M × γ|²"}, i.keys()
    for name, v in i.items():
        assert np.nanmax(np.abs(v - v[0])) / max(abs(v[0]), 1.0) < 1e-8, name
    # the drift plot names the rubber integrals typeset, as it names the others
    drift = [t["name"] for t in traces(page, "#plot-drift")]
    assert {"energy H", "γ²", "(ω, γ)", "|M × γ|²"} <= set(drift), drift
    assert not {"spin", "rubber_ball_F"} & set(drift), drift
    # the body in 3D
    page.fill("#f-frames", "60")
    page.click("#scene-btn")
    page.locator("body[data-scene='1']").wait_for(state="attached", timeout=180_000)
    expect(page.locator("#scene-msg")).to_contain_text("frames")
    page.locator("#simulate").evaluate("e => e.scrollIntoView({block: 'start'})")
    page.wait_for_timeout(300)
    page.evaluate("window.scrollTo(0, 0)")
    for d in shot_dirs(artifacts):
        d.mkdir(parents=True, exist_ok=True)
        page.screenshot(path=str(d / "rubber-case-1280.png"))
    # below the sticky header and the page's navigation
    page.locator("#plot-constraint").evaluate(
        "e => { e.scrollIntoView({block: 'start'}); window.scrollBy(0, -130); }")
    page.wait_for_timeout(300)
    for d in shot_dirs(artifacts):
        page.screenshot(path=str(d / "rubber-case-plots-1280.png"))
