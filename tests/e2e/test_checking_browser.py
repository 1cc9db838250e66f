"""Verdicts on a fresh server and after a restart, in chromium (issue 11, items 3 and 4).

A server with an empty verdict store checks every case in the background. Until a case is
done its cells and claims show the distinct "checking" state (…), never "?" (which means
only "not checkable"), and the case page redraws itself when the check finishes. A restart
on the same store then serves the stored verdicts at once: in the first HTML answer,
before any script runs and with no verification running.
"""

import re

import httpx
from playwright.sync_api import expect

from app.testing import live_server

CASE = "sphere/borisov-fedorov"      # the quickest case to check (well under a second)


def test_checking_state_then_a_restart_serves_stored_verdicts_at_once(page, tmp_path):
    fresh = {"cache_dir": tmp_path, "use_verdict_cache": True, "verify_on_start": True,
             "workers": 2}
    with live_server(**fresh) as url:
        h = httpx.get(f"{url}/api/health").json()["verification"]
        assert h["state"] == "running" and h["cases_done"] == 0, h
        # the home page: cells of cases being checked carry the "checking" mark
        page.goto(url + "/")
        page.locator("body[data-ready='1']").wait_for(state="attached")
        expect(page.locator("#verify-status")).to_contain_text("Computing verdicts")
        mark = page.locator(f'#tbl-sphere .mk[data-case="{CASE}"]').first
        expect(mark).to_have_class(re.compile(r"\bpending\b"))
        expect(mark).to_have_text(re.compile(r"^…"))
        # the case page: every claim "checking", none "?", and the page says it will update
        page.goto(f"{url}/case/{CASE}")
        page.locator("body[data-ready='1']").wait_for(state="attached")
        claims = page.locator("#claimlist article.claim")
        n = claims.count()
        assert n > 0 and page.locator("#claimlist article.claim.pending").count() == n
        assert page.locator("#claimlist .badge.not-checkable").count() == 0
        expect(page.locator("#claimlist .badge.pending").first).to_have_text("… checking")
        expect(page.locator("#tally")).to_contain_text("the page updates when the check")
        expect(page.locator("#claimlist p.checked").first).to_contain_text("being checked now")
        # the check of this case finishes (asked for directly, not waiting for its turn in
        # the background queue): the open page redraws itself, with no reload
        r = httpx.post(f"{url}/api/verify/{CASE}", json={}, timeout=300.0)
        assert r.status_code == 200, r.text
        page.locator("body[data-checked='1']").wait_for(state="attached", timeout=30_000)
        assert page.locator("#claimlist article.claim.pending").count() == 0
        expect(page.locator("#claimlist .badge.as-printed").first).to_be_visible()
        done = {c.get_attribute("id"): c.get_attribute("class") for c in claims.all()}
    # a restart on the same store, with no verification at all: what it shows, it read
    with live_server(cache_dir=tmp_path, use_verdict_cache=True, verify_on_start=False,
                     warm_workers=False, workers=1) as url:
        first_html = httpx.get(f"{url}/case/{CASE}").text
        assert "holds as printed" in first_html     # the marks of issue 17
        assert "checking" not in re.sub(r"<script.*?</script>", "", first_html, flags=re.S)
        page.goto(f"{url}/case/{CASE}")
        page.locator("body[data-ready='1']").wait_for(state="attached")
        assert {c.get_attribute("id"): c.get_attribute("class")
                for c in claims.all()} == done
        expect(page.locator("#claimlist .verdict-line").first).to_contain_text("computed 20")
