"""The small kernels (solvers/kernels/small.py): one plain Runge-Kutta run per case structure
and tableau, state and stages in scalar locals, the generated field inlined.

Against the general kernel (rk.py on the general field, the reference): the same status,
the same accepted and rejected steps and rhs calls, the same samples to round-off, on every
case and on the extremes (near-flat disks, a ball that barely fits its sphere, tiny and huge
inertia, a fast start; a disk falling flat stops with SING_EDGE at the same place, a step
budget runs out at the same attempt). The fields differ in their last bits (generate.py
writes the equations differently), so the samples agree to round-off, not bit for bit.

Against the generated integrator (rk.py compiled against the same generated field, its
tableau loops): bit for bit, since the small kernel adds the same nonzero products in the
same order (a term it drops is an exact zero in the loops); this is what lets integrate()
run a plain request on the small kernel whatever is compiled, with the same answer
(tests/test_generated_integrator.py::test_same_bits_as_the_generated_integrator, beside
the other tests that compile it)."""

import math

import numpy as np
import pytest

from solvers.integrate import integrator
from solvers.integrate.integrator import integrate
from solvers.kernels import generate, rk, small_ops
from solvers.kernels import layout as L
from solvers.models.cases import build, case_ids, registry

GENERATED_CASES = [c for c in case_ids()
                   if build(c, registry()[c].example).model in generate.GENERATED_MODELS]


def run_both(case, params, state, t_out, method="dop853", **kw):
    c = registry()[case]
    m = build(case, {**c.example, **params})
    y0 = c.state if state is None else state
    a = integrate(m.model, m.p, y0, t_out, method=method, generated=False, **kw)
    b = integrate(m.model, m.p, y0, t_out, method=method, **kw)
    assert a.kernel == "rk" and a.vector_field == "general"
    assert b.kernel == "small" and b.vector_field == "generated"
    return a, b


def assert_follows(a, b, tol=1e-9):
    """b (the small kernel on the generated field) follows a (the general kernel on the
    general field): the same status, the states within tol, and the same steps give or
    take two: the two fields are equal to round-off, not bit for bit (the centred ball's
    omega by Sherman-Morrison, the general field's by a 3x3 solve), and a round-off
    difference in an error estimate may move one step (vern9 with h_max 0.5 on the
    Chaplygin ball: 65 steps against 64). That the small kernel takes rk.py's steps
    exactly, on the same field, is tests/test_generated_integrator.py's
    test_same_bits_as_the_generated_integrator."""
    assert a.status == b.status, (a.message, b.message)
    assert abs(a.steps - b.steps) <= 2 and abs(a.rejected - b.rejected) <= 2, \
        ((a.steps, a.rejected), (b.steps, b.rejected))
    assert a.t.shape == b.t.shape and a.y.shape == b.y.shape
    if a.y.size:
        scale = max(1.0, float(np.max(np.abs(a.y))))
        assert float(np.max(np.abs(a.y - b.y))) <= tol * scale
    assert math.isclose(a.t_stop, b.t_stop, rel_tol=1e-12, abs_tol=1e-300)


@pytest.mark.parametrize("case", GENERATED_CASES)
def test_small_follows_general_kernel_on_every_case(case):
    t = np.linspace(0.0, 10.0, 23)         # samples inside steps: dense output
    a, b = run_both(case, {}, None, t, rtol=1e-9, atol=1e-11)
    assert a.success and a.steps > 5, a.message
    assert_follows(a, b)


@pytest.mark.parametrize("method", ["dop853", "vern9"])
def test_small_vern9_and_options_of_a_plain_run(method):
    """vern9's small kernel; a given first step and a maximal step; a vector atol;
    compensated sums (what method="auto" runs)."""
    t = np.linspace(0.0, 30.0, 31)
    for kw in ({}, dict(control=integrator.StepControl(h0=0.01, h_max=0.5)),
               dict(atol=[1e-12, 1e-12, 1e-12, 1e-10, 1e-10, 1e-10]),
               dict(compensated=True)):
        a, b = run_both("plane/chaplygin-ball", {}, None, t, method=method, rtol=1e-10, **kw)
        assert a.success
        assert_follows(a, b)


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


