"""Chaplygin ball on the plane, T = 1000: our compiled RK kernels vs scipy's solve_ivp.

Problem: MODEL_FULL with I = (1, 2, 3), m = 1, ball radius R = 1 (BALL_C), k = 0, a
generic state with |gamma| = 1. Every run samples the same 1001 output times. Errors are
max-norm over the samples against a tight reference: our vern9 at rtol 1e-14, accepted
only if scipy's DOP853 at rtol 1e-13 agrees with it (their difference is printed).
scipy runs on `numpy_field` below: a plain NumPy right-hand side of the same equations
(no numba), as a user of solve_ivp would write it. Ours: best of `REPEATS` in one process
(compilation or cache loading excluded, and reported on its own line).

    .venv/bin/python bench/chaplygin_vs_scipy.py   # writes bench/results/chaplygin_vs_scipy.txt
"""

import time
from pathlib import Path

import numpy as np
from scipy.integrate import solve_ivp

from solvers.integrate.integrator import integrate
from solvers.kernels import layout as L

T_END, RTOL, REPEATS = 1000.0, 1e-10, 5
OUT = Path(__file__).with_name("results") / "chaplygin_vs_scipy.txt"


def parameters():
    p = np.zeros(L.N_PARAMS)
    p[L.I1:L.I3 + 1] = (1.0, 2.0, 3.0)
    p[L.MASS] = 1.0
    p[L.BALL_C] = 1.0
    return p


def initial_state():
    g = np.array([0.3, -0.5, 0.8])
    return np.r_[0.7, -0.4, 1.1, g / np.linalg.norm(g)]


def numpy_field(p):
    """dy/dt of the ball on the plane (CONVENTIONS.md, eq1.1-eq1.2, S = 0, U = 0):
    r = R gamma/|gamma|, I_Q = I + m (r^2 E - r r^T), omega = I_Q^-1 M,
    dgamma/dt = gamma x omega, dr/dt = J dgamma/dt, dM/dt = M x omega + m dr/dt x (omega x r).
    """
    inertia = np.diag(p[L.I1:L.I3 + 1])
    m, R = p[L.MASS], p[L.BALL_C]

    def f(t, y):
        M, g = y[:3], y[3:]
        n = np.linalg.norm(g)
        r = R * g / n
        J = R * (np.eye(3) / n - np.outer(g, g) / n**3)
        IQ = inertia + m * (r @ r * np.eye(3) - np.outer(r, r))
        w = np.linalg.solve(IQ, M)
        gd = np.cross(g, w)
        rd = J @ gd
        return np.r_[np.cross(M, w) + m * np.cross(rd, np.cross(w, r)), gd]

    return f


def scipy_run(p, y0, t, rtol, atol):
    f = numpy_field(p)
    t0 = time.perf_counter()
    sol = solve_ivp(f, (t[0], t[-1]), y0, method="DOP853", t_eval=t, rtol=rtol, atol=atol)
    wall = time.perf_counter() - t0
    assert sol.success, sol.message
    return sol.y.T, wall, sol.nfev


def ours(p, y0, t, method, rtol, atol):
    best = None
    for _ in range(REPEATS):
        r = integrate(L.MODEL_FULL, p, y0, t, method=method, rtol=rtol, atol=atol)
        assert r.success, r.message
        best = r if best is None or r.wall_s < best.wall_s else best
    return best


def main():
    p, y0 = parameters(), initial_state()
    t = np.linspace(0.0, T_END, 1001)
    lines = []

    def say(s=""):
        print(s)
        lines.append(s)

    t0 = time.perf_counter()
    integrate(L.MODEL_FULL, p, y0, t[:2])
    say(f"first call in this process (compile or load from numba's cache): "
        f"{time.perf_counter() - t0:.2f} s")

    ref = integrate(L.MODEL_FULL, p, y0, t, method="vern9", rtol=1e-14, atol=1e-16).y
    ref_sp, _, _ = scipy_run(p, y0, t, 1e-13, 1e-15)
    say(f"reference: our vern9 rtol 1e-14 vs scipy DOP853 rtol 1e-13: max difference "
        f"{np.abs(ref - ref_sp).max():.1e}")
    f = numpy_field(p)
    dy, dy_np = np.empty(6), f(0.0, y0)
    from solvers.kernels.fields import rhs
    rhs(L.MODEL_FULL, 0.0, y0, p, dy)
    say(f"numpy field vs compiled field at y0: {np.abs(dy - dy_np).max():.1e}")
    say()

    sp_y, sp_wall, sp_nfev = scipy_run(p, y0, t, RTOL, RTOL * 1e-2)
    sp_err = np.abs(sp_y - ref).max()
    rows = [("scipy DOP853 (numpy rhs)", RTOL, "-", sp_nfev, sp_wall, sp_err)]
    for method in ("dop853", "vern9"):
        for rtol in (RTOL, RTOL * 10):
            r = ours(p, y0, t, method, rtol, rtol * 1e-2)
            rows.append((f"ours {method}", rtol, r.steps, r.rhs_calls, r.wall_s,
                         np.abs(r.y - ref).max()))
    say(f"Chaplygin ball on the plane, T = {T_END:g}, 1001 samples, atol = rtol/100; "
        f"ours: best of {REPEATS}")
    say(f"{'run':26s} {'rtol':>7s} {'steps':>6s} {'rhs':>8s} {'wall [s]':>10s} "
        f"{'max error':>10s} {'speed-up':>9s} {'err/scipy':>9s}")
    for name, rtol, steps, nfev, wall, err in rows:
        say(f"{name:26s} {rtol:7.0e} {steps!s:>6s} {nfev:8d} {wall:10.4f} {err:10.2e} "
            f"{sp_wall / wall:8.0f}x {err / sp_err:9.2f}")
    eq = [(w, n) for n, rt, _, _, w, e in rows[1:] if e <= sp_err]
    if eq:
        w, n = min(eq)
        say()
        say(f"speed-up at equal or better error: {sp_wall / w:.0f}x ({n}, {w * 1e3:.1f} ms "
            f"vs scipy {sp_wall:.2f} s)")
    per_call = min(r[4] / r[3] for r in rows[1:])
    say(f"cost per rhs call incl. the step: ours {per_call * 1e9:.0f} ns, scipy "
        f"{sp_wall / sp_nfev * 1e6:.1f} us")
    OUT.parent.mkdir(exist_ok=True)
    OUT.write_text("\n".join(lines) + "\n")


if __name__ == "__main__":
    main()
