"""`rolling poincare` and `rolling sweep`: Poincare maps in Andoyer-Deprit variables, one
level or a sweep of them on dask."""

import threading
from typing import Annotated

import typer

from app.cli.common import (
    EXIT_SINGULAR,
    TimeoutOpt,
    check_bounds,
    check_seed,
    check_timeout,
    check_workers,
    fail,
    input_message,
    parse_sets,
    parse_state,
    stderr_console,
    time_limit,
    write_json,
)
from solvers.errors import InputError


def _parse_section(text: str) -> float:
    name, sep, value = text.partition("=")
    if name.strip() != "g" or not sep:
        fail(f"--section {text!r}: expected g=VALUE (the Andoyer-Deprit angle g, radians)")
    try:
        return float(value)
    except ValueError:
        fail(f"--section {text!r}: {value!r} is not a number")


def poincare(
    case: Annotated[str, typer.Argument(help="case id with state (M, gamma), e.g. "
                                        "plane/chaplygin-ball")],
    set_: Annotated[list[str], typer.Option("--set", help="parameter NAME=VALUE")] = [],  # noqa: B006
    energy: Annotated[float, typer.Option(help="energy level E0")] = 1.0,
    section: Annotated[str, typer.Option(help="the section g=g0 (radians)")] = "g=0",
    direction: Annotated[int, typer.Option(help="+1: g increasing, -1: decreasing, "
                                           "0: both")] = 1,
    trajectories: Annotated[int, typer.Option(help="trajectories with sampled starts")] = 8,
    points: Annotated[int, typer.Option(help="crossings per trajectory")] = 200,
    initial: Annotated[list[str], typer.Option(help="a start L/G,H/G,l on the section "
                                               "(repeat; replaces sampling)")] = [],  # noqa: B006
    seed: Annotated[int, typer.Option(help="seed of the sampled starts")] = 0,
    method: Annotated[str, typer.Option(help="compiled integrator")] = "dop853",
    rtol: Annotated[float, typer.Option(help="relative tolerance")] = 1e-10,
    atol: Annotated[float, typer.Option(help="absolute tolerance")] = 1e-12,
    example: Annotated[bool, typer.Option("--example", help="the case's demo parameters "
                                          "(--set overrides)")] = False,
    allow_any_inertia: Annotated[bool, typer.Option("--allow-any-inertia")] = False,
    as_json: Annotated[bool, typer.Option("--json", help="print one JSON object")] = False,
    timeout: TimeoutOpt = None,
):
    """3D Poincare map in Andoyer-Deprit variables (L/G, H/G, l) on the level E = E0."""
    check_seed(seed)
    check_timeout(timeout)
    # refused before the solvers (and their compiled kernels) are imported
    check_bounds("poincare", energy=energy, direction=direction, rtol=rtol, atol=atol)
    # lazy: rich's progress bar, not at the CLI's start
    from rich.progress import BarColumn, MofNCompleteColumn, Progress, TimeElapsedColumn

    # lazy: the maps (numba and their compiled kernels), not at the CLI's start
    from solvers.maps.poincare import MapSpec, map_model, starts_for
    from solvers.maps.poincare import poincare as run
    from solvers.models.cases import get_case
    from solvers.simulate import compiled_methods

    if method not in compiled_methods():
        fail(f"--method {method!r}: choose a compiled method ({', '.join(compiled_methods())})")
    try:
        spec_case = get_case(case)
        params = {**(spec_case.example if example else {}), **parse_sets(set_)}
        starts = [[float(v) for v in parse_state(s)] for s in initial] or None
        spec = MapSpec(energy=energy, g0=_parse_section(section), direction=direction,
                       points=points, method=method, rtol=rtol, atol=atol)
        # bad input (a level whose starts overflow, too many trajectories): one line,
        # before a bar is drawn; the map draws the same starts again (the same seed)
        spec.validate()
        starts_for(map_model(case, params, allow_any_inertia=allow_any_inertia), spec,
                   trajectories=trajectories, initial=starts, seed=seed)
        with time_limit(timeout), Progress(
                "[progress.description]{task.description}", BarColumn(),
                MofNCompleteColumn(), TimeElapsedColumn(),
                console=stderr_console(), transient=as_json) as bar:
            task = bar.add_task("trajectories", total=len(starts) if starts else trajectories)
            res = run(case, params, spec, trajectories=trajectories, initial=starts,
                      seed=seed, allow_any_inertia=allow_any_inertia,
                      progress=lambda done, total: bar.update(task, completed=done,
                                                              total=total))
    except InputError as e:
        fail(input_message(e))
    except ValueError as e:
        fail(str(e))
    out = res.to_json()
    if as_json:
        write_json(out)
    else:
        _poincare_summary(out)
    if any(t["status"] not in ("ok", "no-return") for t in out["trajectories"]):
        raise typer.Exit(EXIT_SINGULAR)


