"""The quantity a teaching scene promises, plotted beside its animation: the scene
response's `series` (solvers/models/kinematics.py) and the preset's `plot`
(catalogue/scenes.yaml). Checked against the scene's own check on the same run."""

import numpy as np

from solvers.models.cases import build
from solvers.models.kinematics import scene
from solvers.models.observables import spin_reversals, vertical_spin
from solvers.scenes.teaching import load_scenes


def _run(sid):
    s = load_scenes()[sid]
    sc = s.scene
    return s, scene(sc.case, sc.params, sc.state, sc.t_end, frames=sc.samples)


def test_the_rattleback_plots_its_spin_and_it_reverses():
    s, d = _run("rattleback-spin-reversal")
    assert s.plot == "vertical_spin"
    spin = np.asarray(d["series"]["vertical_spin"])
    assert len(spin) == len(d["t"])
    check = next(c for c in s.checks if c.kind == "spin_reversal")
    times = spin_reversals(d["t"], spin, check.window)
    assert times and times[0] <= check.before      # what the text promises, on the plot
    # the series is the observable of the frames' states (not a separate run): at t = 0
    # it is the initial spin of the preset
    model = build(s.scene.case, s.scene.params)
    assert abs(spin[0] - vertical_spin(model, np.asarray(s.scene.state))[0]) < 1e-12


def test_the_disk_plots_its_tilt_and_stays_up():
    s, d = _run("rolling-disk-stays-up")
    assert s.plot == "tilt"
    tilt = np.asarray(d["series"]["tilt"])
    g = np.asarray(s.scene.state[3:6])
    assert abs(tilt[0] - np.hypot(g[0], g[1])) < 1e-12
    check = next(c for c in s.checks if c.kind == "stays_up")
    assert tilt.min() >= check.min_tilt


def test_every_plotted_series_exists_in_the_scene():
    for sid, s in load_scenes().items():
        if s.plot:
            _, d = _run(sid)
            assert s.plot in d["series"], sid
