"""The compiled ensemble (solvers/integrate/ensemble.py, solvers/kernels/ensemble.py): many
initial states in one parallel call give, trajectory by trajectory, exactly (bit for bit)
what `integrate` gives one at a time, statuses and budgets per trajectory, and refuse bad
input before anything runs. Speed is in bench/ensemble.py, not here."""

import threading

import numpy as np
import pytest

from solvers.integrate import ensemble as E
from solvers.integrate.batch import integrate_batch, integrate_threads
from solvers.integrate.ensemble import integrate_ensemble
from solvers.integrate.integrator import Section, integrate
from solvers.kernels import layout as L
from solvers.kernels import loop_kernel, rk
from solvers.kernels.integrals import ENERGY
from solvers.models.cases import build, registry


def _case(case_id, n=5, seed=0, scale=0.1):
    c = registry()[case_id]
    m = build(case_id, c.example)
    rng = np.random.default_rng(seed)
    Y0 = []
    for _ in range(n):
        y = np.array(c.state, dtype=float)
        y[:3] += scale * rng.standard_normal(3)
        Y0.append(y)
    return m, np.array(Y0)


def _same(a, b):
    """Bit for bit: the same kernel on the same inputs."""
    assert a.status == b.status and a.message == b.message
    assert a.steps == b.steps and a.rejected == b.rejected and a.rhs_calls == b.rhs_calls
    assert a.t_stop == b.t_stop
    assert np.array_equal(a.t, b.t) and np.array_equal(a.y, b.y)
    assert np.array_equal(a.y_stop, b.y_stop)
    assert np.array_equal(a.crossings_t, b.crossings_t)
    assert np.array_equal(a.crossings_y, b.crossings_y)


CASES = [
    ("plane/chaplygin-ball", {}),
    ("sphere/chaplygin-ball", {"method": "vern9", "rtol": 1e-9, "atol": 1e-11}),
    ("plane/round-disk", {"method": "rk45", "rtol": 1e-7, "atol": 1e-9}),
    ("sphere/flat-base", {"dense_output": False}),
    ("plane/rattleback", {"project_codes": (ENERGY,), "project_every": 3}),
    ("plane/chaplygin-ball", {"section": Section(coef=(0, 0, 0, 1.0, 0, 0)),
                              "max_crossings": 7}),
    ("sphere/chaplygin-ball", {"section": Section(coef=(0, 0, 0, 1.0, 0, 0), direction=0),
                               "compensated": True}),
]


@pytest.mark.parametrize(("case_id", "opts"), CASES, ids=[f"{c}-{i}" for i, (c, _) in
                                                          enumerate(CASES)])
def test_ensemble_equals_one_by_one(case_id, opts):
    m, Y0 = _case(case_id)
    t_out = np.linspace(0.0, 30.0, 13)
    ens = integrate_ensemble(m.model, m.p, Y0, t_out, workers=2, generated=False, **opts)
    assert len(ens) == len(Y0)
    for y0, r in zip(Y0, ens, strict=True):
        _same(integrate(m.model, m.p, y0, t_out, generated=False, **opts), r)
    if "section" in opts:
        assert all(len(r.crossings_t) > 0 for r in ens)


def test_workers_do_not_change_the_numbers():
    m, Y0 = _case("sphere/chaplygin-ball", n=7, seed=3)
    t_out = np.linspace(0.0, 20.0, 5)
    one = integrate_ensemble(m.model, m.p, Y0, t_out, workers=1, generated=False)
    two = integrate_ensemble(m.model, m.p, Y0, t_out, workers=2, generated=False)
    for a, b in zip(one, two, strict=True):
        _same(a, b)


def test_one_row_of_output_times_runs_the_loop_kernel_integrate_runs():
    """A single row of output times becomes a C-ordered table, so the serial path hands the
    loop kernel C-contiguous rows: the specialization integrate() and the warm-up compile,
    not another one (numpy's copy of a broadcast row is F-ordered)."""
    m, Y0 = _case("sphere/chaplygin-ball", n=3, seed=5)
    integrate_ensemble(m.model, m.p, Y0, np.linspace(0.0, 2.0, 5), workers=1,
                       generated=False)
    integrate(m.model, m.p, Y0[0], [0.0, 1.0], generated=False, kernel="rk")
    assert [sig[3].layout for sig in loop_kernel.rk_integrate.signatures] == ["C"]


