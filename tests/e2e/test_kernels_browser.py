"""While the kernels compile in the background (issue 19: the explorer serves at once), the
home page and a case page say so in plain words, and a run still works. The warm-up is a
scripted stand-in (tests/test_kernel_warmup.py's `scripted`) that stays in its first part
for the whole test, so the pages are seen mid-warm-up; the caches themselves are warm."""

import httpx
import pytest
from playwright.sync_api import expect

from app.testing import live_server
from tests.test_kernel_warmup import scripted


@pytest.fixture(scope="module")
def warming_server():
    with live_server(warm_kernels=True, kernels_warm=False,
                     warmup_command=scripted(600.0)) as url:
        yield url


def ready(page):
    page.locator("body[data-ready='1']").wait_for(state="attached")


def test_pages_say_which_kernels_still_warm(page, warming_server, artifacts):
    k = httpx.get(f"{warming_server}/api/health").json()["kernels"]
    assert k["state"] == "running" and k["parts_done"] == 0, k
    page.goto(warming_server + "/")
    ready(page)
    line = page.locator("#kernel-status")
    expect(line).to_contain_text("Kernels: 0 of 3 parts compiled, in the background.")
    expect(line).to_contain_text("compiles its kernel before it starts (about 15 s, "
                                 "first use on this machine)")
    page.screenshot(path=str(artifacts / "home-warming.png"))

    # a case of the structure still compiling
    page.goto(warming_server + "/case/sphere/routh-ball")
    ready(page)
    expect(page.locator("#kernel-status")).to_have_text(
        "Kernels: 0 of 3 parts compiled; a run of this case compiles its kernel before it "
        "starts (about 15 s, first use on this machine).")
    # the run compiles first (here: loads what is cached, in a job without a deadline),
    # then runs and plots
    c = httpx.post(f"{warming_server}/api/simulate/compiles", json={
        "case": "sphere/routh-ball", "example": True, "t_end": 5.0, "samples": 51}).json()
    assert c["compiles"] is True and c["estimate_s"] == 15.0
    page.click("#run")
    page.wait_for_function("document.body.dataset.run === '1'", timeout=120_000)
    expect(page.locator("#runinfo")).to_contain_text("ok")
