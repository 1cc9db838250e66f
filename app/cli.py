"""The `rolling` command line: one entry point per job.

Errors in the input print one line `error: ...` on stderr and exit with code 2 (no
traceback); a run that reaches a singularity prints what it computed and exits with 3.
"""

import json
import sys
from typing import Annotated

import typer

cli = typer.Typer(add_completion=False, no_args_is_help=True, pretty_exceptions_enable=False,
                  help="Rolling bodies on a plane and a sphere (Borisov & Mamaev 2002).")

EXIT_INPUT = 2
EXIT_SINGULAR = 3


def _fail(message: str, code: int = EXIT_INPUT):
    typer.echo(f"error: {message}", err=True)
    raise typer.Exit(code)


def _parse_sets(items: list[str]) -> dict[str, str]:
    params = {}
    for item in items:
        name, sep, value = item.partition("=")
        if not sep or not name.strip():
            _fail(f"--set {item!r}: expected NAME=VALUE")
        params[name.strip()] = value.strip()
    return params


def _parse_state(text: str) -> list[str]:
    return [v.strip() for v in text.replace(" ", ",").split(",") if v.strip()]


@cli.command()
def cases():
    """List the case ids (Tables 1 and 2) with their parameters."""
    from solvers.cases import registry

    for cid, c in registry().items():
        opt = " ".join(f"[{k}]" for k in c.optional)
        typer.echo(f"{cid:32s} {c.title}\n{'':32s} params: {' '.join(c.required)} {opt}")


@cli.command()
def simulate(
    case: Annotated[str, typer.Argument(help="case id, e.g. plane/chaplygin-ball")],
    set_: Annotated[list[str], typer.Option("--set", help="parameter NAME=VALUE")] = [],  # noqa: B006
    state: Annotated[str | None, typer.Option(help="initial state v1,v2,... (M, gamma) "
                                              "or (M, r1, r2)")] = None,
    t_end: Annotated[float | None, typer.Option("--t-end", help="final time")] = None,
    method: Annotated[str, typer.Option(help="integrator (see `rolling methods`)")] = "dop853",
    rtol: Annotated[float, typer.Option(help="relative tolerance")] = 1e-10,
    atol: Annotated[float, typer.Option(help="absolute tolerance")] = 1e-12,
    samples: Annotated[int, typer.Option(help="number of output samples")] = 201,
    project: Annotated[bool, typer.Option("--project", help="project onto the known "
                                          "integrals after every step")] = False,
    example: Annotated[bool, typer.Option("--example", help="start from the case's demo "
                                          "parameters and state (--set overrides)")] = False,
    allow_any_inertia: Annotated[bool, typer.Option("--allow-any-inertia", help="accept "
                                 "moments violating the triangle inequality")] = False,
    as_json: Annotated[bool, typer.Option("--json", help="print one JSON object")] = False,
):
    """Integrate one case and report the state, the invariants and the cost."""
    from solvers.cases import get_case
    from solvers.errors import InputError
    from solvers.simulate import simulate as run

    try:
        spec = get_case(case)
        params = {**(spec.example if example else {}), **_parse_sets(set_)}
        if state is None and not example:
            _fail("--state is required (or --example for the case's demo state)")
        y0 = _parse_state(state) if state is not None else spec.state
        if t_end is None:
            if not example:
                _fail("--t-end is required")
            t_end = 100.0
        res = run(case, params, y0, t_end, method=method, rtol=rtol, atol=atol,
                  samples=samples, project=project, allow_any_inertia=allow_any_inertia)
    except InputError as e:
        _fail(str(e))
    if as_json:
        sys.stdout.write(json.dumps(res.to_json(), allow_nan=False) + "\n")
    else:
        _summary(res)
    if not res.ok:
        typer.echo(f"error: {res.message}", err=True)
        raise typer.Exit(EXIT_SINGULAR)


