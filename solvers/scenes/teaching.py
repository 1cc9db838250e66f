"""Teaching scenes (catalogue/scenes.yaml): presets for a class, validated once.

The YAML is catalogue data; this loader lives beside the scene planner because a preset's
`scene` is the planner's declaration and every preset is checked by building its model, so
the catalogue itself imports no solver.

Each preset is a short explanation for a class, the claim it demonstrates, the paper's
labels, the run itself as the scene planner's declaration (`scene`: a
`solvers.scenes.scenes.Scene` with the case, all its parameters, the initial state, t_end, what
is shown and how many samples / frames), optionally a second body rolled from the same start
beside it (`beside`: the same run on another case, a rubber ball beside a marble one), and
the checks that show the claim on that run
(`checks`, run by solvers.scenes.scene_checks and tests/test_scenes_catalogue.py). The schema is
strict (extra="forbid"); `load_scenes()` also builds every model and validates every state.

    from solvers.scenes.teaching import load_scenes
    load_scenes()["rattleback-spin-reversal"].scene.t_end
"""

from __future__ import annotations

from functools import cache
from typing import Annotated, Literal

import yaml
from pydantic import BaseModel, ConfigDict, Field, model_validator

from catalogue.load import DATA_DIR
from solvers.errors import InputError
from solvers.kernels.integrals import NAMES
from solvers.models.cases import build, get_case, initial_state
from solvers.models.observables import RUBBER
from solvers.scenes.scenes import Scene as SceneDeclaration

PATH = DATA_DIR / "scenes.yaml"


class _Strict(BaseModel):
    model_config = ConfigDict(extra="forbid", frozen=True)


class _Check(_Strict):
    caption: str = Field("", description="plain words under the check's plot on /scenes: "
                         "what to look for and what the numbers mean")


class IntegralsCheck(_Check):
    """The named integrals (solvers/kernels/integrals.py NAMES) stay constant along the
    scene's run: max |F(t) - F(0)| / max(|F(0)|, 1) <= tol."""

    kind: Literal["integrals"]
    names: list[str] = Field(min_length=1)
    tol: float = Field(1e-8, gt=0)


class StaysUpCheck(_Check):
    """A disk that does not fall: sin(theta) = sqrt(g1^2 + g2^2) stays >= min_tilt over
    [0, t_end] (the run reaches t_end; theta is the angle of the axis to the vertical)."""

    kind: Literal["stays_up"]
    min_tilt: float = Field(gt=0, lt=1)


class SpinReversalCheck(_Check):
    """The spin about the vertical, averaged over `window` (to remove the rocking),
    changes sign before time `before`."""

    kind: Literal["spin_reversal"]
    window: float = Field(gt=0)
    before: float = Field(gt=0)


class MapCheck(_Check):
    """On the 3D point map (section g = g0, the scene's own energy) of the scene's state:
    expect "curve": correlation dimension of the points within dim_tol of 1 (two extra
    integrals); "condenses": |x_{n+period} - x_n| falls by at least `factor` from the
    first 100 returns to the last 100 (asymptotic behaviour, no invariant measure)."""

    kind: Literal["map"]
    expect: Literal["curve", "condenses"]
    g0: float = 0.0
    points: int = Field(ge=100, le=20_000)
    dim_tol: float = 0.2
    period: int = Field(1, ge=1)
    factor: float = Field(100.0, gt=1)


class ConservedCheck(_Check):
    """The named integrals as values against time on linear axes (what a class reads: a
    flat line), with the same verdict as `integrals`: max |F(t) - F(0)| / max(|F(0)|, 1)
    <= tol, measured on the plotted values. A name is a kernel integral
    (solvers/kernels/integrals.py NAMES) or a rubber quantity (solvers/models/observables.py
    RUBBER); `run` says whose run: the scene's own, or that of the body rolled beside it."""

    kind: Literal["conserved"]
    names: list[str] = Field(min_length=1)
    tol: float = Field(1e-8, gt=0)
    run: Literal["main", "beside"] = "main"


class NoSpinCheck(_Check):
    """Marble against rubber from the same start: the spin about the normal (omega, gamma)
    of the body beside (rubber) stays within `tol` of zero, while that of the scene's own
    body (marble) leaves zero by at least `marble_min` (both on the plotted values)."""

    kind: Literal["no_spin"]
    tol: float = Field(1e-8, gt=0)
    marble_min: float = Field(gt=0)


Check = Annotated[IntegralsCheck | ConservedCheck | StaysUpCheck | SpinReversalCheck
                  | MapCheck | NoSpinCheck, Field(discriminator="kind")]


