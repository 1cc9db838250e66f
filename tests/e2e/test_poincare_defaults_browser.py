"""Browser: /poincare's defaults, case by case (app/static/data/poincare_defaults.json,
filled in by app/static/js/poincare.js): choosing a case fills the form with its defaults,
and the default map computed from them has returns on every trajectory (issue 20: on the
Borisov–Fedorov ball 4 of 6 default trajectories had none)."""

import json
from pathlib import Path

from playwright.sync_api import expect

DEFAULTS = json.loads((Path(__file__).resolve().parents[2] / "app" / "static" / "data"
                       / "poincare_defaults.json").read_text())


def test_every_case_default_map_returns_on_every_trajectory(page, server):
    page.goto(server + "/poincare")
    page.wait_for_function("document.body?.dataset.defaults === '1'", timeout=60_000)
    cases = page.eval_on_selector_all("#case option", "os => os.map((o) => o.value)")
    assert "sphere/borisov-fedorov" in cases and len(cases) >= 10, cases
    assert set(DEFAULTS["cases"]) <= set(cases), "a default names no case of the form"
    empty = {}
    for n, case in enumerate(cases, start=1):
        page.select_option("#case", case)
        want = {**DEFAULTS["form"], **DEFAULTS["cases"].get(case, {})}
        for k, v in want.items():
            if k == "why":
                continue
            got = page.input_value(f"[name={k}]")
            assert float(got) == float(v), (case, k, got, v)
        page.click("#run")
        page.wait_for_function(f"document.body.dataset.map === '{n}'", timeout=90_000)
        rows = page.eval_on_selector_all(
            "table.maptab tbody tr", "rs => rs.map((r) => [Number(r.cells[2].textContent), "
            "r.cells[3].textContent])")
        assert len(rows) == want["trajectories"], (case, rows)
        expect(page.locator("#map-status")).to_contain_text(
            f"{want['trajectories']} trajectories, {want['points']} points each")
        bad = [r for r in rows if r[0] == 0]
        if bad:
            empty[case] = bad
    assert not empty, f"default trajectories with no return: {empty}"
