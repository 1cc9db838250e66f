"""The generated per-case fields (solvers/kernels/generate.py) against the general field
(solvers/kernels/fields.py) and the independent NumPy field (solvers/models/reference.py):
the same numbers to round-off at random phase points, on and off |gamma| = 1, the same
complex-step derivatives, the same singular statuses, on all cases, with and without the
potentials, with parameters read at run time and folded into the code, and at the
extremes of tests/test_extremes.py."""

import math

import numpy as np
import pytest
from conftest import random_states

from solvers.kernels import layout as L
from solvers.kernels.field_modules import generated
from solvers.kernels.fields import rhs
from solvers.kernels.generate import SLOT_NAMES, equations, numba_source
from solvers.kernels.heyoka_field import heyoka_system
from solvers.models.cases import build, registry
from solvers.models.reference import field as ref_field

TOL = 1e-14        # max-norm difference relative to the max-norm of the field
H = 1e-30          # complex step


def with_potentials(case_id):
    """Example parameters with gravity, Brun field, gyrostat and offsets switched on."""
    c = registry()[case_id]
    extra = {"g": 0.7, "eps": 0.3, "S1": 0.2, "S2": -0.1, "S3": 0.25, "a1": 0.05,
             "a2": -0.07, "c": 0.2}
    return {**c.example, **{k: v for k, v in extra.items() if k in c.param_names}}


def general(model, y):
    d = np.zeros(len(y), dtype=y.dtype)
    return d, rhs(model.model, 0.0, y, np.asarray(model.p), d)


def gen_field(mod, model, y):
    """The generated field at y: compiled for a double state (what the kernels inline); for
    a complex state (the complex-step Jacobian) the same source run by Python
    (`py_func`), since no kernel runs the generated field on complex numbers: compiling
    that specialization took ~4 s per structure, 64 structures here (issue 19's CI time)."""
    d = np.zeros(len(y), dtype=y.dtype)
    field = mod.field.py_func if np.iscomplexobj(y) else mod.field
    return d, field(np.asarray(model.p), y, d)


def rel(a, b):
    return float(np.max(np.abs(a - b)) / max(np.max(np.abs(b)), 1e-300))


