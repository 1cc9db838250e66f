"""The small kernels with sections and with projection (solvers/kernels/small.py,
sections=True, projection=True): a plain run's small kernel plus rk.py's section crossings
or its projection onto the levels of integrals, which integrate(kernel="small") runs
(integrate_ensemble(kernel="small") with a section), and the one with sections a Poincare
map of at least SMALL_MAP_CROSSINGS crossings takes (solvers/maps/poincare.py map_kernel).

That they take rk.py's generated integrator's steps bit for bit is
tests/test_generated_integrator.py's tests (the module that compiles that integrator).
Here: they follow the general kernel (the reference) to the tolerance, the ensemble gives
integrate()'s bits one by one, requests they cannot run are refused, and the map's rule
depends on the request only."""

import numpy as np
import pytest

from app.services import kernel_prepare
from solvers.integrate.ensemble import integrate_ensemble
from solvers.integrate.integrator import Section, integrate
from solvers.kernels import rk
from solvers.kernels.integrals import ENERGY
from solvers.maps.poincare import (
    SMALL_MAP_CROSSINGS,
    MapSpec,
    map_kernel,
    map_model,
    starts_for,
    trace_checked_all,
)
from solvers.models.cases import registry
from tests.test_ensemble import _same

CASE = "plane/chaplygin-ball"


@pytest.fixture(scope="module")
def ball():
    c = registry()[CASE]
    m = map_model(CASE, c.example)
    spec = MapSpec(energy=1.0, points=40)
    return m, spec, starts_for(m, spec, trajectories=3)


def test_follows_the_general_kernel(ball):
    """The same map runs on the general kernel (general field): the same crossings to the
    tolerance, the same steps give or take two (the fields differ in their last bits)."""
    m, spec, starts = ball
    t = np.linspace(0.0, 200.0, 2001)
    for y0 in starts:
        a = integrate(m.model, m.p, y0, t, section=spec.section(), max_crossings=30)
        b = integrate(m.model, m.p, y0, t, section=spec.section(), max_crossings=30,
                      kernel="small")
        assert (a.kernel, b.kernel) == ("rk", "small-sections")
        assert a.status == b.status and abs(a.steps - b.steps) <= 2
        assert len(a.crossings_t) == len(b.crossings_t) > 5
        np.testing.assert_allclose(b.crossings_t, a.crossings_t, rtol=1e-9)
        np.testing.assert_allclose(b.crossings_y, a.crossings_y, rtol=0, atol=1e-8)
        np.testing.assert_allclose(b.y, a.y, rtol=0, atol=1e-8)


def test_the_ensemble_gives_integrates_bits(ball):
    """Per trajectory on threads (ragged output times, their own crossing counts and
    step budgets), the bits of integrate(kernel="small") one by one."""
    m, spec, starts = ball
    T = np.zeros((3, 301))
    n_out = [301, 201, 101]
    for i, k in enumerate(n_out):
        T[i, :k] = np.linspace(0.0, 100.0, k)
    cross, steps = [7, 3, 20], [10**6, 10**6, 150]
    ens = integrate_ensemble(m.model, m.p, starts, T, n_out=n_out, section=spec.section(),
                             max_crossings=cross, max_steps=steps, kernel="small",
                             workers=2)
    for i, r in enumerate(ens):
        one = integrate(m.model, m.p, starts[i], T[i, :n_out[i]], section=spec.section(),
                        max_crossings=cross[i], max_steps=steps[i], kernel="small")
        assert r.kernel == one.kernel == "small-sections"
        _same(one, r)
    assert ens[1].status == rk.CROSSINGS_DONE and len(ens[1].crossings_t) == 3
    assert ens[2].status == rk.MAX_STEPS


def test_projection_follows_the_general_kernel(ball):
    """Projected onto the energy and |gamma|^2 levels every step: the general kernel's
    samples to the tolerance, the same steps give or take two, and the integrals held at
    round-off on the small kernel's samples."""
    from solvers.integrate.integrator import initial_integrals
    from solvers.kernels.integrals import NAMES

    m, _, starts = ball
    codes = (ENERGY, NAMES.index("gamma2"))
    t = np.linspace(0.0, 100.0, 201)
    a = integrate(m.model, m.p, starts[0], t, project_codes=codes)
    b = integrate(m.model, m.p, starts[0], t, project_codes=codes, kernel="small")
    assert (a.kernel, b.kernel) == ("rk", "small-projection")
    assert a.success and b.success and abs(a.steps - b.steps) <= 2
    np.testing.assert_allclose(b.y, a.y, rtol=0, atol=1e-8)
    want = initial_integrals(m.model, m.p, starts[0], np.array(codes))
    for y in b.y[::20]:
        got = initial_integrals(m.model, m.p, y, np.array(codes))
        np.testing.assert_allclose(got, want, rtol=4e-15)


