"""A teaching scene run again with its sliders moved (catalogue/scenes.yaml `sliders`):
the preset with the new parameter or initial-state values, validated as a preset is (a
scene with a body beside keeps its start's omega and gamma, `same_omega`),
and every check of the scene evaluated on that new run (POST /api/scenes/{id}/run), so
that the verdict a class sees after moving a slider is measured, never carried over.

    from solvers.scenes.rerun import rerun_json
    rerun_json("rattleback-spin-reversal", {"delta": 1.2})["checks"][0]["passed"]
"""

from __future__ import annotations

import math

import numpy as np

from solvers.errors import InputError
from solvers.kernels.fields import contact_inertia, full_kinematics
from solvers.models.cases import build
from solvers.models.observables import omega
from solvers.scenes.scene_checks import run_checks
from solvers.scenes.teaching import Scene, load_scenes


def moved(preset, values: dict[str, float]):
    """The preset with `values` (slider name -> value in the slider's units) applied.
    Unknown names, values that are not finite or lie outside a slider's range, and a
    state the case rejects raise InputError; the preset itself never changes."""
    sliders = {s.name: s for s in preset.sliders}
    if not sliders:
        raise InputError(f"scene {preset.id!r} has no sliders")
    unknown = sorted(set(values) - set(sliders))
    if unknown:
        raise InputError(f"unknown sliders {unknown} for scene {preset.id!r}; its sliders: "
                         + ", ".join(sliders))
    decl = preset.scene.model_dump(mode="json")
    for name, v in values.items():
        s = sliders[name]
        if not isinstance(v, int | float) or isinstance(v, bool) or not math.isfinite(v):
            raise InputError(f"slider {name}: {v!r} is not a finite number")
        # a little slack for the browser's rounding of the slider's steps
        eps = 1e-9 * (s.max - s.min)
        if not s.min - eps <= v <= s.max + eps:
            raise InputError(f"slider {name} = {v:g}: outside its range "
                             f"[{s.min:g}, {s.max:g}] {s.units}")
        if s.param is not None:
            decl["params"][s.param] = float(v) * s.factor
        else:
            decl["state"][s.state] = float(v) * s.factor
    if preset.beside is not None:
        decl["state"] = same_omega(preset, decl["params"])
    try:
        return Scene(**{**preset.model_dump(mode="json"), "scene": decl})
    except ValueError as exc:
        raise InputError(f"scene {preset.id!r} with {values}: {exc}") from None


def same_omega(preset, params: dict) -> list[float]:
    """The preset's start with new parameters for a scene with a body beside (marble
    against rubber): gamma and the angular velocity omega of the preset's start kept, so
    (omega, gamma) = 0 still holds (the rubber manifold), and M = I_Q omega under the new
    parameters. Changing only I or m leaves the start's motion, not its momentum, alone."""

    sc = preset.scene
    w = omega(build(sc.case, sc.params), sc.state)[0]
    new = build(sc.case, params)
    g = np.ascontiguousarray(sc.state[3:6], dtype=float)
    r, J, w_, gd, IQ = np.empty(3), np.empty((3, 3)), np.empty(3), np.empty(3), np.empty((3, 3))
    full_kinematics(new.p, np.ascontiguousarray(sc.state[0:3], dtype=float), g, r, J, w_, gd)
    contact_inertia(new.p, r, IQ)
    if not np.all(np.isfinite(w)) or not np.all(np.isfinite(r)):
        raise InputError(f"scene {preset.id!r}: the start is singular with {params}")
    return [*map(float, IQ @ w), *map(float, g)]


def rerun_json(scene_id: str, values: dict[str, float]) -> dict:
    """The moved scene's run declaration and every check of it with its plot (the shape
    of GET /api/scenes/{id}/checks/{k}), in the catalogue's order."""
    preset = load_scenes()[scene_id]
    scene = moved(preset, values)
    results = run_checks(scene)
    checks = [{**r.to_json(), "caption": c.caption, "index": k, "count": len(scene.checks)}
              for k, (r, c) in enumerate(zip(results, scene.checks, strict=True))]
    return {"id": scene_id, "values": values, "scene": scene.scene.model_dump(mode="json"),
            "checks": checks}