class Slider(_Strict):
    """One control of /scenes that changes the physics and runs the scene again: a
    parameter of the case (`param`) or a component of the initial state (`state`, its
    index). The slider moves in the units it shows; the run gets value * factor (degrees
    shown, radians run)."""

    name: str = Field(pattern=r"^[A-Za-z][A-Za-z0-9_]*$")
    label: str = Field(min_length=3, description="plain words, shown beside the slider")
    symbol: str = Field(description="the symbol as TeX (KaTeX typesets it)")
    units: str = Field(description="the units of the value shown")
    param: str | None = None
    state: int | None = Field(None, ge=0, le=5)
    min: float
    max: float
    step: float = Field(gt=0)
    factor: float = Field(1.0, gt=0)

    @model_validator(mode="after")
    def _range(self):
        if (self.param is None) == (self.state is None):
            raise ValueError(f"slider {self.name}: give exactly one of param, state")
        if not self.min < self.max:
            raise ValueError(f"slider {self.name}: min must be below max")
        return self


class Beside(_Strict):
    """A second body rolled beside the scene's own, in the same 3D view's time: the same run
    (parameters, initial state, t_end, frames) on another case (a rubber case beside its
    marble one). `label` names each body under its view."""

    case: str
    label: str = Field(min_length=3, description="the body beside, in plain words")
    main_label: str = Field(min_length=3, description="the scene's own body, in plain words")


class Scene(_Strict):
    id: str = Field(pattern=r"^[a-z0-9]+(-[a-z0-9]+)*$")
    title: str
    explanation: str = Field(min_length=40, description="for a class: what to look at")
    claim: str = Field(min_length=20, description="what the scene demonstrates")
    paper: list[str] = Field(default_factory=list, description="equation / figure labels "
                             "of the paper, or other sources")
    scene: SceneDeclaration = Field(description="the run, as the scene planner declares "
                                    "it (solvers/scenes/scenes.py); params and state in full")
    checks: list[Check] = Field(min_length=1)
    plot: Literal["vertical_spin", "tilt"] | None = Field(
        None, description="the quantity the text promises, plotted against time beside "
        "the animation (the scene response's `series`)")
    sentence: str = Field("", description="the claim in one plain sentence, for the "
                          "presentation mode of /scenes")
    sliders: list[Slider] = Field(default_factory=list, max_length=2, description="what "
                                  "a class may change and run again")
    beside: Beside | None = Field(None, description="a second body rolled from the same "
                                  "start beside the scene's own (marble against rubber)")

    @model_validator(mode="after")
    def _runnable(self):
        sc = self.scene
        try:
            case = get_case(sc.case)
            missing = [k for k in case.required if k not in sc.params]
            if missing or sc.state is None:
                raise InputError(f"give every required parameter ({missing} missing) and "
                                 "the state: a preset does not lean on the case's example")
            initial_state(build(sc.case, sc.params), sc.state)
            if self.beside is not None:
                initial_state(build(self.beside.case, sc.params), sc.state)
        except InputError as exc:
            raise ValueError(f"scene {self.id}: {exc}") from None
        if "animation" not in sc.shows:
            raise ValueError(f"scene {self.id}: a teaching scene plays: shows must "
                             "include animation")
        if self.beside is not None and any(sl.state is not None for sl in self.sliders):
            raise ValueError(f"scene {self.id}: a scene with a body beside takes parameter "
                             "sliders only (its start is kept on the rubber manifold)")
        for sl in self.sliders:
            now = sc.params.get(sl.param) if sl.param else sc.state[sl.state]
            if sl.param and sl.param not in sc.params:
                raise ValueError(f"scene {self.id}: slider {sl.name} changes {sl.param!r}, "
                                 "not a parameter of the scene")
            if not sl.min <= now / sl.factor <= sl.max:
                raise ValueError(f"scene {self.id}: slider {sl.name} starts outside its "
                                 f"range [{sl.min}, {sl.max}]")
        for c in self.checks:
            if isinstance(c, IntegralsCheck | ConservedCheck):
                known = (*NAMES, *RUBBER) if isinstance(c, ConservedCheck) else NAMES
                bad = [n for n in c.names if n not in known]
                if bad:
                    raise ValueError(f"scene {self.id}: unknown integrals {bad}")
            if (isinstance(c, NoSpinCheck) or getattr(c, "run", "main") == "beside") \
                    and self.beside is None:
                raise ValueError(f"scene {self.id}: a {c.kind} check on the body beside "
                                 "needs `beside`")
        return self


class ScenesFile(_Strict):
    scenes: list[Scene] = Field(min_length=6)

    @model_validator(mode="after")
    def _unique(self):
        ids = [s.id for s in self.scenes]
        dup = {i for i in ids if ids.count(i) > 1}
        if dup:
            raise ValueError(f"duplicate scene ids: {sorted(dup)}")
        return self


def parse(raw: dict) -> dict[str, Scene]:
    return {s.id: s for s in ScenesFile(**raw).scenes}


@cache
def load_scenes() -> dict[str, Scene]:
    """id -> Scene, in the file's order (parsed and validated once)."""
    return parse(yaml.safe_load(PATH.read_text()))
