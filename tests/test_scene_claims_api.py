"""GET /api/scenes/{id}/checks/{k}: every teaching scene's check with the plot of the data
its verdict was taken from (solvers/scenes/scene_checks.py). The verdict passes, and the
plotted claim series gives back the check's measured value: the plot /scenes draws is the
check, not a second run."""

import math

import numpy as np
import pytest

from solvers.scenes.teaching import load_scenes

SCENES = load_scenes()
CASES = [(sid, k) for sid, s in SCENES.items() for k in range(len(s.checks))]


def _claim(plot):
    return [tr for tr in plot["traces"] if tr["role"] == "claim"]


def _values(tr):
    return np.array([np.nan if v is None else v for v in tr["y"]], dtype=float)


@pytest.mark.filterwarnings("ignore::DeprecationWarning")
@pytest.mark.parametrize("sid, k", CASES)
def test_every_check_passes_and_its_plot_is_its_data(patient_client, sid, k):
    r = patient_client.get(f"/api/scenes/{sid}/checks/{k}")
    assert r.status_code == 200, r.text
    d = r.json()
    check = SCENES[sid].checks[k]
    assert d["kind"] == check.kind and d["index"] == k and d["count"] == len(SCENES[sid].checks)
    assert d["passed"], d["detail"]
    assert d["caption"] == check.caption and len(d["caption"]) >= 40
    p = d["plot"]
    claim = _claim(p)
    assert claim and p["title"] and p["x_title"] and p["y_title"]
    if check.kind == "integrals":
        # one series per claimed integral; its largest relative change is the value
        assert [tr["quantity"] for tr in claim] == list(check.names)
        worst = max(np.nanmax(_values(tr)) for tr in claim)
        assert worst == d["value"] <= check.tol
        assert p["log_y"]
        contrast = [tr for tr in p["traces"] if tr["role"] == "contrast"]
        # the quantity that does change is many orders of magnitude above the integrals
        assert all(np.nanmax(_values(tr)) > 1e4 * check.tol for tr in contrast)
    elif check.kind == "conserved":
        # the integrals themselves on linear axes; the verdict is read off these values
        assert [tr["quantity"] for tr in claim] == list(check.names)
        assert not p["log_y"]
        worst = max(np.nanmax(np.abs(_values(tr)[1:] - _values(tr)[0]))
                    / max(abs(_values(tr)[0]), 1.0) for tr in claim)
        assert worst == d["value"] <= check.tol
        contrast = [tr for tr in p["traces"] if tr["role"] == "contrast"]
        assert all(np.ptp(_values(tr)) > 1e4 * check.tol for tr in contrast)
    elif check.kind == "stays_up":
        tilt = _values(claim[0])
        assert math.isclose(math.cos(math.radians(tilt.max())), d["value"], rel_tol=1e-12)
        assert tilt.max() < 90 - 60          # far from lying flat (90 degrees)
        assert 5 < tilt[0] < 20              # "tilted by about 11 degrees"
    elif check.kind == "spin_reversal":
        from solvers.models.observables import spin_reversals

        raw = next(tr for tr in p["traces"] if tr["role"] == "raw")
        times = spin_reversals(raw["x"], _values(raw), check.window)
        assert times[0] == d["value"] <= check.before
        avg = _values(claim[0])
        assert avg[0] > 0 > avg[-1] or avg[0] < 0 < avg[-1]   # it changed sign
    elif check.kind == "no_spin":
        # (omega, gamma) of both bodies: the rubber one's (beside) is the value, at zero;
        # the marble one's leaves zero
        run = {tr["run"]: tr for tr in p["traces"]}
        assert run["beside"]["role"] == "claim"
        assert np.nanmax(np.abs(_values(run["beside"]))) == d["value"] <= check.tol
        assert np.nanmax(np.abs(_values(run["main"]))) >= check.marble_min
        assert _values(run["main"])[0] == pytest.approx(0.0, abs=1e-12)   # the same start
    elif check.expect == "condenses":
        y = _values(claim[0])
        ratio = np.median(y[:100]) / np.median(y[-100:])
        assert math.isclose(ratio, d["value"], rel_tol=1e-12) and ratio >= check.factor
    else:
        from solvers.maps.map_analysis import correlation_dimension

        tr = claim[0]
        assert len(tr["x"]) == check.points
        P = np.c_[tr["y"], tr["hg"], tr["x"]]          # (L/G, H/G, l) as the map returns
        assert correlation_dimension(P, 0.01, 0.1) == d["value"]
        assert abs(d["value"] - 1.0) <= check.dim_tol
        assert claim[0]["mode"] == "markers"
    # every plot says where the animation's time cursor goes: on the time axis, or along
    # data that carries its own times within the scene's run
    cur = p["cursor"]
    if cur["axis"] != "t":
        ts = np.array(cur["t"], dtype=float)
        assert len(ts) == len(cur["x"]) > 1 and np.all(np.diff(ts) > 0) and ts[0] >= 0
    else:
        assert p["x_title"] == "time t"
    # the second request is the same answer (kept per server process)
    assert patient_client.get(f"/api/scenes/{sid}/checks/{k}").content == r.content


@pytest.mark.filterwarnings("ignore::DeprecationWarning")
def test_unknown_scene_or_check_is_404(patient_client):
    assert patient_client.get("/api/scenes/nope/checks/0").status_code == 404
    r = patient_client.get("/api/scenes/routh-ball-jellett-routh/checks/5")
    assert r.status_code == 404 and "checks 0" in r.json()["detail"]
