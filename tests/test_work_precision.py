"""The committed work-precision results (bench/work_precision.py), their summary, the
explorer's GET /api/work-precision and page, `rolling bench`, and the batch runner."""

import json
import math
from pathlib import Path

import numpy as np
import pytest
from fastapi.testclient import TestClient

from solvers.integrate import workprecision as wp
from solvers.integrate.batch import integrate_batch
from solvers.integrate.integrator import Section, integrate
from solvers.models.cases import build, registry

pytestmark = pytest.mark.filterwarnings("ignore::DeprecationWarning")


def test_committed_results_cover_the_cases_and_methods():
    data = wp.load_results()
    ids = {c["id"] for c in data["cases"]}
    assert {"plane/chaplygin-ball", "plane/unbalanced-ball", "plane/round-disk",
            "plane/ellipsoid", "sphere/chaplygin-ball", "sphere/flat-base"} <= ids
    methods = {r["method"] for r in data["runs"]}
    assert set(wp.OURS) | {wp.HEYOKA, wp.SCIPY_COMPILED} <= methods
    for r in data["runs"]:
        if r["ok"]:
            assert r["error"] is not None and math.isfinite(r["error"]) and r["wall_s"] > 0


def test_data_file_names_its_format_and_generator(tmp_path):
    data = wp.load_results()
    assert data["format"] == wp.FORMAT
    assert data["generator"].startswith(wp.GENERATOR)
    # the generator is a script of this checkout
    script = data["generator"].split(",")[0].split()[1]
    assert (Path(__file__).resolve().parents[1] / script).is_file()
    # a file without the fields (format 1) is read; an unknown format is refused
    raw = {k: v for k, v in json.loads(wp.RESULTS.read_text()).items()
           if k not in ("format", "generator")}
    old = tmp_path / "old.json"
    old.write_text(json.dumps(raw))
    assert wp.load_results(old)["cases"]
    for bad in ({**raw, "format": wp.FORMAT + 1}, {**raw, "format": "1"},
                {**raw, "generator": 3}, {k: v for k, v in raw.items() if k != "runs"}):
        path = tmp_path / "bad.json"
        path.write_text(json.dumps(bad))
        wp._load.cache_clear()
        with pytest.raises(ValueError):
            wp.load_results(path)


def test_summary_is_consistent_with_the_runs():
    data = wp.load_results()
    for cid, s in data["summary"].items():
        assert s["default_method"] in wp.PLAIN
        assert s["tolerance_buys"]
        for row in s["table"]:
            best = row["ours"]
            if best is not None:
                assert best["error"] <= row["level"]
                runs = [r for r in data["runs"] if r["case"] == cid
                        and r["method"] in wp.OURS and r["ok"] and r["error"] <= row["level"]]
                assert best["wall_s"] == min(r["wall_s"] for r in runs)


def test_pareto_front_is_monotone():
    runs = [{"ok": True, "error": e, "wall_s": w, "method": "x", "tol": 0, "rhs_calls": 0}
            for e, w in ((1e-3, 1.0), (1e-5, 2.0), (1e-4, 3.0), (1e-8, 4.0))]
    front = wp.pareto(runs)
    assert [r["error"] for r in front] == [1e-8, 1e-5, 1e-3]


def test_api_and_page():
    from app.main import create_app
    from app.testing import settings_for_tests

    with TestClient(create_app(settings_for_tests(warm_workers=False))) as client:
        r = client.get("/api/work-precision")
        assert r.status_code == 200
        body = r.json()
        assert body["summary"] and body["runs"] and body["cases"]
        page = client.get("/work-precision")
        assert page.status_code == 200 and 'id="wp-cases"' in page.text
        js = client.get("/static/js/work_precision.js")
        assert js.status_code == 200 and "/api/work-precision" in js.text


def test_default_method_falls_back():
    assert wp.default_method("no/such-case") == "dop853"
    assert wp.default_method("plane/chaplygin-ball") in wp.PLAIN


def test_simulate_auto_picks_from_the_fronts_at_the_requested_error():
    """auto is chosen per case and tolerance (solvers/integrate/auto.py; it was the case's
    default method regardless of rtol before issue 12), from the fronts measured over many
    starts (solvers/integrate/auto_choice.py)."""
    from solvers.integrate import auto, auto_choice
    from solvers.simulate import simulate

    c = registry()["plane/ellipsoid"]
    r = simulate("plane/ellipsoid", c.example, c.state, 10.0, method="auto", samples=11)
    pick = auto_choice.first_choice("plane/ellipsoid", 1e-10, auto.CANDIDATES)  # the default rtol
    assert r.ok and r.stats["auto"]["method"] == pick["method"]
    assert r.stats["auto"]["tol"] == pick["tol"]


def test_batch_equals_one_by_one_on_two_threads():
    c = registry()["sphere/chaplygin-ball"]
    m = build("sphere/chaplygin-ball", c.example)
    rng = np.random.default_rng(0)
    Y0 = []
    for _ in range(6):
        y = np.array(c.state)
        y[:3] += 0.1 * rng.standard_normal(3)
        Y0.append(y)
    sec = Section(coef=(0, 0, 0, 0, 0, 1.0))
    batch = integrate_batch(m.model, m.p, Y0, [0.0, 300.0], workers=2, section=sec,
                            max_crossings=20)
    for y0, r in zip(Y0, batch, strict=True):
        one = integrate(m.model, m.p, y0, [0.0, 300.0], section=sec, max_crossings=20)
        assert np.array_equal(one.crossings_y, r.crossings_y)
        assert np.array_equal(one.y, r.y)
