"""POST /api/poincare?stream=true for a class (issue 20): an estimate from a real pilot
before the map starts, then progress after every trajectory that returns (not per round),
each with the time left; the same map as without the stream."""

import json

import pytest

BODY = {"case": "plane/chaplygin-ball", "example": True, "energy": 1.0, "section": "g=0",
        "trajectories": 5, "points": 60, "rtol": 1e-8}


@pytest.mark.filterwarnings("ignore::DeprecationWarning")
def test_estimate_then_progress_on_every_trajectory(patient_client):
    r = patient_client.post("/api/poincare?stream=true", json=BODY)
    assert r.status_code == 200, r.text
    events = [json.loads(x) for x in r.text.strip().splitlines()]
    # the kernels are warm here (./dev test's warm-up, Settings.kernels_warm), and the
    # warm-up covers maps (tests/test_warm_covers_requests.py): nothing to compile first
    assert events[0]["event"] == "estimate" and events[0]["total"] == 5
    assert 0 < events[0]["seconds"] < 60
    progress = [e for e in events if e["event"] == "progress"]
    assert [e["done"] for e in progress] == [0, 1, 2, 3, 4, 5]
    assert all(e["remaining"] >= 0 for e in progress[1:]) and progress[-1]["remaining"] == 0
    assert events[-1]["event"] == "result"
    res = events[-1]["result"]
    assert res["rtol"] == 1e-8 and [len(t["points"]) for t in res["trajectories"]] == [60] * 5
    plain = patient_client.post("/api/poincare", json=BODY).json()
    assert [t["points"] for t in plain["trajectories"]] == [t["points"]
                                                            for t in res["trajectories"]]


@pytest.mark.filterwarnings("ignore::DeprecationWarning")
def test_a_bad_rtol_names_the_field(patient_client):
    r = patient_client.post("/api/poincare?stream=true", json={**BODY, "rtol": 0.5})
    assert r.status_code == 422 and "rtol" in r.text
