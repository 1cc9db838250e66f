"""`rolling kernels`: which compiled kernels a run of a case needs and whether they are
compiled on this machine (solvers/compile_state.py: plan, is_compiled), and with --compile
compiles the missing ones."""

from typing import Annotated

import typer

from app.cli.common import fail, input_message, parse_sets
from solvers.errors import InputError


def kernels(
    case: Annotated[str, typer.Argument(help="case id, e.g. plane/chaplygin-ball")],
    set_: Annotated[list[str], typer.Option("--set", help="parameter NAME=VALUE (over the "
                                            "case's demo parameters)")] = [],  # noqa: B006
    method: Annotated[str, typer.Option(help="integrator (see `rolling methods`)")] = "dop853",
    rtol: Annotated[float, typer.Option(help="relative tolerance")] = 1e-10,
    t_end: Annotated[float, typer.Option("--t-end", help="final time (taylor and auto "
                                         "compile for the run's length)")] = 100.0,
    step: Annotated[float | None, typer.Option(help="constant step")] = None,
    precision: Annotated[str | None, typer.Option(help="method taylor's precision")] = None,
    project: Annotated[bool, typer.Option("--project", help="a projected run")] = False,
    field: Annotated[str, typer.Option(help="auto, generated or general (as simulate)")] = "auto",
    compile_: Annotated[bool, typer.Option("--compile", help="compile what is not compiled "
                                           "(seconds to minutes per kernel)")] = False,
):
    """List the kernels a run of the case needs, compiled or not (--compile: compile them)."""
    # lazy: the solvers (numba and the compiled kernels), not at the CLI's start
    from solvers import compile_state
    from solvers.models.cases import get_case

    try:
        spec = get_case(case)
        req = compile_state.request(case, {**spec.example, **parse_sets(set_)}, spec.state,
                                    method=method, rtol=rtol, t_end=t_end, step=step,
                                    precision=precision, project=project, field=field)
        keys = compile_state.plan(req)
    except InputError as e:
        fail(input_message(e))
    todo = [k for k in keys if not compile_state.is_compiled(k)]
    if compile_ and todo:
        compile_state.compile(todo, req)
    for k in keys:
        state = "compiled" if compile_state.is_compiled(k) else "not compiled"
        typer.echo(f"{state:13s} {' '.join(map(str, k))}")
    if compile_ and any(not compile_state.is_compiled(k) for k in keys):
        fail("some kernels did not compile: run `rolling simulate` with the same options "
             "to see why")
