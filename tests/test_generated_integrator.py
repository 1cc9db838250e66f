"""integrate(generated=True) and everything else that runs rk.py compiled against a case's
generated field (solvers/kernels/field_modules.py generated_integrator, and its ensemble twin).
These are the project's biggest kernels (~32 s a structure to compile on 2 cores), which
no default route runs: they are all tested here, in one module, so that under
pytest-xdist (--dist loadfile) each compiles once per test session instead of once in
every module that needs it (issue 19, CI time).

  * the kernels follow the general kernel's trajectory (same tableau, same controller,
    fields equal to round-off), with the same step counts: rk.py's generated integrator
    (kernel="rk") on a ball, the small kernel a plain run takes by default on a ball and a
    flat base;
  * the small kernel gives the generated integrator's bits (tests/test_small.py's rule);
  * integrate(generated=True) and the ensemble twin run the same module, and the twin
    gives the generated integrator's bits one by one."""

import numpy as np
import pytest

from solvers.integrate import integrator
from solvers.integrate.ensemble import integrate_ensemble
from solvers.integrate.integrator import Section, integrate
from solvers.kernels import field_modules, generate
from solvers.kernels.rk import CROSSINGS_DONE, MAX_STEPS
from solvers.models.cases import build, registry
from tests.test_ensemble import _case, _same


# rk.py's generated integrator on the ball only: it is rk.py's code bound to the field
# (test_integrate_and_the_ensemble_twin_run_one_module), and every case's
# generated field is checked against the general one (tests/test_generated.py), so a
# second structure (the flat base's 5-dimensional state) cost a ~37 s compile in CI for a
# combination of two parts checked each on its own; the flat base's small kernel stays
# (issue 19, CI time)
@pytest.mark.parametrize(("case", "kernel"), [("plane/chaplygin-ball", "rk"),
                                              ("plane/chaplygin-ball", None),
                                              ("sphere/flat-base", None)])
def test_generated_kernel_follows_general_kernel(case, kernel):
    c = registry()[case]
    model = build(case, c.example)
    t = np.linspace(0.0, 20.0, 21)
    a = integrate(model.model, model.p, c.state, t, rtol=1e-10, atol=1e-12, generated=False)
    b = integrate(model.model, model.p, c.state, t, rtol=1e-10, atol=1e-12, generated=True,
                  kernel=kernel)
    assert (b.vector_field, b.kernel) == ("generated", kernel or "small")
    assert a.success and b.success
    assert abs(a.steps - b.steps) <= 2
    scale = float(np.max(np.abs(a.y)))
    assert float(np.max(np.abs(a.y - b.y))) < 1e-9 * scale


def test_same_bits_as_the_generated_integrator():
    """The small kernel and rk.py's generated integrator (its tableau loops) on the
    same generated field: the same bits, samples inside steps included. Both through
    integrate(), so the generated integrator runs the specialization integrate() compiles
    (a direct call with the model's read-only p compiled a second one: ~100 s)."""
    c = registry()["plane/chaplygin-ball"]
    m = build(c.id, c.example)
    t = np.linspace(0.0, 50.0, 101)
    control = integrator.StepControl(h0=0.01, h_max=0.5)
    atol_v = [1e-12, 1e-12, 1e-12, 1e-10, 1e-10, 1e-10]
    for method, comp, budget, more in (
            ("dop853", False, 10**7, {}), ("vern9", False, 10**7, {}),
            ("dop853", True, 10**7, {}), ("vern9", True, 10**7, {}),
            ("dop853", False, 8, {}),
            # a given first step and a maximal step, a vector atol (tests/test_small.py)
            ("vern9", False, 10**7, {"control": control}),
            ("dop853", False, 10**7, {"control": control}),
            ("vern9", False, 10**7, {"atol": atol_v})):
        kw = dict(method=method, rtol=1e-10, atol=1e-12, compensated=comp, max_steps=budget)
        kw.update(more)
        big = integrate(m.model, m.p, c.state, t, generated=True, kernel="rk", **kw)
        r = integrate(m.model, m.p, c.state, t, **kw)
        assert (big.kernel, big.vector_field) == ("rk", "generated")
        assert (r.kernel, r.vector_field) == ("small", "generated")
        assert (big.status, big.steps, big.rejected, big.rhs_calls) == \
            (r.status, r.steps, r.rejected, r.rhs_calls)
        assert big.t_stop == r.t_stop
        np.testing.assert_array_equal(big.y, r.y)
        np.testing.assert_array_equal(big.y_stop, r.y_stop)


