"""The scene of a rolling body: how it turns and where it touches the support.

Only what the explorer's 3D animation shows, computed when asked. Along a trajectory of the
case's own equations (the compiled field `rhs`), three more equations are integrated:

    dQ/dt   = Q [omega]x          Q: body axes -> space, omega in body axes
    dx_G/dt = Q (r x omega)       the contact point has zero velocity (rolling without
                                  sliding): v_G + (Q omega) x (Q r) = 0
    x_P     = x_G + Q r           the contact point, r = r(gamma) from G (CONVENTIONS.md)

Space frame: the support's unit normal at the first contact point, pointing from the body
into the support, is -e_z (Q(0) gamma(0) = -e_z, the smallest rotation doing so). On the
plane (k = 0) the support is z = 0 and the body stands above it. On a sphere of signed
curvature k the support's centre is the origin and x_P = Q gamma / k (k > 0: inside a
cavity of radius 1/k, or a shell over a ball; k < 0: on the outside of a ball of radius
1/|k|). The flat-base bodies (state (M, r1, r2)) have gamma = e3 and r = (r1, r2, z).

Two identities the equations above do not impose are reported as checks: Q stays a
rotation, and the contact point stays on the support (for a ball on a sphere also
x_P = Q gamma / k).
"""

from __future__ import annotations

import math

import numpy as np

from solvers.errors import InputError
from solvers.integrate.integrator import integrate
from solvers.kernels import layout as L
from solvers.kernels.fields import flat_kinematics, full_kinematics
from solvers.kernels.support import support
from solvers.models.cases import build, initial_state
from solvers.models.observables import vertical_spin

MAX_FRAMES = 10_000
E3 = np.array([0.0, 0.0, 1.0])


class _Singular(Exception):
    pass


def hat(w) -> np.ndarray:
    return np.array([[0.0, -w[2], w[1]], [w[2], 0.0, -w[0]], [-w[1], w[0], 0.0]])


def rotation_taking(a, b) -> np.ndarray:
    """The smallest rotation R with R a = b (a, b unit vectors)."""
    a = np.asarray(a, dtype=float) / np.linalg.norm(a)
    b = np.asarray(b, dtype=float) / np.linalg.norm(b)
    v = np.cross(a, b)
    c = float(a @ b)
    if c < -1.0 + 1e-12:              # opposite: half-turn about any axis normal to a
        axis = np.cross(a, np.eye(3)[np.argmin(abs(a))])
        axis /= np.linalg.norm(axis)
        return 2.0 * np.outer(axis, axis) - np.eye(3)
    V = hat(v)
    return np.eye(3) + V + V @ V / (1.0 + c)


def nearest_rotation(Q) -> np.ndarray:
    U, _, Vt = np.linalg.svd(Q)
    R = U @ Vt
    if np.linalg.det(R) < 0:
        U[:, -1] *= -1
        R = U @ Vt
    return R


class _Body:
    """omega, r and gamma (body axes) of a state of the model."""

    def __init__(self, model):
        self.code = model.model
        self.p = model.p
        self.flat = model.model == L.MODEL_FLAT
        self.r = np.empty(3)
        self.J = np.empty((3, 3))
        self.w = np.empty(3)
        self.gd = np.empty(3)

    def __call__(self, y):
        if self.flat:
            st = flat_kinematics(self.p, y, self.r, self.w)
            g = E3
        else:
            g = y[3:6]
            st = full_kinematics(self.p, y[0:3], g, self.r, self.J, self.w, self.gd)
        if st != L.OK:
            raise _Singular(int(st))
        return self.w.copy(), self.r.copy(), np.array(g, dtype=float)


