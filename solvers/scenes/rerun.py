"""A teaching scene run again with its sliders moved (catalogue/scenes.yaml `sliders`):
the preset with the new parameter or initial-state values, validated as a preset is,
and every check of the scene evaluated on that new run (POST /api/scenes/{id}/run), so
that the verdict a class sees after moving a slider is measured, never carried over.

    from solvers.scenes.rerun import rerun_json
    rerun_json("rattleback-spin-reversal", {"delta": 1.2})["checks"][0]["passed"]
"""

from __future__ import annotations

import math

from solvers.errors import InputError


def moved(preset, values: dict[str, float]):
    """The preset with `values` (slider name -> value in the slider's units) applied.
    Unknown names, values that are not finite or lie outside a slider's range, and a
    state the case rejects raise InputError; the preset itself never changes."""
    from solvers.scenes.teaching import Scene

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
    try:
        return Scene(**{**preset.model_dump(mode="json"), "scene": decl})
    except ValueError as exc:
        raise InputError(f"scene {preset.id!r} with {values}: {exc}") from None


def rerun_json(scene_id: str, values: dict[str, float]) -> dict:
    """The moved scene's run declaration and every check of it with its plot (the shape
    of GET /api/scenes/{id}/checks/{k}), in the catalogue's order."""
    from solvers.scenes.scene_checks import run_checks
    from solvers.scenes.teaching import load_scenes

    preset = load_scenes()[scene_id]
    scene = moved(preset, values)
    results = run_checks(scene)
    checks = [{**r.to_json(), "caption": c.caption, "index": k, "count": len(scene.checks)}
              for k, (r, c) in enumerate(zip(results, scene.checks, strict=True))]
    return {"id": scene_id, "values": values, "scene": scene.scene.model_dump(mode="json"),
            "checks": checks}
