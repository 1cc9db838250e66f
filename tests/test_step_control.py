"""The step written once: its loop in the template (solvers/kernels/step.py), its control in
control.py.

The loop kernel (loop_kernel.py's text from the template, with rk.py's stages and starting
step) and the small kernels (small.py's text from the same template) call the same
functions for what the step decides (the starting step, the step's length, the error
norm, the controllers, the compensated sums, the section's crossing test), and neither
writes those lines itself: their texts hold the calls and none of the controller's own
expressions, which control.py holds once. The loop's own lines (the budget, the
rejections, the accepted step, the samples, the commit) are the template's: written in
step.py and in no backend. That the
kernels give the same bits as before is tests/test_generated_integrator.py's and
tests/test_small.py's (and scripts/same_bytes.py's); here the functions' own behaviour
is checked, compiled as the kernels run them."""

import inspect
import math

import numpy as np
import pytest

from solvers.integrate import integrator  # noqa: F401 (provides the tableaux to baked.py)
from solvers.kernels import baked, control, gauss, loop_kernel, rk, small, step
from solvers.models.cases import build, registry

# expressions of the step control: each must be in control.py once, and in no kernel
CONTROL_LINES = (
    "0.01 * d0 / d1",                       # Hairer's first trial step
    "h1 = max(1e-6, h0 * 1e-3)",            # ... and the starting step
    "min(h0 * 1e-3, hmax)",                 # ... at a singular trial point
    "t + 1.01 * h >= target",               # landing on the target time
    "16.0 * EPS * abs(t)",                  # step size underflow
    "0.01 * e2",                            # Hairer's DOP853 error norm
    "err_old ** beta",                      # the PI controller
    "min(1.0, max(facmin, fac))",           # the step after a rejection
    "(h + t_comp) - (t_new - t)",           # the compensated time
    "d - (yn - y)",                         # Kahan's compensation
    "s_old < 0.0 <= s_new",                 # the section's crossing test
    "GRAZE_H * max(1.0, abs(t))",           # the grazing rule
)
CALLED_BY_BOTH = ("first_guess(", "first_step(", "first_step_singular(", "clip_step(",
                  "shrink(", "grow(", "advance(", "step_end(", "time_compensation(")


def _small_texts():
    c = registry()["plane/chaplygin-ball"]
    m = build(c.id, c.example)
    tabs = baked.baked_tableaux(("dop853", "vern9"))
    return {(method, kind): small.kernel_source(m.model, m.p, method, tabs[method],
                                                sections=kind == "sections",
                                                projection=kind == "projection")
            for method in ("dop853", "vern9") for kind in ("plain", "sections", "projection")}


def test_the_step_control_is_written_once():
    ctl = inspect.getsource(control)
    for line in CONTROL_LINES:
        assert ctl.count(line) == 1, line
    loop = loop_kernel.source() + inspect.getsource(rk)
    kernels = {"loop kernel": loop, "gauss.py": inspect.getsource(gauss),
               **{f"small {k}": v for k, v in _small_texts().items()}}
    for name, text in kernels.items():
        for line in CONTROL_LINES:
            assert line not in text, (name, line)
    for name, text in kernels.items():
        if name == "gauss.py":
            assert "advance(" in text and "finish(" in text
            continue
        for call in CALLED_BY_BOTH:
            assert call in text, (name, call)
        assert "error_norm(" in text or "error_sums(" in text, name
    for kind in ("sections",):
        for method in ("dop853", "vern9"):
            text = _small_texts()[(method, kind)]
            assert "crosses(" in text and "halve(" in text
    assert "crosses(" in kernels["loop kernel"] and "halve(" in kernels["loop kernel"]


# lines of the loop itself: each in the template, and in no backend's source
LOOP_LINES = (
    "attempts += 1",                                        # the step budget
    "h, h_proposed, landing, ok = clip_step(h, hmax, t, ",  # the step's length
    "h = 0.25 * h",                                         # a singular stage
    "h = shrink(h, err, ",                                  # a failed error test
    "h = 0.5 * h",                                          # a misread section
    "t_comp = time_compensation(t, h, t_comp, t_new, landing, compensated)",
    "while j < N and t_out[j] <= t_new:",                   # the samples in the step
    "x = 2.0 * (t_out[j] - t) / h - 1.0",                   # the dense output's abscissa
    "extra_done = True",                                    # the dense stages, once
)


def test_the_loop_is_written_once_in_the_template():
    template = inspect.getsource(step)
    backends = {m.__name__: inspect.getsource(m) for m in (loop_kernel, small, rk)}
    generated = {"loop kernel": loop_kernel.source(),
                 **{f"small {k}": v for k, v in _small_texts().items()}}
    for line in LOOP_LINES:
        assert template.count(line) == 1, line
        for name, text in backends.items():
            assert line not in text, (name, line)
        for name, text in generated.items():
            if line == "h = 0.5 * h" and name.startswith("small") and "sections" not in name:
                continue        # a small kernel without sections has no halving
            assert line in text, (name, line)