def body_mesh(model, extent: float = 1.0) -> dict:
    """A triangle mesh of the body in its own axes (origin at the centre of mass), with a
    two-colour pattern fixed in the body so that its rotation can be seen.

    Convex bodies: the support map r(n) over a grid of unit normals n. Disk: the flat disk
    x3 = a of radius R. Flat base: the face x3 = z (radius from `extent`, the reach of
    the contact point on it) closed by a dome; the paper fixes only the face."""
    case = model.case
    p = model.p
    if case.body == "disk":
        R, a = float(p[L.DISK_D]), float(p[L.A3])
        return _disk_mesh(R, a, dome=None)
    if case.body == "flat":
        z = float(p[L.FLAT_Z])
        rho = max(1.25 * extent, 0.5)
        depth = (z - min(0.0, z)) + 0.8 * rho
        return _disk_mesh(rho, z, dome=depth)
    nt, nf = 24, 48
    verts, normals = [], []
    r = np.empty(3)
    J = np.empty((3, 3))
    for i in range(nt + 1):
        th = math.pi * i / nt
        for j in range(nf):
            ph = 2 * math.pi * j / nf
            n = np.array([math.sin(th) * math.cos(ph), math.sin(th) * math.sin(ph),
                          math.cos(th)])
            support(p, n, r, J)
            verts.append(r.copy())
            normals.append(n)
    faces, pattern = [], []
    for i in range(nt):
        for j in range(nf):
            a, b = i * nf + j, i * nf + (j + 1) % nf
            c, d = a + nf, b + nf
            centre = normals[a] + normals[b] + normals[c] + normals[d]
            # the panels of a beach ball: octants of the body axes alternate in colour
            col = int((centre[0] > 0) ^ (centre[1] > 0) ^ (centre[2] > 0))
            for tri in ((a, b, d), (a, d, c)):
                faces.append(tri)
                pattern.append(col)
    return {"vertices": np.asarray(verts).round(12).tolist(), "faces": faces,
            "pattern": pattern}


def _disk_mesh(R: float, height: float, dome: float | None) -> dict:
    """A disk of radius R in the plane x3 = height (and, for a flat base, a dome of the
    given depth below it)."""
    nr, nf = 4, 48
    verts = [[0.0, 0.0, height]]
    for i in range(1, nr + 1):
        for j in range(nf):
            ph = 2 * math.pi * j / nf
            verts.append([R * i / nr * math.cos(ph), R * i / nr * math.sin(ph), height])
    faces, pattern = [], []

    def col(j):
        ph = 2 * math.pi * (j + 0.5) / nf
        return int((math.cos(ph) > 0) ^ (math.sin(ph) > 0))

    for j in range(nf):
        faces.append((0, 1 + j, 1 + (j + 1) % nf))
        pattern.append(col(j))
    for i in range(1, nr):
        for j in range(nf):
            a, b = 1 + (i - 1) * nf + j, 1 + (i - 1) * nf + (j + 1) % nf
            c, d = a + nf, b + nf
            faces += [(a, b, d), (a, d, c)]
            pattern += [col(j), col(j)]
    if dome is not None:
        rim0 = 1 + (nr - 1) * nf
        nt = 8
        base = len(verts)
        for i in range(1, nt + 1):
            th = 0.5 * math.pi * (1 - i / nt)       # from the rim (pi/2) to the bottom (0)
            for j in range(nf):
                ph = 2 * math.pi * j / nf
                verts.append([R * math.sin(th) * math.cos(ph), R * math.sin(th) * math.sin(ph),
                              height - dome * math.cos(th)])
        for i in range(nt):
            for j in range(nf):
                a = rim0 + j if i == 0 else base + (i - 1) * nf + j
                b = rim0 + (j + 1) % nf if i == 0 else base + (i - 1) * nf + (j + 1) % nf
                c, d = base + i * nf + j, base + i * nf + (j + 1) % nf
                faces += [(a, b, d), (a, d, c)]
                pattern += [col(j) ^ (i % 2), col(j) ^ (i % 2)]
    return {"vertices": verts, "faces": [list(f) for f in faces], "pattern": pattern}


def _series(model, Y) -> dict[str, list[float]]:
    """Time series a teaching scene plots beside the animation, one value per frame:
    `vertical_spin` -(omega, gamma), the spin about the upward vertical (the rattleback's
    reversal), and `tilt` sqrt(g1^2 + g2^2), the sine of the angle between the body's e3
    axis and the vertical (a rolling disk stays up while it stays away from 0)."""
    if model.dim != 6 or len(Y) == 0:
        return {}

    return {"vertical_spin": vertical_spin(model, Y).tolist(),
            "tilt": np.hypot(Y[:, 3], Y[:, 4]).tolist()}


