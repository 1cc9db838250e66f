"""The case registry (solvers/models/cases.yaml), validated once, and the builder that turns a
case id plus named parameters into a kernel model: (model code, parameter vector p)."""

import math
from dataclasses import dataclass
from functools import cache
from pathlib import Path
from typing import Literal

import numpy as np
import yaml
from pydantic import BaseModel, ConfigDict, Field

from solvers.errors import InputError
from solvers.kernels import integrals as Q
from solvers.kernels import layout as L
from solvers.kernels.fields import full_kinematics, rhs
from solvers.models.bodies import NEGATIVE, STATE_LABELS, check_state, fill_body, fill_inertia

PARAM_SLOTS = {"S1": L.S1, "S2": L.S2, "S3": L.S3, "g": L.GRAV, "eps": L.BRUN, "k": L.CURV}


class IntegralSpec(BaseModel):
    model_config = ConfigDict(extra="forbid")
    name: Literal[Q.NAMES]  # type: ignore[valid-type]
    when: list[str] = Field(description="parameters that must be zero for the integral")
    any_nonzero: list[str] = Field(default_factory=list,
                                   description="at least one must be nonzero (else redundant)")


class CaseSpec(BaseModel):
    """One case of the registry (solvers/models/cases.yaml): a body, the surface it rolls
    on, its parameters with an example set, and the first integrals it carries.

    Attributes
    ----------
    id : str
        The case id, "<surface>/<body>", e.g. "plane/chaplygin-ball".
    title : str
        A one-line description.
    surface : {"plane", "sphere"}
        What the body rolls on.
    body : str
        How the parameters make the body's surface (solvers/models/bodies.py): "ball",
        "routh", "disk", "ellipsoid", "revolution", "general", "flat" or "rattleback".
    symmetry : {"none", "axial", "spherical"}
        The dynamical symmetry of the tensor of inertia.
    fixed_k : str or None
        "2/R" for the cases whose curvature k is fixed by R (k is then not a parameter).
    required : list of str
        The parameters `simulate` needs.
    optional : dict of str to float or None
        The other parameters with their defaults (None: I2 equal to I1).
    example : dict of str to float
        A valid parameter set.
    state : list of float
        A valid initial state for `example`.
    integrals : list
        The first integrals the case carries beyond the energy and under which
        parameters (each has a name, `when`: the parameters that must be zero, and
        `any_nonzero`).
    in_tables : bool
        Whether the case is a column of the paper's Tables 1-2 (with claims in
        catalogue/); False for a case the text only mentions, such as the rattleback.
    constraint : {"marble", "rubber"}
        "marble": rolling without slipping (the paper's model); "rubber": also without
        spinning about the normal, (omega, gamma) = 0 (solvers/models/rubber_lagrange.py).
        A rubber case's state lies on (omega, gamma) = 0, |gamma| = 1, and it carries the
        integral "spin", (omega, gamma).
    param_names : list of str
        required, then the optional ones.

    Examples
    --------
    >>> import solvers
    >>> ball = solvers.cases()["plane/chaplygin-ball"]
    >>> ball.surface, ball.required
    ('plane', ['I1', 'I2', 'I3', 'm', 'R'])
    >>> ball.optional["g"], ball.example["I3"], len(ball.state)
    (0.0, 3.0, 6)
    """

    model_config = ConfigDict(extra="forbid")
    id: str
    title: str
    surface: Literal["plane", "sphere"]
    body: Literal["ball", "routh", "disk", "ellipsoid", "revolution", "general", "flat",
                  "rattleback"]
    symmetry: Literal["none", "axial", "spherical"]
    fixed_k: Literal["2/R"] | None = None
    required: list[str]
    optional: dict[str, float | None]
    example: dict[str, float]
    state: list[float]
    integrals: list[IntegralSpec]
    # a column of the paper's Tables 1-2 (with claims in catalogue/); False for a case the
    # text only mentions, such as the rattleback (Celtic stone)
    in_tables: bool = True
    # for a case beyond the tables: what its page says it is, instead of a table column
    note: str | None = None
    constraint: Literal["marble", "rubber"] = "marble"

    @property
    def param_names(self) -> list[str]:
        return [*self.required, *self.optional]


@cache
def registry() -> dict[str, CaseSpec]:
    raw = yaml.safe_load((Path(__file__).parent / "cases.yaml").read_text())
    return {cid: CaseSpec(id=cid, **spec) for cid, spec in raw.items()}


def case_ids() -> list[str]:
    return list(registry())