def test_integrate_and_the_ensemble_twin_run_one_module():
    """What integrate(generated=True) runs on a case: the loop kernel and rk.py's own
    functions (the same code objects' bytecode: its tableau loops) bound to the case's
    generated field, the same module whose rk_integrate the ensemble twin calls; the twin
    is ensemble.py's loop, bound the same way. No source text is read to make them."""
    from solvers.integrate import ensemble
    from solvers.kernels import bind, loop_kernel, rk
    from solvers.kernels import ensemble as ens_kernels

    c = registry()["plane/chaplygin-ball"]
    m = build(c.id, c.example)
    p = np.asarray(m.p, dtype=np.float64)
    mod = integrator.generated_module(m.model, p)
    assert mod is field_modules.generated_integrator(m.model, p)
    field = field_modules.generated(m.model, p)
    assert mod.rhs is field.rhs and rk.rhs is not field.rhs
    own = {**bind.jitted(rk), **bind.jitted(loop_kernel.loop_module())}
    assert "rk_integrate" in own and "stages" in own
    for name, disp in own.items():
        bound = getattr(mod, name)
        assert bound is not disp
        assert bound.py_func.__code__.co_code == disp.py_func.__code__.co_code
        assert bound.py_func.__globals__ is vars(mod)
        assert bound.py_func.__code__.co_filename == mod.__file__
    twin = ensemble.generated_ensemble(m.model, p)
    assert twin.rk_integrate is mod.rk_integrate
    assert twin.rk_ensemble.py_func.__code__.co_code == \
        ens_kernels.rk_ensemble.py_func.__code__.co_code
    assert twin.rk_ensemble.targetoptions.get("parallel") is True


def test_no_module_edits_source_text():
    """No module of solvers/ reads a Python file's text to edit it (str.replace on what
    read_text() or read() returned): kernels are bound (solvers/kernels/bind.py) or
    generated from their own descriptions."""
    import ast
    from pathlib import Path

    root = Path(generate.__file__).resolve().parents[1]
    def read(node) -> bool:     # x.read_text() or x.read()
        return (isinstance(node, ast.Call) and isinstance(node.func, ast.Attribute)
                and node.func.attr in ("read_text", "read"))

    found = []
    for f in sorted(root.rglob("*.py")):
        tree = ast.parse(f.read_text())
        texts = {t.id for node in ast.walk(tree) if isinstance(node, ast.Assign)
                 and read(node.value) for t in node.targets if isinstance(t, ast.Name)}
        for node in ast.walk(tree):
            if (isinstance(node, ast.Call) and isinstance(node.func, ast.Attribute)
                    and node.func.attr == "replace"):
                recv = node.func.value
                if read(recv) or (isinstance(recv, ast.Name) and recv.id in texts):
                    found.append(f"{f.relative_to(root)}:{node.lineno}")
    assert not found, found


def test_generated_ensemble_equals_generated_one_by_one():
    m, Y0 = _case("plane/chaplygin-ball")
    t_out = np.linspace(0.0, 30.0, 7)
    sec = Section(coef=(0, 0, 0, 1.0, 0, 0))
    ens = integrate_ensemble(m.model, m.p, Y0, t_out, generated=True, section=sec,
                             max_crossings=5)
    for y0, r in zip(Y0, ens, strict=True):
        _same(integrate(m.model, m.p, y0, t_out, generated=True, section=sec,
                        max_crossings=5), r)
        assert len(r.crossings_t) > 0
    # and the generated field is another kernel: same trajectory to the tolerance only
    gen = integrate_ensemble(m.model, m.p, Y0, t_out, generated=False)
    assert all(np.allclose(a.y, b.y, rtol=0, atol=1e-6) for a, b in
               zip(ens, gen, strict=True))


