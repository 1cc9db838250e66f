"""The unrolled steppers (solvers/kernels/unroll.py) against rk.py's tableau loops: the same
kernel source with only its five tableau loops written out, so every run must give the
same status, the same step, rejection and rhs counts and the same states (bit for bit: the
unrolled sums add the same nonzero products in the same order; a dropped term is an exact
zero), for every case, every tableau and every option the kernel has (samples by dense
output, sections, projection, compensated sums, clipped steps, fixed steps, step budget,
singular stops), and the extremes of tests/test_extremes.py.

The 16 cases run on one module (the general field, the tableaux unrolled, the state
dimension a run-time value). The per-case generated module, where the generated field is
inlined into the unrolled stages, is compared with its own loops in
tests/test_generated_integrator.py (with the other tests that compile it)."""

import math

import numpy as np
import pytest

from solvers.integrate import integrator
from solvers.integrate.integrator import Section, integrate, method_arrays
from solvers.integrate.tableaux import METHODS
from solvers.kernels import generate, rk
from solvers.kernels import layout as L
from solvers.kernels.integrals import ENERGY
from solvers.models.cases import build, case_ids, registry

OSC = L.MODEL_TEST_OSC


class _Kernel:
    def __init__(self, fn):
        self.rk_integrate = fn


def pair(monkeypatch, mod, model, p, y0, t_out, **kw):
    """integrate() through mod.rk_integrate (unrolled) and mod.rk_integrate_generic (loops),
    packed by integrate() itself; model MODEL_FULL/FLAT take the generated=True route,
    others are run by swapping rk.rk_integrate."""
    out = []
    for fn in (mod.rk_integrate, mod.rk_integrate_generic):
        if model in generate.GENERATED_MODELS:
            monkeypatch.setattr(integrator.generate, "generated_integrator",
                                lambda *a, fn=fn, **k: _Kernel(fn))
            # integrate() memoizes the generated module per case and its readiness: fresh
            # memos per call, so each call runs this fn and none outlives the test
            monkeypatch.setattr(integrator, "_GEN_MODULES", {})
            monkeypatch.setattr(integrator, "_GEN_READY", {})
            monkeypatch.setattr(integrator, "_mark_ready", lambda *a: None)
            # kernel="rk": a plain run would otherwise take the small kernel (issue 19)
            out.append(integrate(model, p, y0, t_out, generated=True, kernel="rk", **kw))
        else:
            monkeypatch.setattr(integrator.rk, "rk_integrate", fn)
            out.append(integrate(model, p, y0, t_out, **kw))
    return out


def assert_same(a, b):
    assert (a.status, a.steps, a.rejected, a.rhs_calls) == \
        (b.status, b.steps, b.rejected, b.rhs_calls), (a.message, b.message)
    assert a.t_stop == b.t_stop
    np.testing.assert_array_equal(a.y, b.y)
    np.testing.assert_array_equal(a.y_stop, b.y_stop)
    np.testing.assert_array_equal(a.crossings_t, b.crossings_t)
    np.testing.assert_array_equal(a.crossings_y, b.crossings_y)


@pytest.fixture(scope="module")
def general():
    return generate.unrolled_general(METHODS)


def test_every_shipped_tableau_is_recognised(general):
    for t, name in enumerate(sorted(METHODS)):
        A, c, b, E, P, meth = method_arrays(name)
        assert general._which(A, c, b, E, P, meth) == t
        assert general._which(A, c, b, E, np.zeros((0, 1)), meth) == t   # no dense output
    A, c, b, E, P, meth = method_arrays("dop853")
    b2 = b.copy()
    b2[0] = np.nextafter(b2[0], 1.0)
    assert general._which(A, c, b2, E, P, meth) == -1      # any other tableau: the loops


@pytest.mark.parametrize("method", METHODS)
@pytest.mark.parametrize("case", case_ids())
def test_unrolled_equals_loops_on_every_case(monkeypatch, general, case, method):
    c = registry()[case]
    m = build(case, c.example)
    t = np.linspace(0.0, 10.0, 23)         # samples inside steps: dense output
    a, b = pair(monkeypatch, general, m.model, m.p, c.state, t, method=method, rtol=1e-9,
                atol=1e-11)
    assert a.success, a.message
    assert a.steps > 5
    assert_same(a, b)