def cases() -> dict[str, CaseSpec]:
    """The cases `simulate` runs, by id, with their parameters and example values.

    The sixteen columns of the paper's Tables 1 (rolling on a plane) and 2 (rolling on a
    sphere), then the cases the text only mentions (`CaseSpec.in_tables` False), then the
    rubber cases, beyond the paper: the same bodies rolling without slipping and without
    spinning about the normal (`CaseSpec.constraint` "rubber", ids "rubber-plane/..." and
    "rubber-sphere/...").

    Returns
    -------
    dict of str to CaseSpec
        Case id -> its specification, in the registry's order: Table 1, then Table 2,
        then the others. A fresh copy: changing it changes no run.

    Examples
    --------
    >>> import solvers
    >>> every = solvers.cases()
    >>> list(every)[:3]
    ['plane/chaplygin-ball', 'plane/unbalanced-ball', 'plane/ellipsoid']
    >>> sum(c.in_tables for c in every.values()), every["plane/rattleback"].in_tables
    (16, False)
    >>> every["plane/round-disk"].required
    ['I1', 'I3', 'm', 'R']
    >>> every["rubber-plane/round-disk"].constraint, every["rubber-plane/round-disk"].required
    ('rubber', ['I1', 'I3', 'm', 'R'])
    """
    return {cid: spec.model_copy(deep=True) for cid, spec in registry().items()}


def table_case_ids() -> list[str]:
    """The cases that are columns of Tables 1-2 (each has claims in the catalogue)."""
    return [cid for cid, c in registry().items() if c.in_tables]


def beyond_table_ids() -> list[str]:
    """The runnable cases that are no column of Tables 1-2 (no claims in the catalogue)."""
    return [cid for cid, c in registry().items() if not c.in_tables]


def rubber_case_ids() -> list[str]:
    """The cases that roll without slipping and without spinning (constraint "rubber")."""
    return [cid for cid, c in registry().items() if c.constraint == "rubber"]


def get_case(case_id: str) -> CaseSpec:
    try:
        return registry()[case_id]
    except KeyError:
        raise InputError(f"unknown case {case_id!r}; known cases: "
                         + ", ".join(registry())) from None


@dataclass(frozen=True)
class Model:
    """What the kernels need for one run, plus names for people."""
    case: CaseSpec
    params: dict[str, float]
    model: int
    p: np.ndarray
    integral_names: tuple[str, ...]   # always "energy" first; "gamma2" for (M, gamma)
    integral_codes: tuple[int, ...]

    @property
    def state_labels(self) -> tuple[str, ...]:
        return STATE_LABELS[self.model]

    @property
    def dim(self) -> int:
        return L.STATE_DIM[self.model]


def _finite(name: str, value) -> float:
    try:
        v = float(value)
    except (TypeError, ValueError):
        raise InputError(f"{name} = {value!r}: not a number") from None
    if not math.isfinite(v):
        raise InputError(f"{name} = {value!r}: must be a finite number")
    return v


def build(case_id: str, params: dict | None = None, *, allow_any_inertia: bool = False) -> Model:
    """Validate `params` for `case_id` and build its kernel model."""
    case = get_case(case_id)
    params = dict(params or {})
    unknown = [k for k in params if k not in case.param_names]
    if "k" in params and case.fixed_k:
        raise InputError(f"k is fixed by the case {case_id} (k = {case.fixed_k}: "
                         "R0/(R0 - R) = -1); give only R")
    if unknown:
        raise InputError(f"unknown parameter{'s' * (len(unknown) > 1)} "
                         f"{', '.join(unknown)} for case {case_id}; its parameters are: "
                         + " ".join(case.param_names))
    missing = [k for k in case.required if k not in params]
    if missing:
        raise InputError(f"missing parameter{'s' * (len(missing) > 1)} {', '.join(missing)} "
                         f"for case {case_id} (required: {' '.join(case.required)})")
    prm: dict[str, float | None] = {}
    for name in case.param_names:
        if name in params:
            prm[name] = _finite(name, params[name])
        else:
            prm[name] = case.optional[name]
    p = np.zeros(L.N_PARAMS)
    fill_inertia(case.body, case.symmetry, prm, p, allow_any_inertia)
    model = fill_body(case.body, prm, p)
    for name, slot in PARAM_SLOTS.items():
        if name in prm:
            p[slot] = prm[name]
    if case.fixed_k == "2/R":
        p[L.CURV] = 2.0 / prm["R"]
    if "k" in NEGATIVE.get(case.body, ()) and not p[L.CURV] < 0:
        raise InputError(f"k = {float(p[L.CURV])!r}: a flat base rolls on the outside of a fixed "
                         "ball, so k = -1/R0 < 0 (CONVENTIONS.md; the paper's eq3.15 writes "
                         "k = +1/R with gamma pointing out of the support)")
    if case.constraint == "rubber":
        _rubber_checks(case_id, model, p)
        p[L.RUBBER] = 1.0
    names, codes = ["energy"], [Q.ENERGY]
    if model == L.MODEL_FULL:
        names.append("gamma2")
        codes.append(Q.GEOM)
    if case.constraint == "rubber":
        names.append("spin")
        codes.append(Q.SPIN)
    for spec in case.integrals:
        nonzero = not spec.any_nonzero or any(prm.get(c, 0.0) != 0.0 for c in spec.any_nonzero)
        if nonzero and all(prm.get(c, 0.0) == 0.0 for c in spec.when):
            names.append(spec.name)
            codes.append(Q.NAMES.index(spec.name))
    p.setflags(write=False)
    return Model(case, {k: v for k, v in prm.items() if v is not None}, model, p,
                 tuple(names), tuple(codes))


