"""integrate(generated=True): the rk kernel compiled against the generated field follows
the general kernel's trajectory (same tableau, same controller, fields equal to
round-off), with the same step counts, on a ball, a disk and a flat base."""

import numpy as np
import pytest

from solvers.integrate.integrator import integrate
from solvers.models.cases import build, registry


@pytest.mark.parametrize("case", ["plane/chaplygin-ball", "sphere/flat-base"])
def test_generated_kernel_follows_general_kernel(case):
    c = registry()[case]
    model = build(case, c.example)
    t = np.linspace(0.0, 20.0, 21)
    a = integrate(model.model, model.p, c.state, t, rtol=1e-10, atol=1e-12)
    b = integrate(model.model, model.p, c.state, t, rtol=1e-10, atol=1e-12, generated=True)
    assert a.success and b.success
    assert abs(a.steps - b.steps) <= 2
    scale = float(np.max(np.abs(a.y)))
    assert float(np.max(np.abs(a.y - b.y))) < 1e-9 * scale
