"""integrate(generated=True): the kernels compiled against the generated field follow the
general kernel's trajectory (same tableau, same controller, fields equal to round-off),
with the same step counts, on a ball and a flat base: rk.py's generated integrator
(kernel="rk") and the small kernel a plain run takes by default (issue 19)."""

import numpy as np
import pytest

from solvers.integrate.integrator import integrate
from solvers.models.cases import build, registry


@pytest.mark.parametrize("kernel", ["rk", None])
@pytest.mark.parametrize("case", ["plane/chaplygin-ball", "sphere/flat-base"])
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
