"""Vector fields of every model, dispatched on an integer model code.

`rhs(model, t, y, p, dydt) -> status` is the one function the integrator kernels call
(a module-level global, so numba's on-disk cache works: no function passed as argument).

Full model (CONVENTIONS.md), state (M, gamma):
  omega = I_Q^-1 M,  I_Q = I + m (r^2 E - r r^T)                          eq1.6
  (E - k J) dgamma/dt = gamma x omega,  dr/dt = J dgamma/dt                eq1.2 / eq1.3
  dM/dt = (M + S) x omega + m dr/dt x (omega x r) + M_Q                   eq1.1
  M_Q = gamma x (E - k J^T)^-1 dU/dgamma,  U = m g (r, gamma) + eps/2 (I gamma, gamma)
Flat base on a sphere, state (M, r1, r2), gamma = e3 fixed, r = (r1, r2, z):
  0 = gamma x omega + k dr/dt  =>  dr/dt = (omega2, -omega1, 0) / k     eq3.15
  (the paper prints eq3.15 with k = +1/R for the outside of the sphere, i.e. with gamma
  pointing out of the support; under CONVENTIONS.md the outside is k = -1/R0).
"""

import numpy as np

from solvers.kernels import layout as L
from solvers.kernels.jit import kernel
from solvers.kernels.linalg import cross, solve3
from solvers.kernels.reduced import rev_reduced
from solvers.kernels.support import support


@kernel
def contact_inertia(p, r, IQ):
    """I_Q = I + m (r^2 E - r r^T): tensor of inertia about the contact point."""
    m = p[L.MASS]
    r2 = r[0] * r[0] + r[1] * r[1] + r[2] * r[2]
    for i in range(3):
        for j in range(3):
            IQ[i, j] = -m * r[i] * r[j]
        IQ[i, i] += p[L.I1 + i] + m * r2


@kernel
def full_kinematics(p, M, g, r, J, w, gd):
    """r, J, omega and dgamma/dt of the full model. Returns a status code."""
    s = support(p, g, r, J)
    if s == 0.0:
        return L.SING_EDGE
    IQ = np.empty((3, 3), dtype=r.dtype)
    contact_inertia(p, r, IQ)
    if solve3(IQ, M, w) == 0:
        return L.SING_INERTIA
    u = np.empty(3, dtype=r.dtype)
    cross(g, w, u)
    k = p[L.CURV]
    if k == 0.0:
        gd[0] = u[0]
        gd[1] = u[1]
        gd[2] = u[2]
    else:
        A = np.empty((3, 3), dtype=r.dtype)
        for i in range(3):
            for j in range(3):
                A[i, j] = -k * J[i, j]
            A[i, i] += 1.0
        # det(E - k J) changes sign where 1 - k * (radius of curvature) crosses 0
        if solve3(A, u, gd).real <= 0.0:
            return L.SING_FIT
    return L.OK


