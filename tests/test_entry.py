"""The thin entry (issue 12, item 3): memoized validation, models, output times, option
vectors and generated-kernel lookups must never change a result; and the generated
field, the default where it is compiled, agrees with the general field on every case."""

import numpy as np
import pytest

from solvers import compile_state
from solvers.errors import InputError
from solvers.integrate import integrator as I
from solvers.models.cases import build, case_ids, registry
from solvers.simulate import simulate

BALL = "plane/chaplygin-ball"


def _ball(**over):
    c = registry()[BALL]
    return {**c.example, **over}, list(c.state)


def test_different_params_give_different_runs_and_repeat_exactly():
    params, state = _ball()
    a = simulate(BALL, params, state, 5.0, samples=11)
    b = simulate(BALL, _ball(I3=2.5)[0], state, 5.0, samples=11)
    a2 = simulate(BALL, params, state, 5.0, samples=11)
    assert a.params["I3"] == 3.0 and b.params["I3"] == 2.5
    assert not np.allclose(a.state[-1], b.state[-1])
    np.testing.assert_array_equal(a.state, a2.state)   # the memo changed nothing
    np.testing.assert_array_equal(a.invariants["energy"], a2.invariants["energy"])


def test_different_case_method_samples_and_tolerance_are_not_confused():
    params, state = _ball()
    base = simulate(BALL, params, state, 5.0, samples=11)
    other = simulate("sphere/borisov-fedorov", registry()["sphere/borisov-fedorov"].example,
                     state, 5.0, samples=11)
    assert "borisov_fedorov" in other.invariants and "borisov_fedorov" not in base.invariants
    vern = simulate(BALL, params, state, 5.0, samples=11, method="vern9")
    assert vern.stats["method"] == "vern9" and vern.stats["steps"] != base.stats["steps"]
    many = simulate(BALL, params, state, 5.0, samples=21)
    assert many.t.shape == (21,) and many.state.shape == (21, 6)
    np.testing.assert_allclose(many.state[::2], base.state, rtol=0, atol=1e-9)
    loose = simulate(BALL, params, state, 5.0, samples=11, rtol=1e-5, atol=1e-7)
    assert loose.stats["steps"] < base.stats["steps"] and loose.stats["rtol"] == 1e-5
    longer = simulate(BALL, params, state, 6.0, samples=11)
    assert longer.t[-1] == 6.0


def test_results_are_not_aliased_to_memoized_or_reused_buffers():
    params, state = _ball()
    a = simulate(BALL, params, state, 5.0, samples=11)
    ref = simulate(BALL, params, state, 5.0, samples=11)
    # the caller scribbles over everything it was given
    a.t[:] = -1.0
    a.state[:] = np.nan
    for v in a.invariants.values():
        v[:] = 7.0
    a.params["I1"] = 99.0
    a.stats["drift"]["energy"] = 1.0
    params["I1"] = 42.0          # and over its own input, after the run
    state[0] = 3.0
    b = simulate(BALL, _ball()[0], _ball()[1], 5.0, samples=11)
    np.testing.assert_array_equal(b.t, ref.t)
    np.testing.assert_array_equal(b.state, ref.state)
    for k in ref.invariants:
        np.testing.assert_array_equal(b.invariants[k], ref.invariants[k])
    assert b.params == ref.params and b.stats["drift"] == ref.stats["drift"]


def test_integrate_outputs_are_fresh_and_option_vectors_not_shared():
    m = build(BALL, registry()[BALL].example)
    y0 = registry()[BALL].state
    t = I.output_times(3.0, 7)
    with pytest.raises(ValueError):
        t[0] = 1.0                       # the trusted times are read-only
    a = I.integrate(m.model, m.p, y0, t)
    a.y[:] = 0.0
    a.t[:] = 0.0
    b = I.integrate(m.model, m.p, y0, t)
    assert b.t[-1] == 3.0 and np.all(np.isfinite(b.y)) and np.any(b.y != 0.0)
    tight = I.integrate(m.model, m.p, y0, t, rtol=1e-12, atol=1e-14)
    again = I.integrate(m.model, m.p, y0, t)
    assert tight.steps > again.steps and again.steps == b.steps
    np.testing.assert_array_equal(again.y, b.y)
    # an untrusted array equal to the trusted one is checked and gives the same run
    c = I.integrate(m.model, m.p, y0, np.linspace(0.0, 3.0, 7))
    np.testing.assert_array_equal(c.y, b.y)
    with pytest.raises(ValueError):
        I.integrate(m.model, m.p, y0, [0.0, 2.0, 1.0])
    with pytest.raises(ValueError):
        I.integrate(m.model, m.p, y0, [0.0, np.nan, 1.0])