def sweep(
    case: Annotated[str, typer.Argument(help="case id with state (M, gamma)")],
    set_: Annotated[list[str], typer.Option("--set", help="parameter NAME=VALUE")] = [],  # noqa: B006
    vary: Annotated[str | None, typer.Option(help="NAME=v1,v2,...: one map per value")] = None,
    energies: Annotated[str | None, typer.Option(help="e1,e2,...: one map per energy "
                                                 "level (a Poincare atlas)")] = None,
    energy: Annotated[float, typer.Option(help="energy level of a --vary sweep")] = 1.0,
    section: Annotated[str, typer.Option(help="the section g=g0 (radians)")] = "g=0",
    trajectories: Annotated[int, typer.Option(help="trajectories per map")] = 4,
    points: Annotated[int, typer.Option(help="crossings per trajectory")] = 200,
    seed: Annotated[int, typer.Option(help="seed of the sweep (every task's starts)")] = 0,
    workers: Annotated[int | None, typer.Option(help="LocalCluster workers (default "
                                                "ROLLING_DASK_WORKERS or 2)")] = None,
    scheduler: Annotated[str | None, typer.Option(help="address of a running dask "
                                                  "scheduler (default ROLLING_DASK_SCHEDULER;"
                                                  " none: a LocalCluster)")] = None,
    example: Annotated[bool, typer.Option("--example", help="the case's demo parameters "
                                          "(--set overrides)")] = False,
    as_json: Annotated[bool, typer.Option("--json", help="print one JSON object")] = False,
    timeout: TimeoutOpt = None,
):
    """Maps over a parameter (--vary) or over energy levels (--energies) on dask."""
    # lazy: rich's progress bar, not at the CLI's start
    from rich.progress import BarColumn, MofNCompleteColumn, Progress, TimeElapsedColumn

    # lazy: the sweeps (numpy, pydantic) and the cases' models (numba), not at the CLI's
    # start
    from solvers.maps.sweeps import (
        DaskSettings,
        energy_tasks,
        parameter_tasks,
        seeded,
        validate,
    )
    from solvers.maps.sweeps import sweep as run
    from solvers.models.cases import get_case

    if (vary is None) == (energies is None):
        fail("give exactly one of --vary NAME=v1,v2,... and --energies e1,e2,...")
    check_workers(workers)     # 0 would start a cluster without workers and wait forever
    check_seed(seed)
    check_timeout(timeout)
    try:
        params = {**(get_case(case).example if example else {}), **parse_sets(set_)}
        kw = {"g0": _parse_section(section), "trajectories": trajectories, "points": points}
        if vary is not None:
            name, sep, vals = vary.partition("=")
            if not sep:
                fail(f"--vary {vary!r}: expected NAME=v1,v2,...")
            tasks = parameter_tasks(case, params, name.strip(),
                                    [float(v) for v in parse_state(vals)], energy, **kw)
        else:
            tasks = energy_tasks(case, params, [float(v) for v in parse_state(energies)],
                                 **kw)
        base = DaskSettings()
        settings = base.model_copy(update={k: v for k, v in
                                           {"workers": workers, "scheduler": scheduler}.items()
                                           if v is not None})
        validate(seeded(tasks, seed))     # bad input: one line, before a bar is drawn
        up = threading.Event()
        with time_limit(timeout, graceful=up), Progress(
                "[progress.description]{task.description}", BarColumn(),
                MofNCompleteColumn(), TimeElapsedColumn(),
                console=stderr_console(), transient=True) as bar:
            task = bar.add_task("maps", total=len(tasks))
            res = run(tasks, seed=seed, settings=settings,
                      progress=lambda done, total: (up.set(),
                                                    bar.update(task, completed=done)))
    except (InputError, ValueError) as e:
        fail(str(e))
    if as_json:
        write_json(res.to_json())
        return
    # lazy: rich's tables, not at the CLI's start
    from rich.console import Console
    from rich.table import Table

    tab = Table("map", "trajectories", "median D2", "worst integral spread", "wall s")
    for r in res.results:
        d2 = [t["D2"] for t in r["trajectories"] if t["D2"] is not None]
        spreads = [v for t in r["trajectories"] for k, v in t["spread"].items() if k != "H/G"]
        tab.add_row(r["label"], str(len(r["trajectories"])),
                    f"{sorted(d2)[len(d2) // 2]:.2f}" if d2 else "-",
                    f"{max(spreads):.1e}" if spreads else "-", f"{r['wall_s']:.2f}")
    con = Console()
    con.print(tab)
    con.print(f"{res.scheduler}: {res.wall_s:.2f} s")


def _poincare_summary(out: dict):
    # lazy: rich's tables, not at the CLI's start
    from rich.console import Console
    from rich.table import Table

    con = Console()
    con.print(f"[bold]{out['case']}[/bold]  E0 = {out['energy']:g}  section g = "
              f"{out['section']['g0']:g} (direction {out['section']['direction']:+d})")
    tab = Table("#", "start L/G, H/G, l", "points", "status", "missed", "spread of integrals")
    for i, t in enumerate(out["trajectories"]):
        x = ", ".join(f"{v:.4f}" for v in t["initial"])
        spread = "  ".join(f"{k} {v:.1e}" for k, v in t["spread"].items())
        tab.add_row(str(i), x, str(len(t["points"])), t["status"],
                    str(t["check"].get("missed", "-")), spread)
    con.print(tab)
