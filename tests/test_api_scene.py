"""POST /api/scene (app/api/routes/simulate.py) and the kinematics behind it
(solvers/models/kinematics.py): the body's rotation and contact path for the 3D animation."""

import numpy as np
import pytest
from fastapi.testclient import TestClient

from app.main import create_app
from app.testing import settings_for_tests
from solvers.models.cases import registry, table_case_ids
from solvers.models.kinematics import nearest_rotation, rotation_taking, scene

pytestmark = pytest.mark.filterwarnings("ignore::DeprecationWarning")


@pytest.fixture(scope="module")
def client():
    with TestClient(create_app(settings_for_tests())) as c:
        yield c


def test_scene_route(client):
    r = client.post("/api/scene", json={"case": "plane/chaplygin-ball", "example": True,
                                        "t_end": 10, "frames": 21})
    assert r.status_code == 200, r.text
    d = r.json()
    assert len(d["t"]) == len(d["Q"]) == len(d["x_G"]) == len(d["contact"]) == 21
    assert d["status"] == "ok" and d["support_radius"] is None
    m = d["mesh"]
    assert len(m["faces"]) == len(m["pattern"])
    assert max(max(f) for f in m["faces"]) < len(m["vertices"])
    assert d["checks"]["contact_on_support"] < 1e-7


def test_scene_limits(client):
    r = client.post("/api/scene", json={"case": "plane/chaplygin-ball", "example": True,
                                        "t_end": 10, "frames": 100000})
    assert r.status_code == 422 and "frames" in r.json()["detail"]


@pytest.mark.parametrize("cid", table_case_ids())
def test_rolling_without_sliding_keeps_the_contact_on_the_support(cid):
    """The kinematics integrates only dQ/dt and dx_G/dt; that the contact point stays on
    the plane or sphere (and x_P = Q gamma / k on a sphere) is a consequence, checked."""
    spec = registry()[cid]
    d = scene(cid, spec.example, spec.state, 2.0, frames=11)
    assert d["status"] in ("ok", "singular")
    assert len(d["t"]) >= 2
    assert d["checks"]["orthogonality"] < 1e-6
    assert d["checks"]["contact_on_support"] < 1e-6
    assert d["checks"]["normal_in_space"] < 1e-6
    for Q in d["Q"]:
        Q = np.reshape(Q, (3, 3))
        assert np.allclose(Q.T @ Q, np.eye(3), atol=1e-12) and np.linalg.det(Q) > 0


def test_a_ball_on_the_plane_rolls_the_distance_its_rotation_says():
    """A homogeneous ball spinning about a horizontal axis rolls straight: after time t its
    centre moved R * |omega| * t (a check of the contact condition v_G = -omega x r)."""
    p = {"I1": 0.4, "I2": 0.4 * (1 + 1e-9), "I3": 0.4 * (1 + 2e-9), "m": 1, "R": 1}
    # omega = (1, 0, 0) about a horizontal axis, gamma = (0, 0, 1): M = (I + m R^2) omega
    d = scene("plane/chaplygin-ball", p, [1.4, 0, 0, 0, 0, 1], 3.0, frames=4,
              rtol=1e-11, atol=1e-13)
    x = np.array(d["x_G"])
    assert np.linalg.norm(x[-1, :2] - x[0, :2]) == pytest.approx(3.0, rel=1e-7)
    assert np.allclose(x[:, 2], 1.0)


def test_rotation_helpers():
    rng = np.random.default_rng(0)
    for _ in range(20):
        a, b = rng.normal(size=3), rng.normal(size=3)
        R = rotation_taking(a, b)
        assert np.allclose(R @ a / np.linalg.norm(a), b / np.linalg.norm(b))
        assert np.allclose(R.T @ R, np.eye(3)) and np.linalg.det(R) == pytest.approx(1)
    R = rotation_taking([0, 0, 1], [0, 0, -1])
    assert np.allclose(R @ [0, 0, 1], [0, 0, -1])
    Q = np.eye(3) + 1e-3 * rng.normal(size=(3, 3))
    assert np.allclose(nearest_rotation(Q).T @ nearest_rotation(Q), np.eye(3))