def test_short_time_lists_and_parameter_forms_give_the_same_run():
    """The plain entry's shortcuts (a short list of floats checked before any array, p's
    own bytes as the plan's key, the plan's private copy of p run by the kernel) give the
    run of the same values in any other form, refuse what the general check refuses, and
    never keep a caller's array: a parameter vector changed in place is a new run."""
    m = build(BALL, registry()[BALL].example)
    y0 = np.array(registry()[BALL].state)
    p = np.array(m.p, dtype=np.float64)
    ref = I.integrate(m.model, p, y0, np.array([0.0, 2.0]))
    for t in ([0.0, 2.0], [0, 2], (0.0, 2.0), [np.float64(0.0), 2.0], [0.0, 1.0, 2.0][::2]):
        r = I.integrate(m.model, p, y0, t)
        np.testing.assert_array_equal(r.t, ref.t)
        np.testing.assert_array_equal(r.y, ref.y)
    for q in (list(p), tuple(p), np.repeat(p, 2)[::2], p.astype(">f8"), p.reshape(1, -1)):
        np.testing.assert_array_equal(I.integrate(m.model, q, y0, [0.0, 2.0]).y, ref.y)
    for bad in ([], [0.0, np.nan], [np.nan], [0.0, np.inf], [-np.inf, 0.0], [1.0, 1.0],
                [0.0, 2.0, 1.0], [0.0, "x"]):
        with pytest.raises(ValueError):
            I.integrate(m.model, p, y0, bad)
    q, kw = p.copy(), {"rtol": 1e-9, "atol": 1e-9}
    before = I.integrate(m.model, q, y0, [0.0, 2.0], **kw)    # a plan made from q
    q[0] *= 1.5                          # I1 changed in place after the run
    again = I.integrate(m.model, p.copy(), y0, [0.0, 2.0], **kw)   # that plan, not q
    np.testing.assert_array_equal(again.y, before.y)
    assert not np.array_equal(I.integrate(m.model, q, y0, [0.0, 2.0], **kw).y, before.y)


def test_bad_input_is_never_memoized():
    params, state = _ball()
    with pytest.raises(InputError, match="I1"):
        simulate(BALL, {**params, "I1": -1.0}, state, 1.0)
    with pytest.raises(InputError, match="I1"):   # the same bad input fails again
        simulate(BALL, {**params, "I1": -1.0}, state, 1.0)
    with pytest.raises(InputError, match="samples"):
        simulate(BALL, params, state, 1.0, samples=2.0)
    simulate(BALL, params, state, 1.0, samples=2)  # valid, memoized...
    with pytest.raises(InputError, match="samples"):   # ...2.0 is still refused
        simulate(BALL, params, state, 1.0, samples=2.0)
    with pytest.raises(InputError, match="gamma"):
        simulate(BALL, params, [*state[:3], 1.0, 1.0, 1.0], 1.0)
    with pytest.raises(InputError, match="field"):
        simulate(BALL, params, state, 1.0, field="lean")
    with pytest.raises(InputError, match="field"):
        simulate(BALL, params, state, 1.0, field="generated", method="gauss4", step=0.1)


def test_auto_field_runs_the_small_kernel():
    """field='auto' on a plain run: the small kernel of the structure (the generated
    field), whatever is compiled; stats say which field and which kernel ran."""
    params, state = _ball()
    gen = simulate(BALL, params, state, 1.0, samples=3, field="generated")
    assert (gen.stats["field"], gen.stats["kernel"]) == ("generated", "small")
    auto = simulate(BALL, params, state, 1.0, samples=3)
    assert (auto.stats["field"], auto.stats["kernel"]) == ("generated", "small")
    assert auto.state.tobytes() == gen.state.tobytes()
    ref = simulate(BALL, params, state, 1.0, samples=3, field="general")
    assert (ref.stats["field"], ref.stats["kernel"]) == ("general", "rk")
    assert simulate(BALL, params, state, 1.0, samples=3,
                    method="scipy-dop853").stats["field"] == "numpy"
    proj = simulate(BALL, params, state, 1.0, samples=3, project=True)
    assert (proj.stats["field"], proj.stats["kernel"]) == ("general", "rk")


def test_auto_on_a_new_structure_is_the_same_answer():
    """A structure outside the warm-up (the ball with gyrostat, gravity and Brun terms all
    on) runs its small kernel under field='auto' too (issue 19: the route depends on the
    request, not on the cache; the pinned rule before was "the general field until someone
    compiles it", whose numbers changed once it was compiled): the same bits as
    field='generated', and the big generated integrator is not compiled by them."""
    params, state = _ball(S1=1e-3, S2=2e-3, S3=3e-3, g=0.5, eps=0.1)
    m = build(BALL, params)
    key = compile_state.generated_key(m.model, m.p)
    had = compile_state.is_compiled(key)
    r = simulate(BALL, params, state, 1.0, samples=3)
    assert (r.stats["field"], r.stats["kernel"]) == ("generated", "small") and r.ok
    g = simulate(BALL, params, state, 1.0, samples=3, field="generated")
    assert r.state.tobytes() == g.state.tobytes()
    assert compile_state.is_compiled(key) == had


@pytest.mark.parametrize("case", case_ids())
def test_generated_default_equals_general_field(case):
    """Through simulate(): the generated field (what field='auto' runs once compiled)
    follows the general field's trajectory to round-off, with the same invariants."""
    c = registry()[case]
    gen = simulate(case, c.example, c.state, 5.0, samples=11, field="generated")
    ref = simulate(case, c.example, c.state, 5.0, samples=11, field="general")
    assert gen.stats["field"] == "generated" and ref.stats["field"] == "general"
    assert gen.status == ref.status == "ok"
    assert abs(gen.stats["steps"] - ref.stats["steps"]) <= 2
    scale = max(1.0, float(np.max(np.abs(ref.state))))
    assert float(np.max(np.abs(gen.state - ref.state))) < 1e-9 * scale
    for k in ref.invariants:
        np.testing.assert_allclose(gen.invariants[k], ref.invariants[k], rtol=1e-9,
                                   atol=1e-9)