def _rubber_checks(case_id: str, model: int, p: np.ndarray) -> None:
    """What the rubber equations cover (solvers/models/rubber_bodies.py): the full model,
    a support function without off-diagonal B, no potential on a sphere."""
    if model != L.MODEL_FULL or any(p[s] != 0.0 for s in (L.B12, L.B13, L.B23)):
        raise InputError(f"case {case_id}: the rubber constraint is modelled for the (M, gamma) "
                         "bodies with principal-axes ellipsoids only")
    if p[L.CURV] != 0.0 and (p[L.GRAV] != 0.0 or p[L.BRUN] != 0.0):
        raise InputError(f"case {case_id}: a potential on a sphere is not modelled for rubber "
                         "bodies: g and eps must be 0 when k != 0")


# |(omega, gamma)| a rubber state may have, relative to |omega| (and at least this absolute):
# a state written with 16 digits keeps it
RUBBER_STATE_TOL = 1e-12


def initial_state(model: Model, state) -> np.ndarray:
    """Validate an initial state for the model: length, finiteness, |gamma| = 1, fit."""
    labels = model.state_labels
    try:
        values = list(state)
    except TypeError:
        raise InputError(f"state = {state!r}: expected {len(labels)} numbers "
                         f"({', '.join(labels)})") from None
    if len(values) != len(labels):
        raise InputError(f"state has {len(values)} values; case {model.case.id} needs "
                         f"{len(labels)}: {', '.join(labels)}")
    y0 = np.array([_finite(n, v) for n, v in zip(labels, values, strict=True)])
    check_state(model.model, model.p, y0, shell=model.case.fixed_k is not None)
    check_derived(model, y0)
    if model.case.constraint == "rubber":
        check_no_spin(model, y0)
    return y0


def check_no_spin(model: Model, y0: np.ndarray) -> None:
    """A rubber state lies on (omega, gamma) = 0 (omega = I_Q^-1 M, eq1.6)."""
    y = np.ascontiguousarray(y0, dtype=float)
    r, J, w, gd = np.empty(3), np.empty((3, 3)), np.empty(3), np.empty(3)
    full_kinematics(model.p, y[0:3], y[3:6], r, J, w, gd)
    spin = float(w @ y[3:6])
    if not abs(spin) <= RUBBER_STATE_TOL * max(1.0, float(np.linalg.norm(w))):
        raise InputError(
            f"(omega, gamma) = {spin:.3g}: a rubber body does not spin about the normal, so "
            "its state needs omega = I_Q^-1 M orthogonal to gamma (M = I_Q omega with "
            "(omega, gamma) = 0; I_Q = I + m (r^2 E - r r^T), eq1.6)")


def check_derived(model: Model, y0: np.ndarray, blame: str | None = None) -> None:
    """Finite inputs can still overflow what the run derives from them (m = 1e308 makes
    the contact inertia m R^2 infinite): the field and the energy at the start must be
    finite numbers. `blame`: what to name in the error ('name = value'); by default the
    parameter or state value of largest magnitude."""
    y = np.ascontiguousarray(y0, dtype=float)
    dydt = np.empty_like(y)
    with np.errstate(all="ignore"):
        ok = bool(np.all(np.isfinite(y)))
        if ok:
            st = rhs(model.model, 0.0, y, model.p, dydt)
            energy = Q.integral(Q.ENERGY, model.model, y, model.p)
            # SING_NONFINITE: the kernel met inf or NaN; the other statuses are geometric
            # singularities that check_state reports in its own words
            ok = (st != L.SING_NONFINITE and (st != L.OK or bool(np.all(np.isfinite(dydt))))
                  and math.isfinite(energy))
    if ok:
        return
    if blame is None:
        named = [*model.params.items(), *zip(model.state_labels, y0.tolist(), strict=True)]
        name, value = max(named, key=lambda kv: abs(kv[1]) if math.isfinite(kv[1]) else 0.0)
        blame = f"{name} = {value!r}"
    raise InputError(f"{blame}: too large: the velocities or the energy this run derives "
                     "from it overflow double precision")