def test_small_kernel_with_sections_takes_the_generated_integrators_steps():
    """The small kernel with sections (integrate(kernel="small") with a section: a large
    Poincare map's runs) against rk.py's generated integrator on the same field: the same
    steps, rejections, field calls, status and samples, bit for bit (its step is rk.py's,
    the step control near the Andoyer section and the halving of grazing steps included);
    the crossings, which rk.py's own Henon and Newton code locates on the general field
    (one compile for every structure), agree to a few units of round-off. Both sections:
    the map's g = g0 in Andoyer-Deprit variables, one way, and a plane gamma_1 = 0.2 both
    ways; a plane gamma_1 = 0.8722176 that the trajectory grazes (its gamma_1 peaks at
    0.87221864: steps there are halved until their ends read the section right, 4 more
    rejected steps than without the section); and a run stopped by its number of
    crossings."""
    from solvers.maps.poincare import MapSpec, starts_for

    c = registry()["plane/chaplygin-ball"]
    m = build(c.id, c.example)
    spec = MapSpec(energy=1.0)
    eps = np.finfo(float).eps
    runs = [(y0, spec.section(), 60) for y0 in starts_for(m, spec, trajectories=2)]
    graze = Section(coef=(0, 0, 0, 1.0, 0, 0), offset=0.8722176, direction=0)
    runs += [(c.state, Section(coef=(0, 0, 0, 1.0, 0, 0), offset=0.2, direction=0), 25),
             (c.state, graze, 1000), (c.state, spec.section(), 3)]
    for y0, sec, n_cross in runs:
        t = np.linspace(0.0, 300.0, 3001)
        big = integrate(m.model, m.p, y0, t, generated=True, kernel="rk", section=sec,
                        max_crossings=n_cross)
        r = integrate(m.model, m.p, y0, t, kernel="small", section=sec,
                      max_crossings=n_cross)
        assert (big.kernel, r.kernel, r.vector_field) == ("rk", "small-sections", "generated")
        assert (big.status, big.steps, big.rejected, big.rhs_calls, big.t_stop) == \
            (r.status, r.steps, r.rejected, r.rhs_calls, r.t_stop), (big.message, r.message)
        np.testing.assert_array_equal(big.y, r.y)
        np.testing.assert_array_equal(big.y_stop, r.y_stop)
        assert len(r.crossings_t) == len(big.crossings_t) >= 2
        assert np.all(np.abs(r.crossings_t - big.crossings_t)
                      <= 16 * eps * np.maximum(1.0, np.abs(big.crossings_t)))
        assert np.max(np.abs(r.crossings_y - big.crossings_y)) <= \
            16 * eps * max(1.0, float(np.max(np.abs(big.crossings_y))))
        if sec is graze:
            plain = integrate(m.model, m.p, y0, t)
            assert r.rejected > plain.rejected + 2, (r.rejected, plain.rejected)
    assert big.status == CROSSINGS_DONE and len(big.crossings_t) == 3


def test_small_kernel_with_projection_takes_the_generated_integrators_steps():
    """The small kernel with projection (integrate(kernel="small") with project_codes)
    against rk.py's generated integrator on the same field: the same bits everywhere
    (rk.py's own projection onto the levels, every project_every-th accepted step, the
    field again at the projected point, the interpolated and the step-end samples
    projected too), compensated sums and a step budget included."""
    from solvers.kernels.integrals import ENERGY, NAMES

    c = registry()["plane/chaplygin-ball"]
    m = build(c.id, c.example)
    t = np.linspace(0.0, 40.0, 81)
    codes = [ENERGY, NAMES.index("gamma2"), NAMES.index("area")]   # E, |gamma|^2, M.gamma
    for every, comp, budget in ((1, False, 10**7), (3, False, 10**7), (2, True, 10**7),
                                (1, False, 40)):
        kw = dict(project_codes=codes, project_every=every, compensated=comp,
                  max_steps=budget, rtol=1e-9, atol=1e-11)
        big = integrate(m.model, m.p, c.state, t, generated=True, kernel="rk", **kw)
        r = integrate(m.model, m.p, c.state, t, kernel="small", **kw)
        assert (big.kernel, r.kernel, r.vector_field) == ("rk", "small-projection",
                                                           "generated")
        assert (big.status, big.steps, big.rejected, big.rhs_calls, big.t_stop) == \
            (r.status, r.steps, r.rejected, r.rhs_calls, r.t_stop), (big.message, r.message)
        np.testing.assert_array_equal(big.y, r.y)
        np.testing.assert_array_equal(big.y_stop, r.y_stop)
    assert not big.success and big.status == MAX_STEPS
