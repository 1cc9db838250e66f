"""Work-precision of the rubber cases (bench/work_precision.py --cases): the merge that
measures only the named cases and keeps the others' runs, the heyoka reference's rubber
field, the committed rubber runs as GET /api/work-precision serves them, and the labels
of the rubber integrals in the simulator's drift plot (app/static/js/plots.js)."""

import importlib.util
import json
import re
import sys
from pathlib import Path

import numpy as np
import pytest

from solvers.integrate import workprecision as wp

ROOT = Path(__file__).resolve().parents[1]
RUBBER = "rubber-plane/chaplygin-ball"
MARBLE = ("plane/chaplygin-ball", "plane/unbalanced-ball", "plane/round-disk",
          "plane/ellipsoid", "sphere/chaplygin-ball", "sphere/flat-base")

pytestmark = pytest.mark.filterwarnings("ignore::DeprecationWarning")


def _bench():
    spec = importlib.util.spec_from_file_location("bench_work_precision",
                                                  ROOT / "bench" / "work_precision.py")
    mod = importlib.util.module_from_spec(spec)
    sys.modules[spec.name] = mod        # its dataclasses look their module up there
    spec.loader.exec_module(mod)
    return mod


def _run(case, method, tol, error):
    return {"case": case, "method": method, "tol": tol, "error": error, "wall_s": 1e-3,
            "rhs_calls": 10, "steps": 5, "ok": True, "message": "", "knob": "tol"}


def test_merge_replaces_the_named_case_and_keeps_the_others():
    b = _bench()
    data = {"format": wp.FORMAT, "cases": [{"id": "a", "t_end": 1.0}, {"id": "c", "t_end": 2.0}],
            "runs": [_run("a", "dop853", 1e-6, 1e-5), _run("c", "dop853", 1e-6, 2e-5),
                     _run("c", "vern9", 1e-6, 3e-5)]}
    before = json.loads(json.dumps(data))
    new = b.merged(data, b.WPCase("c", t_end=5.0, note="n"), {"reference": "r"},
                   [_run("c", "vern9", 1e-8, 4e-9)])
    assert data == before                      # the input is not changed
    assert [c["id"] for c in new["cases"]] == ["a", "c"]
    assert new["cases"][1] == {"id": "c", "overrides": {}, "t_end": 5.0, "note": "n",
                               "reference": "r"}
    assert new["runs"] == [_run("a", "dop853", 1e-6, 1e-5), _run("c", "vern9", 1e-8, 4e-9)]
    # a case not yet in the data is appended
    added = b.merged(data, b.WPCase("d"), {}, [_run("d", "dop853", 1e-6, 1e-6)])
    assert [c["id"] for c in added["cases"]] == ["a", "c", "d"]
    assert added["runs"][:3] == data["runs"]


def test_unknown_case_id_is_refused_before_anything_runs():
    b = _bench()
    assert [c.id for c in b.pick_cases(f" {RUBBER}, plane/ellipsoid")] == [
        RUBBER, "plane/ellipsoid"]
    before = wp.RESULTS.read_bytes()
    for bad in ("no/such-case", f"{RUBBER},no/such-case", ","):
        with pytest.raises(SystemExit, match="--cases"):
            b.main(["--cases", bad])
    assert wp.RESULTS.read_bytes() == before


