"""A run's options as a typed record (solvers/integrate/options.py): checked when made, packed
into rk.py's option vectors by its index names, and what integrate() hands the kernel."""

import numpy as np
import pytest

from solvers.integrate import integrator
from solvers.integrate.options import Projection, RunOptions, Section, StepControl, fopt
from solvers.kernels import rk


def test_packed_by_the_kernels_index_names():
    control = StepControl(safety=0.8, fac_min=0.3, fac_max=5.0, beta=0.0, h0=1e-3,
                          h_max=2.0)
    opts = RunOptions(method="vern9", rtol=1e-8, control=control, compensated=True,
                      section=Section(coef=(0, 0, 1.0), offset=0.5, direction=-3),
                      max_crossings=7, projection=Projection(codes=(0, 1), every=4),
                      max_steps=123)
    iopt, fo = opts.packed()
    assert iopt[rk.I_MAX_STEPS] == 123
    assert iopt[rk.I_COMPENSATED] == 1
    assert iopt[rk.I_PROJECT_EVERY] == 4
    assert iopt[rk.I_SECTION] == rk.SECTION_LINEAR
    assert iopt[rk.I_DIRECTION] == -1
    assert iopt[rk.I_MAX_CROSS] == 7
    assert iopt[rk.I_FIXED] == 0
    assert fo[rk.F_RTOL] == 1e-8 and fo[rk.F_H] == 1e-3 and fo[rk.F_HMAX] == 2.0
    assert (fo[rk.F_SAFETY], fo[rk.F_FACMIN], fo[rk.F_FACMAX], fo[rk.F_BETA]) == \
        (0.8, 0.3, 5.0, 0.0)
    assert len(iopt) == 7 and len(fo) == 7
    # a fixed step is the first (and every) step; no section: one crossing slot, none used
    fixed = RunOptions(h_fixed=0.25, control=control)
    iopt, fo = fixed.packed()
    assert iopt[rk.I_FIXED] == 1 and fo[rk.F_H] == 0.25
    assert iopt[rk.I_SECTION] == rk.SECTION_NONE and iopt[rk.I_MAX_CROSS] == 1
    assert fixed.crossings == 1
    # the plain entry's float vector is the same packing
    assert fopt(1e-8, control) == opts.packed()[1]


def test_atol_vector():
    assert np.array_equal(RunOptions(atol=1e-9).atol_vector(3), np.full(3, 1e-9))
    assert np.array_equal(RunOptions(atol=(1e-9, 1e-8, 1e-7)).atol_vector(3),
                          [1e-9, 1e-8, 1e-7])


@pytest.mark.parametrize("kw", [dict(h_fixed=0.0), dict(h_fixed=-1.0),
                                dict(h_fixed=float("nan"))])
def test_bad_step_is_refused(kw):
    with pytest.raises(ValueError, match="h_fixed must be positive"):
        RunOptions(**kw)


@pytest.mark.parametrize("kw", [dict(codes=(0,), values=(1.0, 2.0)),
                                dict(codes=(0,), every=0)])
def test_bad_projection_is_refused(kw):
    with pytest.raises(ValueError, match="one project_value per code"):
        Projection(**kw)


def test_integrate_hands_the_record_to_the_compiled_call(monkeypatch):
    """integrate()'s keywords become one RunOptions, which run_options packs at the call."""
    seen = []

    def spy(model, p, y0, t_out, opts, *, generated=None, kernel=None):
        seen.append((opts, generated, kernel))
        return "ran"

    monkeypatch.setattr(integrator, "run_options", spy)
    from solvers.kernels import layout as L

    p = np.zeros(L.N_PARAMS)
    out = integrator.integrate(L.MODEL_TEST_OSC, p, [1.0, 0.0], [0.0, 1.0], method="rk45",
                               rtol=1e-7, atol=1e-9, project_codes=(rk.TEST_ENERGY,),
                               project_every=2, generated=False, kernel="rk")
    assert out == "ran"
    opts, generated, kernel = seen[0]
    assert (generated, kernel) == (False, "rk")
    assert opts.method == "rk45" and opts.rtol == 1e-7 and opts.atol == 1e-9
    assert opts.projection == Projection(codes=(rk.TEST_ENERGY,), values=(0.5,), every=2)
    assert opts.section is None and not opts.fixed
