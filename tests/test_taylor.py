"""heyoka's expression system of the rolling field (solvers/integrate/taylor.py), an independent
implementation (symbolic r = grad h, J = Hess h of the support function), against the
compiled field; and heyoka's Taylor integrator against ours on a short run."""

import numpy as np
import pytest
from conftest import random_states
from test_fields import with_potentials

from solvers.kernels import layout as L
from solvers.models.cases import build, registry
from solvers.models.derivatives import field

hy = pytest.importorskip("heyoka")

from solvers.integrate.taylor import Taylor, field_function  # noqa: E402

CASES = [c for c in ("plane/chaplygin-ball", "plane/unbalanced-ball", "plane/round-disk",
                     "plane/ellipsoid", "plane/spherical-inertia", "sphere/chaplygin-ball",
                     "sphere/round-disk", "sphere/flat-base", "plane/rattleback")
         if c in registry()]


@pytest.mark.parametrize("case_id", CASES)
def test_expression_system_equals_the_compiled_field(case_id):
    model = build(case_id, with_potentials(case_id))
    f = field_function(model.model, model.p)
    rng = np.random.default_rng(5)
    for y in random_states(model, 20, rng, 0.3):
        d, status = field(model.model, model.p, y)
        assert status == L.OK
        assert np.max(np.abs(f(y) - d)) <= 1e-13 * np.max(np.abs(d)) + 1e-15


def test_taylor_run_agrees_with_ours():
    from solvers.integrate.integrator import integrate

    c = registry()["plane/chaplygin-ball"]
    model = build("plane/chaplygin-ball", c.example)
    y0 = np.array(c.state)
    t = np.linspace(0.0, 20.0, 11)
    ta = Taylor(model.model, model.p, y0, tol=1e-15, compact_mode=True)
    Y, _, _, _, ok = ta.run(y0, t)
    assert ok
    ours = integrate(model.model, model.p, y0, t, method="vern9", rtol=1e-14, atol=1e-16)
    assert np.abs(Y - ours.y).max() < 1e-12


def test_extended_precision_reference_agrees_with_float64():
    c = registry()["sphere/flat-base"]
    model = build("sphere/flat-base", c.example)
    y0 = np.array(c.state)
    t = np.linspace(0.0, 10.0, 6)
    ld = Taylor(model.model, model.p, y0, tol=1e-19, fp="longdouble", compact_mode=True)
    Yl, native, _, _, ok = ld.run(y0, t)
    assert ok and native.dtype == np.longdouble
    f64 = Taylor(model.model, model.p, y0, tol=1e-16, compact_mode=True)
    Yd, _, _, _, ok2 = f64.run(y0, t)
    assert ok2 and np.abs(Yl - Yd).max() < 1e-13