@kernel
def full_field(p, y, dydt):
    M = y[0:3]
    g = y[3:6]
    r = np.empty(3, dtype=y.dtype)
    J = np.empty((3, 3), dtype=y.dtype)
    w = np.empty(3, dtype=y.dtype)
    gd = np.empty(3, dtype=y.dtype)
    st = full_kinematics(p, M, g, r, J, w, gd)
    if st != L.OK:
        return st
    m = p[L.MASS]
    k = p[L.CURV]
    rd = np.empty(3, dtype=y.dtype)
    for i in range(3):
        rd[i] = J[i, 0] * gd[0] + J[i, 1] * gd[1] + J[i, 2] * gd[2]
    # dU/dgamma for gravity U = m g (r, gamma) and the Brun field U = eps/2 (I gamma, gamma)
    dU = np.empty(3, dtype=y.dtype)
    mg = m * p[L.GRAV]
    eps = p[L.BRUN]
    for i in range(3):
        jtg = J[0, i] * g[0] + J[1, i] * g[1] + J[2, i] * g[2]
        dU[i] = mg * (r[i] + jtg) + eps * p[L.I1 + i] * g[i]
    if k != 0.0 and (mg != 0.0 or eps != 0.0):
        A = np.empty((3, 3), dtype=y.dtype)
        for i in range(3):
            for j in range(3):
                A[i, j] = -k * J[j, i]
            A[i, i] += 1.0
        tmp = np.empty(3, dtype=y.dtype)
        if solve3(A, dU, tmp) == 0:
            return L.SING_FIT
        dU[:] = tmp
    MS = np.empty(3, dtype=y.dtype)
    for i in range(3):
        MS[i] = M[i] + p[L.S1 + i]
    wxr = np.empty(3, dtype=y.dtype)
    cross(w, r, wxr)
    t1 = np.empty(3, dtype=y.dtype)
    t2 = np.empty(3, dtype=y.dtype)
    t3 = np.empty(3, dtype=y.dtype)
    cross(MS, w, t1)
    cross(rd, wxr, t2)
    cross(g, dU, t3)
    for i in range(3):
        dydt[i] = t1[i] + m * t2[i] + t3[i]
        dydt[3 + i] = gd[i]
    return L.OK


@kernel
def flat_kinematics(p, y, r, w):
    """r = (r1, r2, z) and omega of the flat-base model. Returns a status code."""
    r[0] = y[3]
    r[1] = y[4]
    r[2] = p[L.FLAT_Z] + 0.0 * y[3]
    IQ = np.empty((3, 3), dtype=y.dtype)
    contact_inertia(p, r, IQ)
    if solve3(IQ, y[0:3], w) == 0:
        return L.SING_INERTIA
    return L.OK


@kernel
def flat_field(p, y, dydt):
    r = np.empty(3, dtype=y.dtype)
    w = np.empty(3, dtype=y.dtype)
    st = flat_kinematics(p, y, r, w)
    if st != L.OK:
        return st
    m = p[L.MASS]
    k = p[L.CURV]
    rd = np.empty(3, dtype=y.dtype)
    rd[0] = w[1] / k
    rd[1] = -w[0] / k
    rd[2] = 0.0 * w[0]
    MS = np.empty(3, dtype=y.dtype)
    for i in range(3):
        MS[i] = y[i] + p[L.S1 + i]
    wxr = np.empty(3, dtype=y.dtype)
    cross(w, r, wxr)
    t1 = np.empty(3, dtype=y.dtype)
    t2 = np.empty(3, dtype=y.dtype)
    cross(MS, w, t1)
    cross(rd, wxr, t2)
    for i in range(3):
        dydt[i] = t1[i] + m * t2[i]
    dydt[3] = rd[0]
    dydt[4] = rd[1]
    return L.OK


@kernel
def test_field(model, y, dydt):
    if model == L.MODEL_TEST_OSC:
        dydt[0] = y[1]
        dydt[1] = -y[0]
    else:  # planar Kepler
        r2 = y[0] * y[0] + y[1] * y[1]
        r3 = r2 * np.sqrt(r2)
        dydt[0] = y[2]
        dydt[1] = y[3]
        dydt[2] = -y[0] / r3
        dydt[3] = -y[1] / r3
    return L.OK


@kernel
def rhs(model, t, y, p, dydt):
    """dy/dt of `model` at (t, y) with parameters p, written into dydt. Returns a status."""
    if model == L.MODEL_FULL:
        st = full_field(p, y, dydt)
    elif model == L.MODEL_FLAT:
        st = flat_field(p, y, dydt)
    elif model == L.MODEL_REV_REDUCED:
        st = rev_reduced(p, y, dydt)  # eq2-*1, solvers.kernels.reduced
    else:
        st = test_field(model, y, dydt)
    if st == L.OK:
        for i in range(dydt.shape[0]):
            if not np.isfinite(dydt[i]):
                return L.SING_NONFINITE
    return st
