"""Browser: a permalink ("Link to this run" on a case page, the address of a computed
map on /poincare) opens scrolled at the result it reproduces, not at the top of the page
(app/static/js/permalink.js scrollToResultWhenDone, issue 20)."""

from playwright.sync_api import expect


def at_top_of_view(page, selector) -> bool:
    box = page.locator(selector).bounding_box()
    head = page.locator("header.site").bounding_box()
    top = head["y"] + head["height"] if head else 0
    return (box is not None and top - 2 <= box["y"] <= top + 40
            and page.evaluate("scrollY") > 300)


def test_link_to_this_run_opens_at_the_results(page, server):
    page.set_viewport_size({"width": 1280, "height": 720})
    page.goto(server + "/case/plane/chaplygin-ball")
    page.wait_for_function("document.body?.dataset.ready === '1'", timeout=60_000)
    page.click("#run")
    page.wait_for_function("document.body.dataset.run === '1'", timeout=120_000)
    link = page.locator("#permalink").get_attribute("href")
    assert "run=1" in link
    page.goto(link if link.startswith("http") else server + link)
    page.wait_for_function("document.body?.dataset.run === '1'", timeout=120_000)
    page.wait_for_timeout(300)
    assert at_top_of_view(page, "#results"), (page.evaluate("scrollY"),
                                              page.locator("#results").bounding_box())


def test_a_map_permalink_opens_at_the_map(page, server):
    page.set_viewport_size({"width": 1280, "height": 720})
    page.goto(server + "/poincare?case=plane/chaplygin-ball&energy=1&g0=0&direction=1"
              "&trajectories=2&points=40&rtol=1e-8&seed=0&run=1")
    page.wait_for_function("document.body?.dataset.map === '1'", timeout=120_000)
    expect(page.locator("#map-status")).to_contain_text("2 trajectories, 40 points each")
    page.wait_for_timeout(300)
    assert at_top_of_view(page, "#map-plot"), (page.evaluate("scrollY"),
                                               page.locator("#map-plot").bounding_box())