def test_clip_step_lands_caps_and_detects_underflow():
    h, hp, landing, ok = control.clip_step(0.995, 10.0, 0.0, 1.0)
    assert (h, hp, landing, ok) == (1.0, 0.995, True, True)    # within 1 %: stretched
    h, hp, landing, ok = control.clip_step(0.5, 0.25, 0.0, 1.0)
    assert (h, hp, landing, ok) == (0.25, 0.25, False, True)   # hmax
    h, hp, landing, ok = control.clip_step(1e-12, 1.0, 1e6, 2e6)
    assert not landing and not ok                             # below 16 ulp(t)
    h, hp, landing, ok = control.clip_step(1e-8, 1.0, 1e6, 2e6)
    assert not landing and ok


def test_the_controllers_clamp_the_factor():
    # after a rejection: never longer, at most facmin shorter, facmin for a NaN error
    assert control.shrink(1.0, 1e30, -0.125, 0.9, 0.2) == 0.2
    assert control.shrink(1.0, np.nan, -0.125, 0.9, 0.2) == 0.2
    assert control.shrink(1.0, 1.0000001, -0.125, 0.9, 0.2) == pytest.approx(0.9)
    # after an accepted step: facmax for a zero error, not growing after a rejection
    h, err_old = control.grow(1.0, 0.0, 1e-4, 0.1, 0.04, 0.9, 0.333, 6.0, False, False, 1.0)
    assert (h, err_old) == (6.0, 1e-4)
    h, _ = control.grow(1.0, 0.0, 1e-4, 0.1, 0.04, 0.9, 0.333, 6.0, True, False, 1.0)
    assert h == 1.0
    h, err_old = control.grow(1.0, 0.5, 0.3, 0.1, 0.04, 0.9, 0.333, 6.0, False, False, 1.0)
    assert h == pytest.approx(0.9 * 0.5 ** -0.1 * 0.3 ** 0.04) and err_old == 0.5
    # a step cut to land on an output time keeps the step proposed before the cut
    h, _ = control.grow(0.01, 0.9, 0.3, 0.1, 0.04, 0.9, 0.333, 6.0, False, True, 0.5)
    assert h == 0.5


def test_starting_step_follows_hairer():
    # tiny norms: h0 = 1e-6; max(d1, d2) tiny: h1 = max(1e-6, 1e-3 h0)
    h0, d1 = control.first_guess(1e-12, 1e-40, 4, 10.0)
    assert h0 == 1e-6 and d1 == pytest.approx(5e-21)
    assert control.first_step(h0, d1, 0.0, 4, 1 / 9, 10.0, 1.0) == 1e-6
    # a norm above 1e-15: h1 = (0.01 / max(d1, d2))^(1/(order+1)), here above 100 h0
    h0, d1 = control.first_guess(1e-12, 1e-12, 4, 10.0)
    assert control.first_step(h0, d1, 0.0, 4, 1 / 9, 10.0, 1.0) == 100 * 1e-6
    # h0 = 0.01 d0/d1, capped by the span; the step by 100 h0, the span and hmax
    h0, d1 = control.first_guess(4.0, 16.0, 4, 10.0)
    assert h0 == pytest.approx(0.005) and d1 == 2.0
    h = control.first_step(h0, d1, 4.0 * (0.005 ** 2), 4, 1 / 9, 10.0, 1.0)
    assert h == pytest.approx(min(100 * 0.005, (0.01 / 2.0) ** (1 / 9)))
    assert control.first_step_singular(0.5, 1e-4) == 1e-4


def test_error_norm_embedded_and_dop853():
    assert control.error_norm(4.0, 0.0, -0.5, 4, control.ERR_EMBEDDED) == 0.5
    assert control.error_norm(0.0, 0.0, 0.5, 4, control.ERR_DOP853) == 0.0
    e = control.error_norm(4.0, 100.0, 0.5, 4, control.ERR_DOP853)
    assert e == pytest.approx(0.5 * 4.0 / math.sqrt((4.0 + 1.0) * 4))


def test_compensated_sum_keeps_the_round_off():
    y, c = 1.0, 0.0
    plain = 1.0
    for _ in range(10):
        y, c = control.advance(y, 1e-16, c, True)
        plain, _ = control.advance(plain, 1e-16, 0.0, False)
    assert plain == 1.0                   # each 1e-16 is lost without compensation
    assert abs(y - (1.0 + 1e-15)) <= 2.3e-16    # Kahan: within an ulp of the sum
    assert control.step_end(1.0, 0.5, 1e-17, 2.0, True, True) == 2.0
    t_new = control.step_end(1.0, 0.5, 0.0, 2.0, False, True)
    assert control.time_compensation(1.0, 0.5, 0.0, t_new, False, True) == 0.0
    assert control.time_compensation(1.0, 0.5, 1e-3, 1.5, True, True) == 0.0


def test_section_crossing_and_grazing_rule():
    assert control.crosses(-1.0, 0.0, 1) and not control.crosses(-1.0, 0.0, -1)
    assert control.crosses(1.0, -1.0, -1) and control.crosses(1.0, 0.0, 0)
    assert not control.crosses(1.0, 2.0, 0)
    assert control.halve(2, 1e-3, 1.0) and not control.halve(1, 1e-3, 1.0)
    assert not control.halve(2, 1e-10, 1.0)     # below GRAZE_H |t|: left unresolved


def test_finish_writes_the_stop_state():
    y, ys = np.array([1.0, 2.0]), np.zeros(2)
    assert control.finish(y, ys, control.MAX_STEPS, 3.5) == (control.MAX_STEPS, 3.5)
    assert list(ys) == [1.0, 2.0]
