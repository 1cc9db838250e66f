"""`rolling cases`, `rolling simulate` and `rolling methods`: the cases of Tables 1-2 and
one integration of a case."""

from typing import Annotated

import typer

from app.cli.common import (
    EXIT_SINGULAR,
    TimeoutOpt,
    check_bounds,
    check_timeout,
    fail,
    input_message,
    parse_sets,
    parse_state,
    time_limit,
    write_json,
)
from solvers.errors import InputError


def cases():
    """List the case ids (Tables 1 and 2) with their parameters."""
    # lazy: the catalogue (yaml) and the cases' models (numba), not at the CLI's start
    from catalogue.numbering import cite
    from solvers.models.cases import registry

    for cid, c in registry().items():
        opt = " ".join(f"[{k}]" for k in c.optional)
        typer.echo(f"{cid:32s} {cite(c.title)}\n{'':32s} params: {' '.join(c.required)} {opt}")


def simulate(
    case: Annotated[str, typer.Argument(help="case id, e.g. plane/chaplygin-ball")],
    set_: Annotated[list[str], typer.Option("--set", help="parameter NAME=VALUE")] = [],  # noqa: B006
    state: Annotated[str | None, typer.Option(help="initial state v1,v2,... (M, gamma) "
                                              "or (M, r1, r2)")] = None,
    t_end: Annotated[float | None, typer.Option("--t-end", help="final time")] = None,
    method: Annotated[str, typer.Option(help="integrator (see `rolling methods`)")] = "dop853",
    rtol: Annotated[float, typer.Option(help="relative tolerance")] = 1e-10,
    atol: Annotated[float, typer.Option(help="absolute tolerance")] = 1e-12,
    step: Annotated[float | None, typer.Option(help="constant step of a symmetric method "
                                               "(gauss4/6/8; required there)")] = None,
    precision: Annotated[str | None, typer.Option(help="method taylor: double, 'long double' "
                                                  "or quad (default: chosen from rtol)")] = None,
    samples: Annotated[int, typer.Option(help="number of output samples")] = 201,
    project: Annotated[bool, typer.Option("--project", help="project onto the known "
                                          "integrals after every step")] = False,
    example: Annotated[bool, typer.Option("--example", help="start from the case's demo "
                                          "parameters and state (--set overrides)")] = False,
    allow_any_inertia: Annotated[bool, typer.Option("--allow-any-inertia", help="accept "
                                 "moments violating the triangle inequality")] = False,
    field: Annotated[str, typer.Option(help="vector field of the compiled Runge-Kutta "
                                       "methods: auto (the case's generated field for a "
                                       "plain run, else the general one: the same numbers "
                                       "whatever is compiled), generated (also with "
                                       "--project, which compiles rk.py on it, a long "
                                       "compile once per structure), general (the "
                                       "reference)")] = "auto",
    as_json: Annotated[bool, typer.Option("--json", help="print one JSON object")] = False,
    timeout: TimeoutOpt = None,
):
    """Integrate one case and report the state, the invariants and the cost."""
    check_timeout(timeout)
    if state is None and not example:
        fail("--state is required (or --example for the case's demo state)")
    if t_end is None:
        if not example:
            fail("--t-end is required")
        t_end = 100.0
    # refused before the solvers (and their compiled kernels) are imported
    check_bounds("simulate", t_end=t_end, samples=samples, rtol=rtol, atol=atol, step=step)
    # lazy: the solvers (numba and the compiled kernels), not at the CLI's start
    from solvers import simulate as sim
    from solvers.models.cases import get_case

    try:
        spec = get_case(case)
        params = {**(spec.example if example else {}), **parse_sets(set_)}
        y0 = parse_state(state) if state is not None else spec.state
        with time_limit(timeout):
            res = sim.simulate(case, params, y0, t_end, method=method, rtol=rtol, atol=atol,
                               samples=samples, project=project,
                               allow_any_inertia=allow_any_inertia, step=step, field=field,
                               precision=precision)
    except InputError as e:
        fail(input_message(e))
    if as_json:
        write_json(res.to_json())
    else:
        _summary(res)
    if not res.ok:
        typer.echo(f"error: {res.message}", err=True)
        raise typer.Exit(EXIT_SINGULAR)


def _summary(res):
    # lazy: rich's tables, not at the CLI's start
    from rich.console import Console
    from rich.table import Table

    con = Console()
    s = res.stats
    con.print(f"[bold]{res.case}[/bold]  " + " ".join(f"{k}={v:g}" for k, v in res.params.items()))
    con.print(f"status: {res.status}" + (f"  {res.message}" if not res.ok else ""))
    knob = f"step {s['step']:g}" if "step" in s else f"rtol {s['rtol']:g}  atol {s['atol']:g}"
    con.print(f"method {s['method']} ({s.get('field', 'general')} field)  {knob}  "
              f"steps {s['steps']}"
              f"  rhs calls {s['rhs_calls']}  wall {s['wall_s'] * 1e3:.1f} ms"
              f"{'  (projected)' if s['projected'] else ''}"
              + (f"  precision {s['precision']}" if "precision" in s else ""))
    if "auto" in s:
        con.print(f"auto chose {s['method']}: {s['auto']['reason']}")
    if len(res.t):
        tab = Table("t", *res.state_labels)
        for i in sorted({0, len(res.t) // 2, len(res.t) - 1}):
            tab.add_row(f"{res.t[i]:.6g}", *(f"{v:.10g}" for v in res.state[i]))
        con.print(tab)
    inv = Table("invariant", "initial", "final", "max drift (rel.)")
    for name, v in res.invariants.items():
        inv.add_row(name, f"{v[0]:.15g}", f"{v[-1]:.15g}", f"{res.drift(name):.2e}")
    con.print(inv)


def methods():
    """List the integration methods."""
    # lazy: the methods' tableaux (numpy, mpmath) and the solvers (numba), not at the CLI's
    # start
    from solvers.integrate.collocation import load
    from solvers.integrate.tableaux import TABLEAUX
    from solvers.simulate import SCIPY_METHODS, compiled_methods, symmetric_methods

    for name in compiled_methods():
        t = TABLEAUX[name]
        typer.echo(f"{name:14s} compiled explicit Runge-Kutta, order {t.order}, "
                   f"{len(t.c)} stages")
    for name in symmetric_methods():
        m = load(name)
        typer.echo(f"{name:14s} compiled Gauss collocation, symmetric, order {m.order}, "
                   f"{m.stages} implicit stages, constant step (--step)")
    typer.echo(f"{'taylor':14s} heyoka's adaptive Taylor integrator on the case's generated "
               "field (optional extra 'taylor'), --precision double | 'long double' | quad")
    typer.echo(f"{'auto':14s} chosen per case and tolerance from the measured "
               "work-precision front (among dop853, vern9, taylor)")
    for name, sp in SCIPY_METHODS.items():
        typer.echo(f"{name:14s} scipy solve_ivp {sp} on the independent NumPy field (reference)")