OPTIONS = {
    "section": dict(section=Section(coef=(0, 0, 0, 1.0, 0, 0), direction=0),
                    max_crossings=5),
    "projection": dict(project_codes=(ENERGY,), project_every=3),
    "compensated": dict(compensated=True),
    "clipped": dict(dense_output=False),
    "fixed": dict(h_fixed=0.05),
    "budget": dict(max_steps=8),
}


@pytest.mark.parametrize("method", METHODS)
@pytest.mark.parametrize("option", sorted(OPTIONS))
def test_unrolled_equals_loops_with_every_option(monkeypatch, general, option, method):
    case = "plane/chaplygin-ball"
    c = registry()[case]
    m = build(case, c.example)
    t = np.linspace(0.0, 30.0, 31)
    a, b = pair(monkeypatch, general, m.model, m.p, c.state, t, method=method, rtol=1e-9,
                atol=1e-11, **OPTIONS[option])
    if option == "budget":
        assert a.status == rk.MAX_STEPS
    elif option == "section":
        assert a.success and len(a.crossings_t) >= 2, (a.message, a.crossings_t)
    else:
        assert a.success, a.message
    assert_same(a, b)


EXTREMES = [   # tests/test_extremes.py and tests/test_generated.py::test_extremes_agree
    ("plane/round-disk", {}, [0.0, 0.3, 3.0, 1e-2, 0.0, math.sqrt(1 - 1e-4)], 10.0, {}),
    ("plane/round-disk", {}, [0.0, 0.3, 3.0, 1e-6, 0.0, math.sqrt(1 - 1e-12)], 10.0, {}),
    ("plane/round-disk", {}, [10.0, 0.0, 5e3, math.cos(1e-3), 0.0, math.sin(1e-3)], 0.02, {}),
    ("sphere/chaplygin-ball", {"k": 1.0 - 1e-4}, None, 1e-3, {}),
    ("sphere/chaplygin-ball", {"k": 1.0 - 1e-8}, None, 1e-7, {"max_steps": 3000}),
    ("plane/chaplygin-ball", {"I2": 1.0 + 1e-12, "I3": 1.5}, None, 10.0, {}),
    ("plane/chaplygin-ball", {"I1": 1e-6, "I2": 2e-6, "I3": 2.5e-6}, None, 1e-4, {}),
    ("plane/chaplygin-ball", {"I1": 1e6, "I2": 2e6, "I3": 2.5e6}, None, 10.0, {}),
    ("plane/chaplygin-ball", {}, [0.5e4, -0.3e4, 0.8e4, 0.3, 0.4, 0.8660254037844386], 0.01,
     {}),
]


@pytest.mark.parametrize("method", ["dop853", "vern9"])
@pytest.mark.parametrize(("case", "params", "state", "t_end", "kw"), EXTREMES)
def test_unrolled_equals_loops_on_the_extremes(monkeypatch, general, case, params, state,
                                               t_end, kw, method):
    extreme(monkeypatch, general, case, params, state, t_end, kw, method)


def extreme(monkeypatch, general, case, params, state, t_end, kw, method):
    c = registry()[case]
    m = build(case, {**c.example, **params})
    y0 = c.state if state is None else state
    a, b = pair(monkeypatch, general, m.model, m.p, y0, np.linspace(0.0, t_end, 11),
                method=method, rtol=1e-10, atol=1e-12, **kw)
    assert_same(a, b)
    return a


def test_singular_stops_are_the_same(monkeypatch, general):
    """The disk falling through flat (SING_EDGE) and the ball that barely fits on its step
    budget stop at the same place with the same status."""
    a = extreme(monkeypatch, general, *EXTREMES[1], "dop853")
    assert a.status == L.SING_EDGE
    a = extreme(monkeypatch, general, *EXTREMES[4], "dop853")
    assert a.status == rk.MAX_STEPS


@pytest.mark.parametrize("method", METHODS)
def test_test_models_and_grazing_sections(monkeypatch, general, method):
    """The oscillator with a grazed section (Henon steps, refinement) and a fixed step."""
    sec = Section(coef=(1.0, 0.0), offset=1.0 - 1e-6, direction=0)
    a, b = pair(monkeypatch, general, OSC, np.zeros(L.N_PARAMS), [0.0, 1.0],
                np.linspace(0.0, 6 * math.pi, 7), method=method, rtol=1e-10, atol=1e-12,
                section=sec)
    assert a.status == 0 and len(a.crossings_t) == 6
    assert_same(a, b)