def test_heyoka_reference_system_has_the_rubber_reaction():
    """The reference's expression system (solvers/integrate/taylor.py) against the
    compiled rubber field, at states along a rubber run (on the constraint manifold)."""
    pytest.importorskip("heyoka")
    from solvers.integrate.integrator import integrate
    from solvers.integrate.taylor import field_function
    from solvers.kernels import layout as L
    from solvers.kernels.fields import rhs
    from solvers.models.cases import build, initial_state, registry

    for cid in (RUBBER, "rubber-sphere/ball-inside"):
        spec = registry()[cid]
        m = build(cid, spec.example)
        y0 = initial_state(m, spec.state)
        f = field_function(m.model, m.p)
        run = integrate(m.model, m.p, y0, np.linspace(0.0, 20.0, 6), method="vern9",
                        rtol=1e-12, atol=1e-12)
        d = np.empty(m.dim)
        for y in run.y:
            rhs(m.model, 0.0, y, m.p, d)
            assert np.max(np.abs(f(y) - d)) < 1e-14 * max(1.0, np.max(np.abs(d))), cid
        # the marble field of the same body differs: the reaction is really there
        p = np.array(m.p, dtype=float)
        p[L.RUBBER] = 0.0
        g = field_function(m.model, p)
        assert np.max(np.abs(g(run.y[-1]) - f(run.y[-1]))) > 1e-3, cid


def test_committed_rubber_runs_are_served_and_summarised():
    from fastapi.testclient import TestClient

    from app.main import create_app
    from app.testing import settings_for_tests

    with TestClient(create_app(settings_for_tests(warm_workers=False))) as client:
        body = client.get("/api/work-precision").json()
    ids = [c["id"] for c in body["cases"]]
    assert set(MARBLE) | {RUBBER} <= set(ids)
    entry = next(c for c in body["cases"] if c["id"] == RUBBER)
    assert entry["reference"] == "heyoka long double, tol 1e-19"
    # the long-double reference and its real128 check agree to round-off of double
    assert entry["reference_error_bound"] < 1e-13
    runs = [r for r in body["runs"] if r["case"] == RUBBER]
    methods = {r["method"] for r in runs}
    assert set(wp.OURS) | {wp.HEYOKA, wp.TAYLOR, wp.SCIPY_COMPILED, wp.SCIPY_NUMPY} <= methods
    assert all(r["ok"] and r["error"] is not None for r in runs
               if r["method"] in wp.PLAIN and r["tol"] >= 1e-12)
    # the compiled field and the reference's independent expression system agree: ours
    # comes far below the errors of a loose tolerance
    assert min(r["error"] for r in runs if r["method"] in wp.PLAIN and r["ok"]) < 1e-11
    # scipy's DOP853 on the Lagrange-d'Alembert field (NumPy) and on the compiled field take
    # the same steps and make the same error: the two derivations give the same motion, to
    # far less than the integration error
    by = {m: {r["tol"]: r for r in runs if r["method"] == m and r["ok"]}
          for m in (wp.SCIPY_NUMPY, wp.SCIPY_COMPILED)}
    tight = [t for t in by[wp.SCIPY_NUMPY] if t <= 1e-6]
    assert len(tight) >= 4
    for t in tight:
        a, c = by[wp.SCIPY_NUMPY][t], by[wp.SCIPY_COMPILED][t]
        assert a["rhs_calls"] == c["rhs_calls"], t
        assert abs(a["error"] - c["error"]) < 0.05 * c["error"], t
    s = body["summary"][RUBBER]
    assert s["default_method"] in wp.PLAIN and s["tolerance_buys"] and s["table"]


def _js_labels():
    text = (ROOT / "app/static/js/plots.js").read_text()
    block = re.search(r"const INVARIANT_NAMES = \{(.*?)\n\};", text, re.S).group(1)
    block = re.sub(r"//[^\n]*", "", block)
    return dict(re.findall(r"(\w+): \"([^\"]+)\"", block))


def test_every_integral_has_a_typeset_drift_plot_label():
    """Every first integral a run can report (kernels' NAMES under their public names) is
    named in the drift plot's legend by a label, not by its code name."""
    from solvers.kernels.integrals import NAMES
    from solvers.models.observables import public_name

    labels = _js_labels()
    names = [public_name(n) for n in NAMES]
    missing = [n for n in names if n not in labels]
    assert not missing, missing
    assert len({labels[n] for n in names}) == len(names)          # no two alike
    assert all(labels[n] != n for n in names)
    assert labels["spin"] == "(ω, γ)" and labels["rubber_ball_F"] == "|M × γ|²"
    assert labels["rubber_routh"].startswith("N ω₃")