def _summary(res):
    from rich.console import Console
    from rich.table import Table

    con = Console()
    s = res.stats
    con.print(f"[bold]{res.case}[/bold]  " + " ".join(f"{k}={v:g}" for k, v in res.params.items()))
    con.print(f"status: {res.status}" + (f"  {res.message}" if not res.ok else ""))
    con.print(f"method {s['method']}  rtol {s['rtol']:g}  atol {s['atol']:g}  steps {s['steps']}"
              f"  rhs calls {s['rhs_calls']}  wall {s['wall_s'] * 1e3:.1f} ms"
              f"{'  (projected)' if s['projected'] else ''}")
    if len(res.t):
        tab = Table("t", *res.state_labels)
        for i in sorted({0, len(res.t) // 2, len(res.t) - 1}):
            tab.add_row(f"{res.t[i]:.6g}", *(f"{v:.10g}" for v in res.state[i]))
        con.print(tab)
    inv = Table("invariant", "initial", "final", "max drift (rel.)")
    for name, v in res.invariants.items():
        inv.add_row(name, f"{v[0]:.15g}", f"{v[-1]:.15g}", f"{res.drift(name):.2e}")
    con.print(inv)


@cli.command()
def verify(
    case: Annotated[str | None, typer.Option(help="only this case id")] = None,
    claim: Annotated[str | None, typer.Option(help="only this claim id")] = None,
    as_json: Annotated[bool, typer.Option("--json", help="print a JSON list of records")] = False,
    workers: Annotated[int, typer.Option(help="worker processes (0: one per core)")] = 0,
):
    """Check every claim of Tables 1-2 and the text; print the tables with verdict marks."""
    from solvers.errors import InputError
    from solvers.verify.parallel import verify_parallel

    try:
        records = verify_parallel(case=case, claim=claim, workers=workers)
    except InputError as e:
        _fail(str(e))
    if as_json:
        sys.stdout.write(json.dumps(records, allow_nan=False) + "\n")
        return
    _verify_tables(records, case)


def _verify_tables(records, only_case):
    from collections import Counter

    from rich.console import Console
    from rich.table import Table

    from catalogue.load import load_catalogue
    from solvers.verify.table import MARKS, table_marks

    con = Console(width=max(Console().width, 160))
    cat = load_catalogue()
    for table in cat.tables():
        cases = [c for c in table.cases if only_case in (None, c.id)]
        if not cases:
            continue
        marks = table_marks(table, records)
        tab = Table(title=f"Table {table.number}: {table.caption_plain}", show_lines=True)
        tab.add_column("row")
        for c in cases:
            tab.add_column(c.id.split("/", 1)[1], overflow="fold")
        for row in table.rows:
            cells = []
            for c in cases:
                cell = c.cells[row.key]
                mark = MARKS[marks[c.id][row.key.value]]
                text = cell.plain if len(cell.plain) < 60 else cell.plain[:57] + "..."
                cells.append(f"{mark} {text}" if mark else text)
            tab.add_row(row.plain, *cells)
        con.print(tab)
    counts = Counter(r["verdict"] for r in records)
    con.print("claims: " + str(len(records)) + "  " +
              "  ".join(f"{MARKS[v]} {v}: {counts.get(v, 0)}"
                        for v in ("verified", "fails", "evidence", "unchecked")))
    for r in records:
        if r["verdict"] == "fails":
            res = "n/a" if r["residual"] is None else f"{r['residual']:.2e}"
            con.print(f"✗ {r['claim']} ({r['label'] or ''}): residual {res} — {r['message']}")


@cli.command()
def methods():
    """List the integration methods."""
    from solvers.simulate import SCIPY_METHODS, compiled_methods
    from solvers.tableaux import TABLEAUX

    for name in compiled_methods():
        t = TABLEAUX[name]
        typer.echo(f"{name:14s} compiled explicit Runge-Kutta, order {t.order}, "
                   f"{len(t.c)} stages")
    for name, sp in SCIPY_METHODS.items():
        typer.echo(f"{name:14s} scipy solve_ivp {sp} on the independent NumPy field (reference)")


def main():
    cli()


if __name__ == "__main__":
    main()