def scene(case: str, params: dict | None, state0, t_end: float, *, frames: int = 200,
          rtol: float = 1e-9, atol: float = 1e-11, max_steps: int = 100_000,
          allow_any_inertia: bool = False) -> dict:
    """Frames of the rolling body over [0, t_end]; see the module docstring."""
    model = build(case, params, allow_any_inertia=allow_any_inertia)
    y0 = initial_state(model, state0)
    if not isinstance(t_end, int | float) or not math.isfinite(t_end) or not t_end > 0:
        raise InputError(f"t_end = {t_end!r}: must be a positive finite number")
    if isinstance(frames, bool) or not isinstance(frames, int) or not 2 <= frames <= MAX_FRAMES:
        raise InputError(f"frames = {frames!r}: must be an integer in [2, {MAX_FRAMES}]")
    body = _Body(model)
    n = model.dim
    k = float(model.p[L.CURV])
    try:
        _, r0, g0 = body(y0)
    except _Singular as exc:   # no first frame to draw: the input's fault, said as such
        raise InputError("the initial state is singular for this body: "
                         f"{L.STATUS_TEXT[exc.args[0]]}") from None
    Q0 = rotation_taking(g0, -E3)
    xP0 = np.zeros(3) if k == 0.0 else Q0 @ g0 / k
    z0 = np.concatenate([y0, Q0.ravel(), xP0 - Q0 @ r0])
    # the compiled scene model integrates (state, Q, x_G) together (fields.scene_field)
    scene_model = L.MODEL_FLAT_SCENE if model.model == L.MODEL_FLAT else L.MODEL_FULL_SCENE
    t_frames = np.linspace(0.0, float(t_end), frames)
    res = integrate(scene_model, model.p, z0, t_frames, method="dop853", rtol=rtol, atol=atol,
                    max_steps=max_steps)
    status, message, steps = "ok", "", res.steps
    if not res.success:
        if res.budget_exhausted:
            status = "budget"
            message = (f"step budget of {max_steps} steps used up at t = {res.t_stop:.6g}; "
                       "the scene shows the frames before it")
        else:
            status = "singular"
            message = f"{res.message}; the scene stops there"
    out = list(res.y[:len(res.t)]) or [z0]
    Z = np.asarray(out)
    Qs, xP, errs = [], [], []
    orth = 0.0
    for z in Z:
        Q = z[n:n + 9].reshape(3, 3)
        orth = max(orth, float(np.max(np.abs(Q.T @ Q - np.eye(3)))))
        _, r, g = body(np.ascontiguousarray(z[:n]))
        p_ = z[n + 9:n + 12] + Q @ r
        if k == 0.0:
            errs.append((abs(p_[2]), float(np.max(np.abs(Q @ g + E3)))))
        else:
            errs.append((abs(np.linalg.norm(p_) - 1.0 / abs(k)),
                         float(np.max(np.abs(p_ - Q @ g / k)))))
        Qs.append(nearest_rotation(Q).ravel())
        xP.append(p_)
    # A trajectory that steps across a singular configuration (a disk passing through the
    # flat position, where its contact point is undefined) makes the contact point jump
    # off the support: the scene stops before that frame rather than show it.
    errs = np.asarray(errs)
    scale = 1.0 + float(np.max(np.abs(Z[:, n + 9:n + 12])))
    bad = np.flatnonzero(errs.max(axis=1) > 1e-6 * scale)
    if bad.size:
        j = int(bad[0])
        status = "singular"
        message = (f"the contact point left the support between t = {t_frames[j - 1]:.6g} and "
                   f"t = {t_frames[j]:.6g}: the trajectory crossed a configuration where the "
                   "contact point is undefined (a disk passing through the flat position); "
                   "the scene stops before it")
        Z, errs, Qs, xP = Z[:j], errs[:j], Qs[:j], xP[:j]
    t = t_frames[:len(Z)]
    xG = Z[:, n + 9:n + 12]
    on_support, gamma_err = (float(v) for v in errs.max(axis=0))
    xP = np.asarray(xP)
    reach = np.asarray([body(np.ascontiguousarray(z[:n]))[1] for z in Z])
    extent = float(np.max(np.hypot(reach[:, 0], reach[:, 1])))
    return {
        "series": _series(model, Z[:, :n]),
        "case": model.case.id,
        "surface": model.case.surface,
        "body": model.case.body,
        "k": k,
        "support_radius": None if k == 0.0 else 1.0 / abs(k),
        "support_inside_body": model.case.fixed_k is not None,
        "t": t.tolist(),
        "Q": np.asarray(Qs).tolist(),
        "x_G": xG.tolist(),
        "contact": xP.tolist(),
        "mesh": body_mesh(model, extent),
        "status": status,
        "message": message,
        "stats": {"steps": steps, "rhs_calls": int(res.rhs_calls), "frames": len(t)},
        "checks": {
            "orthogonality": orth,          # max |Q^T Q - E| before re-orthonormalising
            "contact_on_support": on_support,
            "normal_in_space": gamma_err,   # plane: |Q gamma + e_z|; sphere: |x_P - Q gamma/k|
        },
    }