@pytest.mark.parametrize("kw", [dict(project_codes=(ENERGY,)), dict(h_fixed=0.05),
                                dict(dense_output=False), dict(method="rk45"),
                                dict(generated=False)])
def test_a_run_it_cannot_take_is_refused(ball, kw):
    """Neither integrate nor the ensemble runs a small kernel where none fits (a section
    and a projection together, fixed or clipped steps, a tableau without one, the general
    field asked for); the ensemble has no small kernel with projection."""
    m, spec, starts = ball
    t = np.linspace(0.0, 1.0, 3)
    with pytest.raises(ValueError, match="kernel = 'small'"):
        integrate(m.model, m.p, starts[0], t, section=spec.section(), kernel="small", **kw)
    with pytest.raises(ValueError, match="kernel = 'small'"):
        integrate_ensemble(m.model, m.p, starts, t, section=spec.section(), kernel="small",
                           **kw)
    if "project_codes" not in kw:
        with pytest.raises(ValueError, match="kernel = 'small'"):
            integrate(m.model, m.p, starts[0], t, project_codes=(ENERGY,), kernel="small",
                      **kw)
    with pytest.raises(ValueError, match="kernel = 'small'"):
        integrate_ensemble(m.model, m.p, starts, t, project_codes=(ENERGY,), kernel="small")


def test_a_section_runs_the_general_kernel_unless_asked():
    """Sections are used by the checks, the scenes and the maps: none of them compiles a
    small kernel with sections unless it asks (kernel="small")."""
    c = registry()[CASE]
    m = map_model(CASE, c.example)
    r = integrate(m.model, m.p, c.state, np.linspace(0.0, 5.0, 3),
                  section=Section(coef=(0, 0, 0, 1.0, 0, 0)))
    assert (r.kernel, r.vector_field) == ("rk", "general")


def test_the_maps_kernel_is_decided_by_its_size(ball):
    """A map of SMALL_MAP_CROSSINGS crossings or more runs the small kernel, a smaller one
    the general kernel; a method or field without small kernels, the general one; an
    explicit choice stands. The request decides, whatever is compiled."""
    m, spec, _ = ball
    n = SMALL_MAP_CROSSINGS // spec.points
    assert map_kernel(m, spec, 8) == "general"
    assert map_kernel(m, spec, n - 1) == "general"
    assert map_kernel(m, spec, n) == "small"
    assert map_kernel(m, MapSpec(energy=1.0, points=40, method="rk45"), n) == "general"
    assert map_kernel(m, MapSpec(energy=1.0, points=40, generated=False), n) == "general"
    assert map_kernel(m, MapSpec(energy=1.0, points=40, kernel="small"), 1) == "small"
    assert map_kernel(m, MapSpec(energy=1.0, points=40, kernel="general"), n) == "general"
    with pytest.raises(Exception, match="kernel"):
        MapSpec(energy=1.0, kernel="fast").validate()


def test_a_map_on_the_small_kernel(ball):
    """The map's own machinery (pilot, chunks, the missed-crossing check) on the small
    kernel: the points of the general kernel's map to the tolerance, nothing missed, and
    the same bits on a second run."""
    from dataclasses import replace

    m, spec, starts = ball
    small = trace_checked_all(m, starts, replace(spec, kernel="small"), workers=1)
    again = trace_checked_all(m, starts, replace(spec, kernel="small"), workers=2)
    general = trace_checked_all(m, starts, spec, workers=1)
    for a, b, g in zip(small, again, general, strict=True):
        assert a.status == g.status == "ok" and len(a.t) == len(g.t) == spec.points
        assert a.check["missed"] == a.check["extra"] == 0
        np.testing.assert_array_equal(a.points, b.points)
        np.testing.assert_allclose(a.points, g.points, rtol=0, atol=1e-7)


def test_the_explorer_prepares_a_large_maps_kernel():
    """The route's key for a map's job: the general kernel's (compiled by the warm-up) or
    the small kernel with sections of its case and parameters, which is prepared before
    the map's deadline even on a warm server (the warm-up does not compile those)."""
    from app.services.kernel_warmup import KernelWarmup

    job = {"case": CASE, "params": {"I1": 1.0}, "spec": {"kernel": "small",
                                                         "method": "dop853"}}
    key = kernel_prepare.map_key(job)
    assert key[0] == "small-sections"
    general = kernel_prepare.map_key({**job, "spec": {**job["spec"], "kernel": "general"}})
    assert general == ("map", CASE, "dop853")
    warm = KernelWarmup()
    warm.state = "done"
    assert kernel_prepare.needed(warm, True, [key])
    assert not kernel_prepare.needed(warm, True, [general])