def test_one_singular_trajectory_does_not_spoil_the_others():
    m, Y0 = _case("plane/chaplygin-ball", n=4)
    Y0[1, 0] = np.nan                       # the field is not finite there
    t_out = [0.0, 10.0, 20.0]
    ens = integrate_ensemble(m.model, m.p, Y0, t_out, generated=False)
    assert ens[1].status == L.SING_NONFINITE and not ens[1].success
    assert ens[1].t_stop == 0.0 and len(ens[1].t) == 1
    for i in (0, 2, 3):
        assert ens[i].success and len(ens[i].t) == 3
        _same(integrate(m.model, m.p, Y0[i], t_out, generated=False), ens[i])


def test_round_disk_falling_flat_stops_alone():
    m, Y0 = _case("plane/round-disk", n=3)
    flat = Y0[0].copy()
    flat[3:] = [0.0, 0.0, 1.0]              # gamma along the axis: the disk lies flat
    Y0 = np.vstack([Y0, flat])
    ens = integrate_ensemble(m.model, m.p, Y0, [0.0, 5.0], generated=False)
    assert ens[-1].status == L.SING_EDGE
    assert all(r.success for r in ens[:-1])


def test_max_steps_per_trajectory():
    m, Y0 = _case("plane/chaplygin-ball", n=3)
    t_out = [0.0, 200.0]
    budget = [15, 10_000_000, 40]
    ens = integrate_ensemble(m.model, m.p, Y0, t_out, max_steps=budget, generated=False)
    assert [r.status for r in ens] == [rk.MAX_STEPS, L.OK, rk.MAX_STEPS]
    assert ens[0].budget_exhausted and ens[0].steps + ens[0].rejected == 15
    for y0, r, b in zip(Y0, ens, budget, strict=True):
        _same(integrate(m.model, m.p, y0, t_out, max_steps=b, generated=False), r)


def test_ragged_output_times_and_h_max_per_trajectory():
    m, Y0 = _case("sphere/chaplygin-ball", n=3)
    rows = [np.linspace(0.0, 10.0, 6), np.linspace(1.0, 4.0, 3), np.array([2.0, 9.0])]
    T = np.full((3, 6), -1.0)               # the padding is never read
    for i, r in enumerate(rows):
        T[i, :len(r)] = r
    h_max = [np.inf, 0.05, 0.3]
    ens = integrate_ensemble(m.model, m.p, Y0, T, n_out=[len(r) for r in rows],
                             h_max=h_max, generated=False)
    from solvers.integrate.integrator import StepControl

    for y0, r, t, h in zip(Y0, ens, rows, h_max, strict=True):
        _same(integrate(m.model, m.p, y0, t, control=StepControl(h_max=h),
                        generated=False), r)


def test_empty_and_one_row():
    m, Y0 = _case("plane/chaplygin-ball", n=1)
    assert integrate_ensemble(m.model, m.p, np.empty((0, 6)), [0.0, 1.0]) == []
    (r,) = integrate_ensemble(m.model, m.p, Y0[0], [0.0, 1.0, 2.0], generated=False)
    _same(integrate(m.model, m.p, Y0[0], [0.0, 1.0, 2.0], generated=False), r)
    (r,) = integrate_ensemble(m.model, m.p, Y0, [0.0], generated=False)   # t0 only
    assert r.success and len(r.t) == 1 and np.array_equal(r.y[0], Y0[0])


BAD = [
    ({"Y0": np.zeros((2, 5))}, "dimension 6"),
    ({"t_out": [0.0, 2.0, 1.0]}, "strictly increasing"),
    ({"t_out": [0.0, np.nan]}, "strictly increasing"),
    ({"t_out": []}, "at least one time"),
    ({"t_out": np.zeros((3, 2))}, "one per trajectory"),
    ({"method": "euler"}, "unknown method"),
    ({"method": "gauss8"}, "collocation"),
    ({"max_steps": [1, 2, 3]}, "max_steps"),
    ({"h_max": -1.0}, "h_max > 0"),
    ({"rtol": -1e-9}, "rtol"),
    ({"atol": [1e-12, 1e-12]}, "atol"),
    ({"workers": 0}, "workers"),
    ({"h_fixed": -0.1}, "h_fixed"),
    ({"project_codes": (ENERGY,), "project_values": [1.0, 2.0]}, "project_values"),
    ({"n_out": [1, 9]}, "at least one time"),
]


