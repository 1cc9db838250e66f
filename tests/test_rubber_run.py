"""Along a run of every rubber case (scipy DOP853, rtol = atol = 1e-12) the constraint
(omega, gamma) = 0, |gamma| = 1 and the energy hold to the integrator's tolerance.

The runs are short (T = 40 time units, 15 for the disk, whose field is stiffer near the
flat position): the plain-NumPy field is too slow for runs of 10^4 time units within the
test budget; those wait for the compiled rubber fields."""

import numpy as np
import pytest
from scipy.integrate import solve_ivp

from solvers.models import rubber_bodies as rb
from solvers.models import rubber_lagrange as rl

TOL = 1e-12
BOUND = 2e-10


@pytest.mark.parametrize("case_id", sorted(rb.CASES))
def test_constraints_and_energy_hold_along_a_run(case_id):
    b = rb.body(case_id)
    T = 15.0 if b.d else 40.0
    y0 = rl.state_on_manifold(b, [0.3, -0.5, 0.7], [0.2, 0.3, 0.9])
    sol = solve_ivp(lambda t, y: rl.field(b, y), (0.0, T), y0, method="DOP853",
                    rtol=TOL, atol=TOL)
    assert sol.status == 0, sol.message
    Y = sol.y.T
    H0 = rl.energy(b, y0)
    spin = max(abs(rl.spin(b, y)) for y in Y)
    unit = float(np.max(np.abs(np.linalg.norm(Y[:, 3:], axis=1) - 1.0)))
    drift = max(abs(rl.energy(b, y) - H0) for y in Y) / abs(H0)
    assert spin < BOUND and unit < BOUND and drift < BOUND, (spin, unit, drift)
    # the run moved: the state is not an equilibrium
    assert np.max(np.abs(Y[-1] - Y[0])) > 1e-2
