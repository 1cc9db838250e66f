"""A run's data with its provenance, in chromium: the case page's CSV begins with the run's
case, parameters, method, tolerances, version, date and the address that reproduces it,
carries the JSON's column names and a file name with the hash of the run's inputs; that
address runs the same run again. On /errata each symbol of a formula links to its
definition on /notation, which a click opens in place."""

import csv
import re
from pathlib import Path

import httpx
import pytest
from playwright.sync_api import expect

from tests.e2e.servers import stored_verdicts_server

CASE = "plane/chaplygin-ball"


def _download_csv(page) -> tuple[str, str]:
    with page.expect_download() as dl:
        page.click("#dl-csv")
    return dl.value.suggested_filename, Path(dl.value.path()).read_text()


def _split(text: str) -> tuple[dict, list[list[str]]]:
    lines = text.splitlines()
    comments = [x for x in lines if x.startswith("# ")]
    assert lines[:len(comments)] == comments, "the '# ' lines come first"
    head = dict(x[2:].split(": ", 1) for x in comments)
    return head, list(csv.reader(lines[len(comments):]))


def _run(page, url):
    page.goto(url)
    page.locator("body[data-ready='1']").wait_for(state="attached")


def test_the_csv_carries_the_runs_provenance_and_reproduces_it(page, server, context):
    _run(page, f"{server}/case/{CASE}")
    page.fill("#f-t_end", "3.5")
    page.fill("#f-samples", "36")
    page.fill("#f-s-M1", "0.25")
    page.click("#run")
    page.locator("body[data-run='1']").wait_for(state="attached", timeout=120_000)
    name, text = _download_csv(page)
    m = re.fullmatch(r"plane_chaplygin-ball_t3\.5_([0-9a-f]{8})\.csv", name)
    assert m, name
    head, rows = _split(text)
    assert head["case"] == CASE and head["hash"] == m[1]
    assert "I1 = " in head["parameters"] and "R = " in head["parameters"]
    assert head["initial state"].startswith("0.25, ")
    assert head["method"].startswith("dop853")
    assert head["tolerances"].startswith("rtol = ") and "atol = " in head["tolerances"]
    health = httpx.get(f"{server}/api/health", timeout=30).json()
    assert head["version"] == f"rolling-hierarchy {health['version']}"
    assert re.fullmatch(r"\d{4}-\d\d-\d\dT\d\d:\d\d:\d\dZ", head["date"])
    assert head["reproduce"].startswith(f"{server}/case/{CASE}?run=1&")
    # the columns: the JSON's names, the component M2 beside the integral M_squared
    assert rows[0][:7] == ["t", "M1", "M2", "M3", "g1", "g2", "g3"]
    assert {"M_squared", "gamma_squared", "energy", "area"} <= set(rows[0])
    assert len(set(rows[0])) == len(rows[0]) and len(rows) == 1 + 36
    # the server's CSV of the same run begins with the same lines (but the date)
    server_csv = httpx.post(f"{server}/api/simulate?format=csv", timeout=120, json={
        "case": CASE, "params": {k: float(v) for k, v in
                                 (p.split(" = ") for p in head["parameters"].split(", "))},
        "state": [float(x) for x in head["initial state"].split(", ")],
        "t_end": 3.5, "samples": 36})
    assert server_csv.status_code == 200, server_csv.text
    s_head, s_rows = _split(server_csv.text)
    assert {k: v for k, v in s_head.items() if k != "date"} == \
        {k: v for k, v in head.items() if k != "date"}
    # the same numbers, bit for bit (each side writes the shortest repr: 0.0 or 0)
    assert s_rows[0] == rows[0]
    assert [[float(x) for x in r] for r in s_rows[1:]] == [[float(x) for x in r]
                                                            for r in rows[1:]]
    assert f'filename="{name}"' in server_csv.headers["content-disposition"]
    # the address in the header runs the same run: the same numbers, the same file name
    other = context.new_page()
    try:
        other.goto(head["reproduce"])
        other.locator("body[data-run='1']").wait_for(state="attached", timeout=120_000)
        again, text2 = _download_csv(other)
        assert again == name
        assert _split(text2)[1] == rows
    finally:
        other.close()


@pytest.fixture(scope="module")
def verified(catalogue_records, tmp_path_factory):
    with stored_verdicts_server(catalogue_records, tmp_path_factory.mktemp("verdicts")) as url:
        yield url


def test_errata_symbols_link_to_their_definitions(page, verified):
    rows = httpx.get(f"{verified}/api/errata", timeout=60).json()
    e = next(r for r in rows if r["kind"] == "misprint" and r["symbols"].get("corrected"))
    page.goto(f"{verified}/errata#{e['anchor']}")
    page.wait_for_function("document.body?.dataset.ready === '1'")
    row = page.locator(f"details.erow[id='{e['anchor']}']")
    expect(row).to_have_attribute("open", "")
    assert e["symbols"]["printed"] and e["symbols"]["corrected"]
    links = row.locator("p.symbols a.sym")
    hrefs = set(links.evaluate_all("els => els.map((a) => a.getAttribute('href'))"))
    want = {s["href"] for refs in e["symbols"].values() for s in refs}
    assert want <= hrefs, (want - hrefs)
    assert row.locator("p.symbols a.sym .katex").count() >= len(want)   # typeset
    # a click opens the definition in place, as on a case page; Escape closes it
    first = links.first
    sid, href = first.get_attribute("data-sym"), first.get_attribute("href")
    first.click()
    box = row.locator(".symbox")
    expect(box).to_be_visible()
    expect(box.locator("a[href^='/notation#sym-']")).to_have_count(1)
    page.keyboard.press("Escape")
    expect(box).to_have_count(0)
    # the link itself leads to the definition on /notation
    page.goto(f"{verified}{href}")
    expect(page.locator(f"#sym-{sid}")).to_be_visible()