@pytest.mark.parametrize(("bad", "words"), BAD, ids=[w for _, w in BAD])
def test_bad_input_is_refused_before_anything_runs(monkeypatch, bad, words):
    m, Y0 = _case("plane/chaplygin-ball", n=2)

    def never(*a, **k):
        raise AssertionError("the kernel ran on bad input")

    monkeypatch.setattr(E.kernels, "rk_ensemble", never)
    monkeypatch.setattr(E, "generated_ensemble", never)
    args = {"Y0": Y0, "t_out": [0.0, 1.0], **bad}
    y, t = args.pop("Y0"), args.pop("t_out")
    with pytest.raises(ValueError, match=words):
        integrate_ensemble(m.model, m.p, y, t, **args)


def test_two_python_threads_at_once():
    m, Y0 = _case("plane/chaplygin-ball", n=6, seed=5)
    m2, Z0 = _case("sphere/chaplygin-ball", n=6, seed=6)
    t_out = np.linspace(0.0, 40.0, 9)
    want = ([integrate(m.model, m.p, y, t_out, generated=False) for y in Y0],
            [integrate(m2.model, m2.p, z, t_out, generated=False) for z in Z0])
    got: dict = {}
    go = threading.Barrier(4)

    def run(key, mm, Y):
        go.wait()
        for k in range(3):
            got[key, k] = integrate_ensemble(mm.model, mm.p, Y, t_out, generated=False)

    threads = [threading.Thread(target=run, args=(key, mm, Y)) for key, mm, Y in
               (("a", m, Y0), ("b", m2, Z0), ("c", m, Y0), ("d", m2, Z0))]
    for th in threads:
        th.start()
    for th in threads:
        th.join()
    for key, ref in (("a", want[0]), ("b", want[1]), ("c", want[0]), ("d", want[1])):
        for k in range(3):
            for a, b in zip(ref, got[key, k], strict=True):
                _same(a, b)


def test_batch_api_runs_the_ensemble_and_the_thread_pool_agrees():
    m, Y0 = _case("sphere/chaplygin-ball", n=4)
    t_out = [0.0, 5.0, 10.0]
    a = integrate_batch(m.model, m.p, Y0, t_out, workers=2, generated=False)
    b = integrate_threads(m.model, m.p, Y0, t_out, workers=2, generated=False)
    for x, y in zip(a, b, strict=True):
        _same(x, y)
    g = integrate_batch(m.model, m.p, Y0, t_out, method="gauss4", h_fixed=0.05)
    assert all(r.success and r.method == "gauss4" for r in g)


def test_threading_layer_is_named():
    assert E.threading_layer() in ("workqueue", "omp", "tbb")


def test_poincare_map_in_lockstep_equals_one_by_one(monkeypatch):
    """The map's trajectories run together (one ensemble call per round, a pilot then
    chunks, some finishing early) give what trace_checked gives one at a time."""
    from solvers.maps.poincare import (
        MapSpec,
        map_model,
        starts_for,
        trace_checked,
        trace_checked_all,
    )

    c = registry()["plane/chaplygin-ball"]
    model = map_model("plane/chaplygin-ball", c.example)
    spec = MapSpec(energy=1.0, points=40, max_steps=6000)
    starts = starts_for(model, spec, trajectories=4, seed=2)
    calls = []
    together = trace_checked_all(model, starts, spec, progress=lambda d, n: calls.append(d))
    assert calls[-1] == 4 and calls == sorted(calls)
    for y0, a in zip(starts, together, strict=True):
        b = trace_checked(model, y0, spec)
        assert a.status == b.status and a.message == b.message and a.check == b.check
        assert a.steps == b.steps and a.rhs_calls == b.rhs_calls
        assert np.array_equal(a.t, b.t) and np.array_equal(a.states, b.states)
    assert all(len(tr.t) == 40 for tr in together if tr.status == "ok")
    # a round cut into several calls (the memory cap) gives the same map
    from solvers.maps import poincare as pc

    monkeypatch.setattr(pc, "ROUND_BYTES", 3 * 2000 * 6 * 8)
    cut = trace_checked_all(model, starts, spec)
    for a, b in zip(together, cut, strict=True):
        assert np.array_equal(a.states, b.states) and a.check == b.check