def points(model, rng, n=16):
    """Random states near the demo state; for (M, gamma) also off the unit sphere (the
    generated field must not assume |gamma| = 1)."""
    out = random_states(model, n, rng, 0.4)
    if model.model == L.MODEL_FULL:
        for y in list(out[: n // 2]):
            z = y.copy()
            z[3:] *= rng.uniform(0.9, 1.1)
            out.append(z)
    return out


def exact(model, y, digits=50):
    """The generator's equations evaluated in `digits`-digit arithmetic at the double
    inputs: the round-off-free value every double implementation is measured against."""
    import sympy as sp

    prog, state, params, outs, _ = equations(model.model, model.p)
    env = {s: sp.Float(float(model.p[SLOT_NAMES.index(s.name)]), digits) for s in params}
    env.update({s: sp.Float(float(v), digits) for s, v in zip(state, y, strict=True)})
    for sym, ex in prog.assign:
        env[sym] = ex.xreplace(env).evalf(digits)
    return np.array([float(sp.sympify(o).xreplace(env).evalf(digits)) for o in outs])


def check_model(model, rng, fold, n_exact=3):
    """Worst relative errors over random points: generated, general and reference fields
    against the exact value (n_exact points), generated vs general (all points), and the
    complex-step Jacobian columns of generated vs general."""
    mod = generated(model.model, model.p, fold)
    worst = {"gen-general": 0.0, "gen": 0.0, "general": 0.0, "ref": 0.0, "cs": 0.0}
    for i, y in enumerate(points(model, rng)):
        d, st = general(model, y)
        e, st_gen = gen_field(mod, model, y)
        assert st_gen == st
        if st != L.OK:
            continue
        worst["gen-general"] = max(worst["gen-general"], rel(e, d))
        if i < n_exact:
            x = exact(model, y)
            eg, ed = rel(e, x), rel(d, x)
            # never less accurate than the general field, and at 1e-14 where it is
            assert eg <= max(TOL, ed), (eg, ed)
            worst["gen"] = max(worst["gen"], eg)
            worst["general"] = max(worst["general"], ed)
            if model.model == L.MODEL_FLAT or abs(np.linalg.norm(y[3:]) - 1.0) < 1e-12:
                worst["ref"] = max(worst["ref"], rel(ref_field(model.model, model.p, y), x))
        # complex step: every column of the Jacobian, generated vs general
        for j in range(len(y)):
            yc = y.astype(complex)
            yc[j] += 1j * H
            dc, _ = general(model, yc)
            ec, stc = gen_field(mod, model, yc)
            assert stc == L.OK
            assert np.array_equal(ec.real, e)        # the real part is the float field
            col_g, col_e = dc.imag / H, ec.imag / H
            if np.max(np.abs(col_g)) > 0:
                worst["cs"] = max(worst["cs"], rel(col_e, col_g))
    return worst


@pytest.mark.parametrize("fold", [False, True])
@pytest.mark.parametrize("potentials", [False, True])
def test_generated_field_equals_general_and_reference(case_id, potentials, fold):
    """The exact value of the equations agrees with the two independent double fields
    (so the generated equations are the paper's), and the generated double code is within
    round-off of it: 1e-14 relative, or the general field's own error where the case's
    conditioning puts that higher (the rattleback: ~2.5e-14 general, ~5e-14 NumPy)."""
    c = registry()[case_id]
    model = build(case_id, with_potentials(case_id) if potentials else c.example)
    w = check_model(model, np.random.default_rng(7), fold)
    assert w["general"] < 1e-13, w
    assert w["ref"] < 1e-13, w
    assert w["gen-general"] < 1e-13, w
    assert w["cs"] < 1e-12, w


def test_zero_terms_are_dropped():
    """The Chaplygin ball has no gravity, Brun, gyrostat or curvature term and no 3x3 solve
    for dgamma/dt; its generated code reads only I, m and R."""
    c = registry()["plane/chaplygin-ball"]
    model = build(c.id, c.example)
    src = numba_source(model.model, model.p)
    for slot in ("p[4]", "p[5]", "p[8]", "p[9]", "p[17]", "p[18]"):
        assert slot not in src
    assert src.count("1.0/(") < 8
    folded = numba_source(model.model, model.p, fold=True)
    assert "p[" not in folded.split("def rhs")[0]


def test_ball_needs_no_hessian_and_no_solve():
    """A ball's support c |gamma| (+ (a, gamma)) has J = lam (E - gamma gamma^T / |gamma|^2):
    the generator writes J dgamma/dt = lam dgamma/dt and solves (E - k J) dgamma/dt =
    gamma x omega by one division. The centred Chaplygin ball: I_Q = D - (m c^2 /
    |gamma|^2) gamma gamma^T, D = diag(I_i + m c^2), solved by Sherman-Morrison: on the
    plane no square root and five divisions, two that depend on the state (1/|gamma|^2
    and 1/q) and three on the parameters only (1/D_i, the same at every stage); in a
    sphere one square root (lam) and one division more (1/(1 - k lam)), where the
    general 3x3 solve with refinement took a dozen; with an offset centre (the
    unbalanced ball) r = lam gamma + a needs lam."""
    def src(case, **kw):
        c = registry()[case]
        m = build(case, {**c.example, **kw})
        return numba_source(m.model, m.p).split("def rhs")[0]

    plane = src("plane/chaplygin-ball")
    assert "np.sqrt" not in plane and plane.count("1.0/(") == 5
    assert plane.count("(I1 + (m*(c*c)))") == 1    # D_1, once
    sphere = src("sphere/chaplygin-ball")
    assert sphere.count("np.sqrt") == 1 and sphere.count("1.0/(") == 6
    assert src("plane/unbalanced-ball").count("np.sqrt") == 1
    # the disk: the flat-disk check and gravity's d/s; none on the way to omega
    disk = src("plane/round-disk")
    assert disk.count("np.sqrt") == 2 and disk.count("1.0/(") == 2


@pytest.mark.parametrize(("case", "params", "state"), [
    ("plane/round-disk", {}, [0.0, 0.3, 3.0, 1e-4, 0.0, math.sqrt(1 - 1e-8)]),
    ("plane/round-disk", {}, [0.0, 0.3, 3.0, 1e-9, 0.0, 1.0]),          # flat: SING_EDGE
    ("plane/round-disk", {}, [10.0, 0.0, 5e3, math.cos(1e-3), 0.0, math.sin(1e-3)]),
    ("sphere/chaplygin-ball", {"k": 1.0 - 1e-6}, None),
    ("sphere/chaplygin-ball", {"k": 1.0 - 1e-8}, None),
    ("sphere/chaplygin-ball", {"k": 2.0}, None),    # does not fit (refused at the input)
    ("plane/chaplygin-ball", {"I2": 1.0 + 1e-12, "I3": 1.5}, None),
    ("plane/chaplygin-ball", {"I1": 1e-6, "I2": 2e-6, "I3": 2.5e-6}, None),
    ("plane/chaplygin-ball", {"I1": 1e6, "I2": 2e6, "I3": 2.5e6}, None),
    ("plane/chaplygin-ball", {}, [0.5e4, -0.3e4, 0.8e4, 0.3, 0.4, 0.8660254037844386]),
])
def test_extremes_agree(case, params, state):
    """Same status as the general field; at least as accurate against the exact value.
    Near the fit limit (1 - kR = 1e-6, 1e-8) E - k J is nearly singular: the general
    field's adjugate solve loses digits like cond^2 (5e-8 and 2e-2 relative, measured);
    the generated one refines once and stays at cond * eps (like numpy.linalg.solve)."""
    c = registry()[case]
    model = build(case, {**c.example, **params})
    y = np.array(state if state is not None else c.state, dtype=float)
    d, st = general(model, y)
    x = exact(model, y) if st == L.OK else None
    for fold in (False, True):
        e, st_gen = gen_field(generated(model.model, model.p, fold), model, y)
        assert st_gen == st
        if st == L.OK:
            assert rel(e, x) <= max(TOL, rel(d, x)), (rel(e, x), rel(d, x))


def test_heyoka_lean_system_matches(case_id):
    """The heyoka expressions from the same generator evaluate to the general field."""
    hy = pytest.importorskip("heyoka")
    model = build(case_id, with_potentials(case_id))
    for fold in (True, False):
        vars_, rhs_, pars = heyoka_system(model.model, model.p, fold)
        cf = hy.cfunc(rhs_, vars=vars_)
        for y in random_states(model, 5, np.random.default_rng(3), 0.3):
            d, _ = general(model, y)
            e = cf(y, pars=pars) if not fold else cf(y)
            assert rel(e, d) < 1e-13