@pytest.mark.parametrize(("case", "params", "state", "t_end", "kw"), EXTREMES)
def test_small_follows_general_kernel_on_the_extremes(case, params, state, t_end, kw):
    a, b = run_both(case, params, state, np.linspace(0.0, t_end, 11), rtol=1e-10, atol=1e-12,
                    **kw)
    if (case, state) == (EXTREMES[1][0], EXTREMES[1][2]):
        # the disk falling flat (s = 1e-6): both stop with SING_EDGE at the same time to
        # round-off (4.12497164397493e-06), but the rejected steps that hunt the edge
        # follow the fields' last bits, which differ there (generate.py writes the disk
        # with its tangent, fields.py with the Hessian): 45 + 55 rejected against 50 + 60
        assert a.status == b.status == L.SING_EDGE
        assert math.isclose(a.t_stop, b.t_stop, rel_tol=1e-12)
        np.testing.assert_allclose(b.y_stop, a.y_stop, rtol=1e-9, atol=1e-12)
        return
    if params.get("k") == 1.0 - 1e-8:
        # the ball that just fits its sphere (1 - kR = 1e-8): there the general field's
        # adjugate solve of E - k J loses digits like cond^2 (2e-2 relative, measured in
        # tests/test_generated.py::test_extremes_agree), the generated field refines once:
        # the trajectories are not the same to round-off, only the outcome is (the step
        # budget runs out: 2959 + 41 attempts against 2993 + 7)
        assert a.status == b.status == rk.MAX_STEPS
        return
    assert_follows(a, b, tol=1e-8)


def test_singular_stops_and_budget():
    """The disk falling through flat stops with SING_EDGE, the ball that barely fits on its
    step budget with MAX_STEPS, each at the same place as the general kernel."""
    a, b = run_both(*EXTREMES[1][:3], np.linspace(0.0, 10.0, 11), rtol=1e-10, atol=1e-12)
    assert a.status == b.status == L.SING_EDGE
    case, params, state, t_end, kw = EXTREMES[4]
    a, b = run_both(case, params, state, np.linspace(0.0, t_end, 11), rtol=1e-10,
                    atol=1e-12, **kw)
    assert a.status == b.status == rk.MAX_STEPS
    a, b = run_both("plane/chaplygin-ball", {}, None, np.linspace(0.0, 30.0, 31), rtol=1e-9,
                    atol=1e-11, max_steps=8)
    assert b.status == rk.MAX_STEPS and b.budget_exhausted
    # where the budget stops is a step's end, and the step sizes follow the fields off the
    # sphere |gamma| = 1 (Hairer's first step probes y + h0 f, where the general field and
    # the generated one, which never assumes |gamma| = 1, differ): 4.27493 against
    # 4.27454. The samples up to there agree; the stop itself is compared bit for bit with
    # the generated integrator (same field) in tests/test_generated_integrator.py
    assert (a.status, a.steps, a.rejected, a.rhs_calls) == \
        (b.status, b.steps, b.rejected, b.rhs_calls)
    np.testing.assert_allclose(b.y, a.y, rtol=1e-9, atol=1e-11)


def test_other_runs_take_the_general_kernel_by_default():
    """The route depends on the request only: projection, sections, clipped or fixed
    steps and other tableaux run rk.py (general field) unless generated=True asks for the
    generated integrator."""
    from solvers.kernels.integrals import ENERGY

    c = registry()["plane/chaplygin-ball"]
    m = build(c.id, c.example)
    t = np.linspace(0.0, 1.0, 3)
    for kw in (dict(project_codes=(ENERGY,)), dict(h_fixed=0.05),
               dict(dense_output=False), dict(method="rk45"),
               dict(section=integrator.Section(coef=(0, 0, 0, 1.0, 0, 0)))):
        r = integrate(m.model, m.p, c.state, t, **kw)
        assert (r.kernel, r.vector_field) == ("rk", "general"), kw


def test_small_kernel_is_scalar_code():
    """State and stages are scalar locals (no work arrays), the field is inlined code of
    the generator, and the tableau's coefficients are literals, passed with their stages
    to the shared combinations (small_ops.ops_source: axpy2 is y + h * (a0 * k0 + a1 * k1))."""
    from solvers.kernels import small

    c = registry()["plane/chaplygin-ball"]
    m = build(c.id, c.example)
    src = open(small.small_kernel(m.model, m.p, "dop853").__file__).read()
    run = src[src.index("def run("):]
    assert "np.empty" not in run and "np.zeros" not in run
    assert "k12_5" in run and "z1_0 = axpy1(y_0, h, 0.05260015195876773, k0_0)" in run
    assert "return y + h * (a0 * k0 + a1 * k1)" in small_ops.ops_source()
    assert generate.numba_source(m.model, m.p).split("v26 = ")[1].split("\n")[0] in src
