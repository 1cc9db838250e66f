"""The polynomial ansatz search for rubber integrals (solvers/models/rubber_ansatz.py) finds
what the exact checks prove and no more, and finds the second integral of the ball of twice
the radius of a fixed internal ball (kR = 2) only at that ratio. Numerical null spaces: the
counts are evidence, the exact proofs are in tests/test_rubber_invariants.py."""

import pytest

from solvers.models import rubber_bodies as rb
from solvers.models.rubber_ansatz import count_integrals


@pytest.mark.parametrize("case_id, expected", [
    ("rubber-plane/chaplygin-ball", 2),     # H and |M x gamma|^2
    ("rubber-plane/routh-ball", 2),         # H and (N omega3)^2
    ("rubber-plane/unbalanced-ball", 1),    # H only
    ("rubber-sphere/ball-over", 1),         # H only (kR = -0.5)
])
def test_polynomial_integrals(case_id, expected):
    assert count_integrals(rb.body(case_id), 2, 2)[0] == expected


@pytest.mark.parametrize("k, expected", [(2.0, 2), (3.0, 1), (0.4, 1), (-0.5, 1)])
def test_second_integral_over_Q_only_at_kR_2(k, expected):
    """F = P / Q, P of omega-degree 2 and gamma-degree <= 2: besides H (= H Q / Q) a second
    one exists at kR = 2 and not at the other ratios."""
    b = rb.body("rubber-sphere/ball-over", k=k, I=(1.3, 1.7, 2.6))
    assert count_integrals(b, 2, 2, q_power=-1.0)[0] == expected
