"""Every rubber case over 10^4 time units: the constraint (omega, gamma) = 0, |gamma| = 1 and
the energy hold.

Projected (project=True: after every step Newton onto the levels of the case's integrals
energy, gamma^2 and spin = (omega, gamma), solvers/kernels/projection.py), they hold to
round-off: asserted below 1e-13. Unprojected (the default route, the generated field in its
small kernel, rtol = 1e-12, atol = 1e-14), they hold to the tolerance accumulated over the
run: asserted below T * rtol = 1e-8 (the local error per unit time, summed over T)."""

import numpy as np
import pytest

import solvers
from solvers.models.cases import registry, rubber_case_ids

T = 1e4
RTOL = 1e-12


def _defects(res):
    """max |(omega, gamma)|, max ||gamma| - 1|, the energy's drift."""
    g = np.linalg.norm(res.state[:, 3:], axis=1)
    return (float(np.max(np.abs(res.invariants["spin"]))), float(np.max(np.abs(g - 1.0))),
            res.drift("energy"))


@pytest.mark.parametrize("cid", rubber_case_ids())
def test_projected_run_holds_the_rubber_manifold_to_round_off(cid):
    spec = registry()[cid]
    res = solvers.simulate(cid, spec.example, spec.state, t_end=T, samples=2001, project=True)
    assert res.ok and res.t[-1] == T and res.stats["projected"]
    spin, unit, energy = _defects(res)
    assert spin < 1e-13 and unit < 1e-13 and energy < 1e-13, (spin, unit, energy)


@pytest.mark.parametrize("cid", rubber_case_ids())
def test_plain_run_holds_the_rubber_manifold_to_its_tolerance(cid):
    spec = registry()[cid]
    res = solvers.simulate(cid, spec.example, spec.state, t_end=T, samples=2001, rtol=RTOL,
                           atol=RTOL * 1e-2)
    assert res.ok and res.t[-1] == T and res.stats["field"] == "generated"
    spin, unit, energy = _defects(res)
    bound = T * RTOL
    assert spin < bound and unit < bound and energy < bound, (spin, unit, energy)
