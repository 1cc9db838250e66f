"""Browser: the 3D point maps page draws the paper's figures and computes a map with
progress (app/static/js/poincare.js); /work-precision draws every case. That every teaching
scene opens from the home page and plays: tests/e2e/test_scenes_browser.py."""

from playwright.sync_api import expect

FIGURES = ("ris-1", "ris-2", "ris-3", "ris-4")


def draw_every_figure(page, timeout=60_000):
    """Scroll to each of the paper's figures on /poincare and wait until it is drawn: a
    figure is drawn when it comes near the screen (app/static/js/poincare.js). Each is a
    3D scatter of ~800 KB of points, rendered without a GPU: give them time."""
    for key in FIGURES:
        plot = page.locator(f"[data-testid=plot-{key}]")
        plot.wait_for(state="attached", timeout=timeout)
        plot.scroll_into_view_if_needed()
        expect(plot).to_have_attribute("data-drawn", "1", timeout=timeout)


def test_paper_figures_and_a_computed_map(page, server, artifacts):
    page.goto(server + "/poincare")
    # a figure is drawn when it comes near the screen (app/static/js/poincare.js): the
    # first row on load, the second, below the fold of 1500x950, once scrolled to
    expect(page.locator("[data-testid=plot-ris-1] .main-svg").first).to_be_attached(
        timeout=60_000)
    page.wait_for_load_state("networkidle")
    page.wait_for_timeout(500)
    assert page.locator("[data-testid=plot-ris-4]").get_attribute("data-drawn") is None
    assert page.locator("[data-testid=plot-ris-4] .main-svg").count() == 0
    draw_every_figure(page)
    for key in FIGURES:
        expect(page.locator(f"[data-testid=plot-{key}] .main-svg").first).to_be_attached()
    page.fill("input[name=trajectories]", "3")
    page.fill("input[name=points]", "60")
    page.click("#run")
    expect(page.locator("#map-status")).to_contain_text("3 trajectories, 60 points each",
                                                     timeout=90_000)
    assert page.eval_on_selector("#progress", "e => [e.value, e.max]") == [3, 3]
    expect(page.locator("table.maptab tbody tr")).to_have_count(3)
    page.screenshot(path=str(artifacts / "poincare.png"))


def test_work_precision_page_draws_every_case(page, server, artifacts):
    """/work-precision: one log-log diagram per benchmarked case with a trace per method
    (ours, gauss8 among them, and the references), and the Pareto table under it."""
    from solvers.integrate.workprecision import load_results

    data = load_results()
    page.goto(server + "/work-precision")
    expect(page.locator("#wp-status")).to_contain_text("output times per run")
    for c in data["cases"]:
        slug = c["id"].replace("/", "-")
        plot = page.locator(f"#plot-{slug}")
        expect(plot.locator(".main-svg").first).to_be_attached(timeout=30_000)
        methods = {r["method"] for r in data["runs"] if r["case"] == c["id"]}
        assert plot.locator(".scatterlayer .trace").count() == len(methods)
        expect(plot.locator(".legend")).to_contain_text("gauss8")
        expect(page.locator(f"#{slug} table tbody tr")).to_have_count(
            len(data["summary"][c["id"]]["table"]))
    page.screenshot(path=str(artifacts / "work-precision.png"), full_page=True)
