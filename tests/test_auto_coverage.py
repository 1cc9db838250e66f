"""A cheap smoke run of bench/auto_coverage.py's measurement: on a couple of random starts
(bench/limit.py's generator, |M| spread over two decades) auto's returned run is within the
requested error against an independent reference (heyoka in long double on the general
expression system), and its estimate, an upper estimate by extrapolation, is above the
achieved error and within a factor 30 of it."""

import sys
from pathlib import Path

import numpy as np
import pytest

pytest.importorskip("heyoka")
sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "bench"))

from solvers.integrate.auto import error_between
from solvers.integrate.taylor import Taylor
from solvers.models.cases import build, registry
from solvers.simulate import simulate


@pytest.mark.parametrize("case", ["plane/chaplygin-ball", "sphere/flat-base"])
def test_auto_meets_the_request_on_random_starts(case):
    from limit import random_starts

    spec = registry()[case]
    model = build(case, spec.example)
    starts = random_starts(case, spec.example, 2, np.random.default_rng(5))
    T, E = 50.0, 1e-9
    t = np.linspace(0.0, T, 51)
    ref = Taylor(model.model, model.p, starts[0], tol=1e-19, fp="longdouble",
                 compact_mode=True)
    for y0 in starts:
        Yref, _, _, _, ok = ref.run(y0, t)
        assert ok
        r = simulate(case, spec.example, list(y0), T, method="auto", rtol=E, atol=E,
                     samples=51)
        achieved = error_between(r.state, Yref)
        assert r.ok and r.stats["auto"]["met"]
        assert achieved <= E, (y0, achieved, r.stats["error_estimate"])
        assert achieved <= r.stats["error_estimate"] <= 30 * achieved
