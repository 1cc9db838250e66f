"""Concrete parameter draws for a claim, from the case's model and the claim's conditions.

`Params` wraps a built model (solvers.models.cases.Model) and exposes the physical quantities a
formula needs by the paper's names (I, m, R, a, b, mu, lam, k, S, g, eps, z, D) plus the
body's r(gamma) and J(gamma) from the compiled support function (complex-safe).
"""

from dataclasses import dataclass

import numpy as np

from catalogue.schema import Case, Claim, Conditions, Gyrostat, InertiaRestriction, Potential
from solvers.errors import InputError
from solvers.kernels import layout as L
from solvers.kernels.support import support
from solvers.models.bodies import check_state, tangent_fit
from solvers.models.cases import Model, build, registry


@dataclass(frozen=True)
class Params:
    model: Model

    # --- names of the paper ----------------------------------------------------------
    @property
    def p(self):
        return self.model.p

    @property
    def I(self):
        return np.array(self.p[L.I1:L.I3 + 1])

    @property
    def m(self):
        return float(self.p[L.MASS])

    @property
    def k(self):
        return float(self.p[L.CURV])

    @property
    def R(self):
        """Ball radius (c of the support function) or disk radius (d)."""
        return float(self.p[L.BALL_C] or self.p[L.DISK_D])

    @property
    def a(self):
        """Centre of mass -> geometric centre, a vector (2.28); a[2] is the axial offset."""
        return np.array(self.p[L.A1:L.A3 + 1])

    @property
    def b(self):
        return np.array([self.p[L.B11], self.p[L.B22], self.p[L.B33]])

    @property
    def S(self):
        return np.array(self.p[L.S1:L.S3 + 1])

    @property
    def g(self):
        return float(self.p[L.GRAV])

    @property
    def eps(self):
        return float(self.p[L.BRUN])

    @property
    def z(self):
        return float(self.p[L.FLAT_Z])

    @property
    def D(self):
        """D = m a^2 of (2.23) (a: the ball's radius)."""
        return self.m * self.R ** 2

    @property
    def mu(self):
        return self.model.params.get("mu")

    @property
    def lam(self):
        return self.model.params.get("lambda")

    # --- geometry ----------------------------------------------------------------------
    def r(self, gamma):
        gamma = np.asarray(gamma)
        r = np.empty(3, dtype=np.result_type(gamma, float))
        J = np.empty((3, 3), dtype=r.dtype)
        support(self.p, gamma, r, J)
        return r

    def J(self, gamma):
        gamma = np.asarray(gamma)
        r = np.empty(3, dtype=np.result_type(gamma, float))
        J = np.empty((3, 3), dtype=r.dtype)
        support(self.p, gamma, r, J)
        return J

    def contact_inertia(self, r):
        """I_Q = I + m (r^2 E - r r^T)."""
        return np.diag(self.I) + self.m * ((r @ r) * np.eye(3) - np.outer(r, r))

    def omega(self, M, gamma_or_r):
        """omega = I_Q^-1 M, with r = r(gamma) or, for flat bases, r given directly."""
        r = gamma_or_r if self.model.model == L.MODEL_FLAT else self.r(gamma_or_r)
        return np.linalg.solve(self.contact_inertia(r), M)


# --- drawing parameters under conditions -------------------------------------------------

def merged_conditions(case: Case, claim: Claim) -> Conditions:
    base = case.model.conditions.model_dump(by_alias=False)
    over = claim.conditions.model_dump(by_alias=False, exclude_none=True)
    base.update(over)
    return Conditions(**{("lambda" if k == "lambda_" else k): v for k, v in base.items()})


def _draw_inertia(rng, restriction, names):
    """Principal moments obeying `restriction` and the triangle inequality."""
    for _ in range(1000):
        I = rng.uniform(1.0, 3.0, 3)
        if restriction in (InertiaRestriction.AXIAL, InertiaRestriction.AXIAL_I1_NE_I3):
            I[1] = I[0]
        elif restriction is InertiaRestriction.AXIAL_I1_GT_I3:
            I[1] = I[0]
            I[2] = I[0] * rng.uniform(0.55, 0.9)
        elif restriction is InertiaRestriction.AXIAL_I1_LT_I3:
            I[1] = I[0]
            I[2] = I[0] * rng.uniform(1.1, 1.9)
        elif restriction is InertiaRestriction.AXIAL_I3_2I1 or \
                restriction is InertiaRestriction.WORONETZ:
            I[1] = I[0]
            I[2] = 2 * I[0]
        elif restriction is InertiaRestriction.SPHERICAL:
            I[:] = I[0]
        elif restriction is InertiaRestriction.FLAT_PLATE:
            I[2] = I[0] + I[1]
        if "I2" not in names:      # axisymmetric case: I2 is I1 by construction
            I[1] = I[0]
        if all(I[i] <= I[(i + 1) % 3] + I[(i + 2) % 3] + 1e-12 for i in range(3)):
            return I
    raise RuntimeError(f"cannot draw inertia for {restriction}")


