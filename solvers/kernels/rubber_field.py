"""The no-spin reaction of a rubber body in the generated fields (solvers/kernels/generate.py):
dM/dt of the marble plus lambda gamma, lambda from d/dt (omega, gamma) = 0, written with the
sympy program of `generate.equations` for the structure's branch (ball on a sphere, disk,
general body)."""

from __future__ import annotations

from solvers.kernels import layout as L


def rubber_reaction(prog, Md, P, g, w, gd, r, rd, inverse_gamma, *, sphere, disk, lam, is2):
    """dM/dt + lambda gamma, the reaction of the no-spin constraint (omega, gamma) = 0
    (layout.RUBBER; the general field's fields.rubber_reaction, derived in
    solvers/models/rubber_lagrange.py): lambda from d/dt (omega, gamma) = 0,
        lambda = -[(I_Q^-1 gamma, N - (dI_Q/dt) omega) + (omega, dgamma/dt)]
                 / (I_Q^-1 gamma, gamma),
    (dI_Q/dt) omega = m (2 (r, dr/dt) omega - dr/dt (r, omega) - r (dr/dt, omega)),
    N = dM/dt of the marble. The branches of `equations` keep r and dr/dt scaled where
    that saves work (a centred ball: r = gamma; m folded into dr/dt); here they are
    the true r and J dgamma/dt. `inverse_gamma()` gives I_Q^-1 gamma in the caller's
    form (a centred ball's Sherman-Morrison, else the symbolic solve), called where it
    was always computed so that the generated code keeps its order."""
    import sympy as sp  # lazy: sympy, not at server start

    m = P[L.MASS]
    Md = [prog.let(x) for x in Md]   # N once: it enters lambda and the result
    if sphere:      # r = lam gamma + a, J dgamma/dt = lam dgamma/dt ((gamma, dgamma/dt) = 0)
        rt = [prog.let(lam * g[i] + P[L.A1 + i]) for i in range(3)]
        rdt = [prog.let(lam * x) for x in gd]
    elif disk:      # r = (d/s) rho, J dgamma/dt = (d/s^3) t (t, dgamma/dt), t = (-g2, g1, 0)
        lam_d = prog.let(P[L.DISK_D] * sp.sqrt(is2))
        rt = [prog.let(lam_d * g[0]), prog.let(lam_d * g[1]), sp.Integer(0)]
        c3 = prog.let(lam_d * is2 * prog.let(g[0] * gd[1] - g[1] * gd[0]))
        rdt = [prog.let(-g[1] * c3), prog.let(g[0] * c3), sp.Integer(0)]
    else:
        rt, rdt = r, rd
    Ag = inverse_gamma()
    rrd = prog.let(sum(rt[i] * rdt[i] for i in range(3)))
    rw = prog.let(sum(rt[i] * w[i] for i in range(3)))
    rdw = prog.let(sum(rdt[i] * w[i] for i in range(3)))
    E = [prog.let(Md[i] - m * (2 * rrd * w[i] - rdt[i] * rw - rt[i] * rdw)) for i in range(3)]
    num = prog.let(sum(Ag[i] * E[i] for i in range(3)) + sum(w[i] * gd[i] for i in range(3)))
    lam_r = prog.let(-num * prog.let(1 / prog.let(sum(Ag[i] * g[i] for i in range(3)))))
    return [prog.let(Md[i] + lam_r * g[i]) for i in range(3)]
