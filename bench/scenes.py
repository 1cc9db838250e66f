"""Each scene's planned model against the full model: cost ratio at the same accuracy of
what the scene shows.

For every scene below (and the teaching presets of catalogue/scenes.yaml), in this
process: the planner's run (solvers/scenes/planner.py: reduced system where it serves, no
orientation or contact path unless animated, only the plotted samples, no dense output
for a section alone) and the baseline `full_plan` (the animation model with every output,
at the scene's samples), best of REPEATS each, with the same rtol/atol. Accuracy: what
the scene shows (series, gamma's path, section points, frames; drift is itself an error
measure and is compared as is) against the baseline run at rtol 1e-13.

    .venv/bin/python bench/scenes.py          (or: rolling bench scenes)

Writes bench/results/scenes.txt.
"""

from __future__ import annotations

import sys
import time
from pathlib import Path

import numpy as np

from solvers.scenes import planner
from solvers.scenes.scenes import Scene

OUT = Path(__file__).with_name("results")
REPEATS = 5

SCENES = {
    "disk-reduced-series": Scene(case="plane/round-disk", t_end=1000.0, shows={"series"},
                                 series=["gamma3", "K1", "K2", "K3"], samples=401),
    "revolution-on-sphere-series": Scene(case="sphere/body-of-revolution", t_end=1000.0,
                                         shows={"series"}, series=["gamma3", "K1", "K2"],
                                         samples=401),
    "chaplygin-ball-drift": Scene(case="plane/chaplygin-ball", t_end=1000.0,
                                  shows={"drift"}, samples=201),
    "ball-on-sphere-section": Scene(case="sphere/chaplygin-ball", t_end=1e5,
                                    shows={"section"},
                                    section={"variable": "g3", "value": 0.0,
                                             "direction": 1, "crossings": 300}),
    "unbalanced-ball-gamma-path": Scene(case="plane/unbalanced-ball", params={"g": 1.0},
                                        t_end=100.0, shows={"gamma_path"}, samples=2001),
    "flat-base-series": Scene(case="sphere/flat-base", t_end=1000.0, shows={"series"},
                              series=["M1", "M2", "M3"], samples=401),
    "disk-animation": Scene(case="plane/round-disk", t_end=60.0, shows={"animation"},
                            samples=400),
}


def _arrays(run: planner.SceneRun) -> dict[str, np.ndarray]:
    """What the scene shows, flattened to named arrays (drift excluded: see below)."""
    out = {}
    s = run.shown
    for name, v in s.get("series", {}).items():
        out[f"series:{name}"] = np.asarray(v)
    if "gamma_path" in run.scene.shows and "gamma_path" in s:
        out["gamma_path"] = s["gamma_path"]
    if "section" in s:
        out["section"] = s["section"]
    if "animation" in run.scene.shows:
        for k in ("Q", "x_G", "contact"):
            out[f"animation:{k}"] = s["animation"][k]
    return out


def shown_error(run, ref) -> float | None:
    a, b = _arrays(run), _arrays(ref)
    errs = []
    for k, v in a.items():
        w = b[k]
        if v.shape != w.shape:
            return float("inf")
        errs.append(float(np.max(np.abs(v - w))) / max(1.0, float(np.max(np.abs(w)))))
    return max(errs) if errs else None


def best(scene, the_plan):
    runs = [planner.run(scene, the_plan) for _ in range(REPEATS)]
    return min(runs, key=lambda r: r.stats["wall_s"])


def scenes() -> dict[str, Scene]:
    out = dict(SCENES)
    try:
        from solvers.scenes.teaching import load_scenes

        out.update({f"preset:{k}": v.scene for k, v in load_scenes().items()})
    except Exception as exc:  # the presets are a colleague's; the bench runs without them
        print(f"(teaching presets not loaded: {exc!r})")
    return out


def main(argv=None):
    lines, rows = [], []

    def say(s=""):
        print(s, flush=True)
        lines.append(s)

    say(f"best of {REPEATS}; ratio = baseline wall / planned wall; error = max over what "
        "is shown of |x - x_ref| / max(1, |x_ref|), x_ref: baseline at rtol 1e-13")
    say("planned/full ms: the whole view (integration and what is derived for display);"
        " 'integ.': the integration alone")
    say(f"{'scene':38s} {'plan':17s} {'dim':>3s} {'samples':>7s} {'planned ms':>10s} "
        f"{'full ms':>9s} {'ratio':>6s} {'integ.':>6s} {'err planned':>11s} {'err full':>9s}")
    for sid, sc in scenes().items():
        pl, full = planner.plan(sc), planner.full_plan(sc)
        planner.run(sc, pl)                      # warm (numba specialisations)
        planner.run(sc, full)
        a, b = best(sc, pl), best(sc, full)
        ref = planner.run(sc.model_copy(update={"rtol": 1e-13, "atol": 1e-15}), full)
        ea, eb = shown_error(a, ref), shown_error(b, ref)
        ratio = b.stats["wall_s"] / a.stats["wall_s"]
        ratio_int = b.stats["integrate_s"] / a.stats["integrate_s"]
        row = {"scene": sid, "case": sc.case, "shows": sorted(sc.shows), "plan": pl.describe(),
               "planned_wall_s": a.stats["wall_s"], "full_wall_s": b.stats["wall_s"],
               "planned_integrate_s": a.stats["integrate_s"],
               "full_integrate_s": b.stats["integrate_s"], "ratio_integrate": ratio_int,
               "planned_steps": a.stats["steps"], "full_steps": b.stats["steps"],
               "planned_rhs": a.stats["rhs_calls"], "full_rhs": b.stats["rhs_calls"],
               "ratio": ratio, "error_planned": ea, "error_full": eb,
               "status": [a.status, b.status, ref.status]}
        if "drift" in sc.shows:
            row["max_drift_planned"] = max(float(np.max(np.abs(v)))
                                           for v in a.shown["drift"].values())
            row["max_drift_full"] = max(float(np.max(np.abs(v)))
                                        for v in b.shown["drift"].values())
        rows.append(row)
        say(f"{sid:38s} {pl.kind:17s} {L_dim(pl):3d} {pl.samples:7d} "
            f"{a.stats['wall_s'] * 1e3:10.2f} {b.stats['wall_s'] * 1e3:9.2f} {ratio:6.1f} "
            f"{ratio_int:6.1f} "
            f"{fmt(ea):>11s} {fmt(eb):>9s}"
            + (f"  drift {row['max_drift_planned']:.1e} / {row['max_drift_full']:.1e}"
               if "drift" in sc.shows else ""))
    OUT.mkdir(exist_ok=True)
    (OUT / "scenes.txt").write_text("\n".join(lines) + "\n")
    return 0


def fmt(e) -> str:
    return "-" if e is None else f"{e:.1e}"


def L_dim(pl) -> int:
    return pl.describe()["dim"]


if __name__ == "__main__":
    if {"-h", "--help"} & set(sys.argv[1:]):     # what it does, without running it
        print(__doc__)
        sys.exit(0)
    t0 = time.perf_counter()
    code = main(sys.argv[1:])
    print(f"total {time.perf_counter() - t0:.0f} s")
    sys.exit(code)
