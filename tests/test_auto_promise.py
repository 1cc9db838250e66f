"""auto's promise on the starts where it was broken: where stats.auto.met says the request
was met, the achieved error, against an independent reference (heyoka in long double on
the general expression system), is within it; and the runs stay in double.

The starts are the many-start benchmark's (bench/auto_coverage.py: seed 19, 20 starts per
case, drawn case after case), the ones bench/auto_coverage.py found missing the request:
the flat base at 1e-6, where an estimate from the pairs' exponent taken at 0.85 said met at
1.1 times the request (start 5), and where a compensated run past double's floor, taken
with the floor 110 times above the request, said met at 3.7 times it (start 14); the round
disk over T = 1000 at 1e-10, where the Taylor backend in double stops above the request
(the run past double's floor, vern9 with compensated sums, reaches it on start 7)."""

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

SEED, N_STARTS, SAMPLES = 19, 20, 101


def _start(case_id, k):
    """The k-th start (1-based) of case_id in the benchmark's draw, its parameters and T."""
    from auto_coverage import draw_only
    from limit import random_starts
    from work_precision import CASES

    rng = np.random.default_rng(SEED)
    for case in CASES:
        if case.id == case_id:
            prm = {**registry()[case.id].example, **case.overrides}
            return random_starts(case.id, prm, N_STARTS, rng)[k - 1], prm, case.t_end
        draw_only(case, N_STARTS, rng)
    raise KeyError(case_id)


@pytest.mark.parametrize("case, k, E", [("sphere/flat-base", 5, 1e-6),
                                         ("sphere/flat-base", 14, 1e-6),
                                         ("plane/round-disk", 7, 1e-10),
                                         ("plane/round-disk", 4, 1e-10)])
def test_met_implies_the_achieved_error_is_within_the_request(case, k, E):
    y0, prm, T = _start(case, k)
    model = build(case, prm)
    t = np.linspace(0.0, T, SAMPLES)
    ref, *_, ok = Taylor(model.model, model.p, y0, tol=1e-18, fp="longdouble",
                         compact_mode=True).run(y0, t)
    assert ok
    r = simulate(case, prm, list(y0), T, method="auto", rtol=E, atol=E, samples=SAMPLES)
    a = r.stats["auto"]
    achieved = error_between(r.state, ref)
    assert r.ok
    # the promise: met implies within the request
    assert (not a["met"]) or achieved <= E, (achieved, r.stats["error_estimate"], a["rounds"])
    # and an estimate of this run that is above its error where it says met
    if a["met"]:
        assert achieved <= r.stats["error_estimate"] <= E
    # a request above 1e-14 never runs in extended precision
    assert all(x["precision"] in (None, "double") for x in a["rounds"])
