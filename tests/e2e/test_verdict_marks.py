"""Issue 10 in the browser: a cell whose property holds shows no red cross even when the
formula printed under it is misprinted; a merged cell shows one mark per body in column
order; the errata page lists the misprints and is linked from the home page."""

import re

import httpx
import pytest
from playwright.sync_api import expect

from tests.e2e.servers import stored_verdicts_server

CASES = ["plane/chaplygin-ball", "plane/routh-ball", "plane/spherical-inertia",
         "sphere/body-of-revolution", "sphere/round-disk", "sphere/routh-ball",
         "sphere/flat-base-axisymmetric", "sphere/borisov-fedorov"]


def ready(page):
    page.wait_for_function("document.body?.dataset.ready === '1'")


@pytest.fixture(scope="module")
def verified(catalogue_records, tmp_path_factory):
    """A server whose store holds every case's verdicts, from the session's full
    verification (tests/e2e/servers.py: stored_verdicts_server); CASES are among them."""
    with stored_verdicts_server(catalogue_records, tmp_path_factory.mktemp("verdicts")) as url:
        for cid in CASES:
            assert httpx.get(f"{url}/api/cases/{cid}", timeout=30).json()[
                "verification"] == "done", cid
        yield url


def test_cells_over_misprints_show_no_cross(page, verified, artifacts):
    server = verified
    page.goto(server + "/")
    ready(page)
    expect(page.locator("#tbl-sphere a.cellmark").first).to_be_visible()
    assert page.locator("table.paper .mk.fails").count() == 0
    gyro = page.locator('#tbl-sphere tr.row-gyrostat td[colspan="4"]')
    marks = gyro.locator(".mk")
    expect(marks).to_have_count(4)
    assert [marks.nth(i).get_attribute("data-case") for i in range(4)] == [
        "sphere/body-of-revolution", "sphere/round-disk", "sphere/routh-ball",
        "sphere/flat-base-axisymmetric"]
    # issue 17: the property holds after correction of the misprinted formula (text, ✎)
    assert all("after-correction" in marks.nth(i).get_attribute("class") for i in range(4))
    expect(gyro.locator(".mkword")).to_have_text(["after correction"])
    expect(gyro.locator("details.mark-why")).to_contain_text("erratum")
    expect(page.locator('.legend .mark.pending')).to_be_visible()       # legend: checking
    page.locator("#tbl-sphere").screenshot(path=str(artifacts / "table-2-levels.png"))
    page.click('header.site a[href="/errata"]')
    page.wait_for_url(re.compile(r"/errata$"))
    ready(page)
    # /errata is a table of rows that open on demand (issue 17): one details.erow per entry
    expect(page.locator("#errata-list details.erow").first).to_be_visible()
    for fid in ("plane/spherical-inertia/negative/sphere-generalization",
                "sphere/borisov-fedorov/reduction/to-chaplygin"):
        expect(page.locator(f'#findings-list details.erow[id="f-{fid}"]')).to_have_count(1)
    expect(page.locator("#conventions-list")).to_contain_text("{H, x}")
    expect(page.locator("#errata-list")).to_contain_text(
        "rolling verify --claim sphere/round-disk/measure --json")
    page.screenshot(path=str(artifacts / "errata.png"), full_page=True)


def test_case_page_says_why_a_cell_holds(page, verified, artifacts):
    server = verified
    page.goto(server + "/case/sphere/round-disk")
    ready(page)
    row = page.locator("#row-gyrostat")
    expect(row.locator(".cellverdict")).to_contain_text("✎ holds after correction")
    assert row.locator(".mk.fails").count() == 0
    claim = page.locator("#claim-sphere_round-disk_gyrostat_linear-integrals")
    expect(claim.locator(".marknote")).to_contain_text("fails as printed only because it uses")
    expect(page.locator('header.site a[href="/errata"]')).to_be_visible()