def draw(case: Case, claim: Claim, rng: np.random.Generator) -> Params:
    """One random parameter set of `case` satisfying the claim's conditions."""
    spec = registry()[case.id]
    cond = merged_conditions(case, claim)
    names = spec.param_names
    prm = {k: v for k, v in spec.example.items()}
    for key in ("m", "R", "b1", "b2", "b3", "mu"):
        if key in prm:
            prm[key] *= rng.uniform(0.8, 1.25)
    if "I1" in names:
        I = _draw_inertia(rng, cond.I, names)
        prm.update(I1=I[0], I3=I[2])
        if "I2" in names:
            prm["I2"] = I[1]
    if cond.I is InertiaRestriction.SPHERICAL and "mu" in names and "lambda" in names:
        prm["lambda"] = 0.0
    # centre-of-mass offset
    for key in ("a1", "a2", "a3", "a"):
        if key in prm:
            prm[key] = 0.0 if cond.a == "0" else prm[key] * rng.uniform(0.7, 1.3) + (
                0.1 * rng.uniform(-1, 1) if cond.a != "0" else 0.0)
    if "z" in names:
        prm["z"] = 0.0 if cond.z == "0" else rng.uniform(0.2, 0.5)
    if "lambda" in names and cond.lambda_ is not None:
        prm["lambda"] = {"0": 0.0, "1": 1.0, "not 0 or 1": rng.uniform(0.3, 0.7),
                         "any": rng.uniform(0.0, 1.0)}[cond.lambda_]
    # curvature
    if "k" in names:
        if cond.k == "0":
            prm["k"] = 0.0
        else:
            sign = rng.choice([-1.0, 1.0]) if "R" in prm or "b1" in prm else -1.0
            if spec.body == "flat":
                sign = -1.0
            size = 1.0 / max(prm.get("R", 1.0), np.sqrt(max(prm.get("b1", 1.0),
                                                              prm.get("b3", 1.0))), 1.0)
            prm["k"] = sign * size * rng.uniform(0.1, 0.35)
    # potentials
    pot = cond.potential
    g = rng.uniform(0.5, 2.0)
    eps = rng.uniform(0.3, 1.5)
    if "g" in names:
        prm["g"] = g if pot in (Potential.GRAVITY, Potential.AXISYMMETRIC, Potential.ANY) else 0.0
    if "eps" in names:
        prm["eps"] = eps if pot in (Potential.BRUN, Potential.AXISYMMETRIC, Potential.ANY) \
            else 0.0
    # gyrostat
    for i, key in enumerate(("S1", "S2", "S3")):
        if key in names:
            on = cond.S is Gyrostat.ANY or (cond.S is Gyrostat.AXIAL and i == 2)
            prm[key] = rng.uniform(0.2, 0.8) * rng.choice([-1.0, 1.0]) if on else 0.0
    try:
        return Params(build(case.id, prm, allow_any_inertia=cond.I is InertiaRestriction.ANY))
    except InputError as e:
        raise RuntimeError(f"{claim.id}: drawn parameters rejected: {e}") from e


def random_states(P: Params, n: int, rng: np.random.Generator, *, pole_margin=0.05):
    """n random phase points (full state) where the model is regular: unit gamma away from
    the poles gamma3 = +-1 (reduced variables and disks need it) and fitting the sphere."""
    out = []
    dim = P.model.dim
    while len(out) < n:
        y = rng.standard_normal(dim)
        if P.model.model == L.MODEL_FULL:
            g = rng.standard_normal(3)
            g /= np.linalg.norm(g)
            if abs(g[2]) > 1 - pole_margin:
                continue
            y[3:] = g
            if P.model.case.fixed_k is None and P.k != 0 and tangent_fit(P.p, g) <= 0.05:
                continue
        else:
            y[3:] *= 0.5
        try:
            check_state(P.model.model, P.p, y, shell=P.model.case.fixed_k is not None)
        except InputError:
            continue
        out.append(y)
    return out
