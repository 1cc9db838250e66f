"""The `rolling` command line: one entry point per job.

Errors in the input print one line `error: ...` on stderr and exit with code 2 (no
traceback, whatever fails); a run that reaches a singularity or its step budget prints what
it computed and exits with 3, and so does a run stopped by --timeout. --json output is
strict JSON: a non-finite number is written as null (as the API does).
"""

import contextlib
import os
import signal
import sys
import threading
from typing import Annotated

import typer

cli = typer.Typer(add_completion=False, no_args_is_help=True, pretty_exceptions_enable=False,
                  help="Rolling bodies on a plane and a sphere (Borisov & Mamaev 2002).")

EXIT_INPUT = 2
EXIT_SINGULAR = 3


def _fail(message: str, code: int = EXIT_INPUT):
    typer.echo(f"error: {message}", err=True)
    raise typer.Exit(code)


def _input_message(e) -> str:
    """An InputError's message, with the flag of this command line that accepts the input
    anyway where there is one (the message itself names no interface's flag)."""
    option = getattr(e, "option", None)
    flag = f" (--{option.replace('_', '-')} studies such input anyway)" if option else ""
    return f"{e}{flag}"


def _check_bounds(request: str, **values) -> None:
    """Options bounded as the API bounds the same fields of its request model
    (app/schemas: "simulate" or "poincare"), refused in the API's words (exit 2)."""
    from app.core.errors import refusal

    if request == "simulate":
        from app.schemas.simulate import SimulateRequest as model
    else:
        from app.schemas.poincare import PoincareRequest as model
    message = refusal(model, {k: v for k, v in values.items() if v is not None})
    if message:
        _fail(message)


def _write_json(obj) -> None:
    from app.services.jobs import dumps

    sys.stdout.write(dumps(obj).decode() + "\n")


TimeoutOpt = Annotated[float | None, typer.Option(
    "--timeout", help="stop after this many seconds of wall time (exit 3; at most a week)")]
# bounds of the inputs that size the machine's work (so that no input ties the machine up
# without end): a week of wall time (a
# larger timer overflows the watchdog's wait), 4 worker processes per core, and the seeds
# the API accepts (app/schemas/poincare.py)
MAX_TIMEOUT_S = 7 * 86400.0
MAX_SEED = 2**32 - 1


def _max_workers() -> int:
    return 4 * (os.cpu_count() or 1)


def _check_workers(n: int | None, zero: str | None = None) -> None:
    """--workers: 1 .. 4 x the cores; 0 only where it has a meaning (`zero`)."""
    if n is None or (n == 0 and zero):
        return
    hi = _max_workers()
    if not 1 <= n <= hi:
        also = f"0 ({zero}) or " if zero else ""
        _fail(f"--workers {n}: must be {also}a number of processes from 1 to {hi} "
              f"(4 x the {os.cpu_count() or 1} cores)")


def _check_seed(seed: int) -> None:
    if not 0 <= seed <= MAX_SEED:
        _fail(f"--seed {seed}: must lie in [0, 2**32 - 1] (as in the API)")


def _check_timeout(seconds: float | None) -> None:
    if seconds is None:
        return
    if not (seconds > 0 and seconds <= MAX_TIMEOUT_S):     # NaN fails both
        _fail(f"--timeout {seconds!r}: must be a positive number of seconds, at most "
              f"{MAX_TIMEOUT_S:g} (a week)")


class _TimedOut(BaseException):
    """Raised in the main thread by --timeout's watchdog (graceful mode), through SIGUSR1:
    not SIGINT, which a process started as a shell's background job ignores, and then
    `_thread.interrupt_main()` does nothing (the sweep then ran its 15 s grace and exited
    hard, leaving the cluster's semaphores to the resource tracker's warning)."""


def _raise_timed_out(signum, frame):
    raise _TimedOut


@contextlib.contextmanager
def _timeout(seconds: float | None, graceful: threading.Event | None = None):
    """Stop the whole process when `seconds` have passed: the compiled kernels run without
    returning to Python, so a watchdog thread ends the process (exit 3) from outside.
    `graceful` (sweep): set once the dask cluster is up; then first interrupt the main
    thread, so that the cluster is shut down by its own `finally` (a process that exits
    under it leaves its semaphores to the resource tracker, which complains on stderr),
    but not before the event (an interrupt inside LocalCluster's start would leave its
    half-made cluster to the tracker); the interrupt is SIGUSR1 (_TimedOut); the hard exit
    follows 15 s after it, or 15 s after the timeout if the cluster never came up."""
    if seconds is None:
        yield
        return
    _check_timeout(seconds)
    done = threading.Event()
    message = f"stopped by --timeout after {seconds:g} s"
    old = signal.signal(signal.SIGUSR1, _raise_timed_out) if graceful is not None else None

    def watch():
        if done.wait(seconds):
            return
        if graceful is not None and graceful.wait(15.0) and not done.is_set():
            import _thread

            _thread.interrupt_main(signal.SIGUSR1)
            if done.wait(15.0):
                return
        if done.is_set():
            return
        sys.stdout.flush()
        sys.stderr.write(f"error: {message}\n")
        sys.stderr.flush()
        os._exit(EXIT_SINGULAR)

    threading.Thread(target=watch, daemon=True).start()
    try:
        yield
    except _TimedOut:
        done.set()
        _fail(message, EXIT_SINGULAR)
    finally:
        done.set()
        if old is not None:
            signal.signal(signal.SIGUSR1, old)


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
    from catalogue.numbering import cite
    from solvers.models.cases import registry

    for cid, c in registry().items():
        opt = " ".join(f"[{k}]" for k in c.optional)
        typer.echo(f"{cid:32s} {cite(c.title)}\n{'':32s} params: {' '.join(c.required)} {opt}")


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
    from solvers import simulate as sim
    from solvers.errors import InputError
    from solvers.models.cases import get_case

    _check_timeout(timeout)
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
        _check_bounds("simulate", t_end=t_end, samples=samples, rtol=rtol, atol=atol,
                      step=step)
        with _timeout(timeout):
            res = sim.simulate(case, params, y0, t_end, method=method, rtol=rtol, atol=atol,
                               samples=samples, project=project,
                               allow_any_inertia=allow_any_inertia, step=step, field=field,
                               precision=precision)
    except InputError as e:
        _fail(_input_message(e))
    if as_json:
        _write_json(res.to_json())
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


@cli.command()
def verify(
    case: Annotated[str | None, typer.Option(help="only this case id")] = None,
    claim: Annotated[str | None, typer.Option(help="only this claim id")] = None,
    as_json: Annotated[bool, typer.Option("--json", help="print a JSON list of records")] = False,
    workers: Annotated[int, typer.Option(help="worker processes (0: one per core)")] = 0,
    timeout: TimeoutOpt = None,
):
    """Check every claim of Tables 1-2 and the text; print the tables with verdict marks."""
    from catalogue.load import load_catalogue
    from solvers.errors import InputError
    from solvers.verify.parallel import verify_parallel

    _check_workers(workers, zero="one per core")
    _check_timeout(timeout)
    if claim is not None:
        known = {cl.id for c in load_catalogue().cases() if case in (None, c.id)
                 for cl in c.claims}
        if claim not in known:
            where = f" of case {case}" if case else ""
            _fail(f"--claim {claim!r}: no such claim{where} (the claim ids: rolling "
                  "verify --json, or GET /api/cases/{id})")
    try:
        with _timeout(timeout):
            records = verify_parallel(case=case, claim=claim, workers=workers)
    except InputError as e:
        _fail(_input_message(e))
    if as_json:
        _write_json(records)
        return
    _verify_tables(records, case)


def _verify_tables(records, only_case):
    from rich.console import Console
    from rich.markup import escape
    from rich.table import Table

    from catalogue.load import load_catalogue
    from catalogue.numbering import cite
    from solvers.verify import marks as vocab
    from solvers.verify.table import cell_id

    con = Console(width=max(Console().width, 160))
    cat = load_catalogue()
    by_claim = {r["claim"]: r for r in records}
    # the same marks, shapes and words as the explorer and /how-we-check (marks.yaml)
    con.print("marks: " + "  ".join(f"{m.shape} {m.name}" for m in vocab.vocabulary()
                                    if m.id != "pending"), markup=False, soft_wrap=True)
    for table in cat.tables():
        cases = [c for c in table.cases if only_case in (None, c.id)]
        if not cases:
            continue
        tab = Table(title=f"{table.caption_plain} "
                    "(cells: the property each states)", show_lines=True)
        tab.add_column("row")
        for c in cases:
            tab.add_column(c.id.split("/", 1)[1], overflow="fold")
        for row in table.rows:
            cells = []
            for c in cases:
                cell = c.cells[row.key]
                rec = by_claim.get(cell_id(c.id, row.key.value))
                plain = cite(cell.plain)      # printed numbers before the cut
                text = plain if len(plain) < 60 else plain[:57] + "..."
                if rec is None:
                    cells.append(escape(text))
                    continue
                m = vocab.by_id()[rec["mark"]]
                cells.append(escape(f"{m.shape} {m.word}: {text}"))
            tab.add_row(row.plain, *cells)
        con.print(tab)
    _verify_summary(con, records)


def _verify_summary(con, records):
    from collections import Counter

    from catalogue.numbering import cite, printed
    from solvers.verify import marks as vocab

    for level in ("cell", "formula"):
        # the project's corrections are records of their own, not claims of the paper
        recs = [r for r in records if r.get("level", "formula") == level
                and r.get("origin") != "project-correction"]
        counts = Counter(r["mark"] for r in recs)
        unit, units = ("cell", "cells") if level == "cell" else ("claim", "claims")
        what = " (properties of table cells)" if level == "cell" else " (printed formulas " \
            "and statements)"
        con.print(f"{units}: {len(recs)}{what}: " + vocab.sentence(
            {k: counts[k] for k in vocab.IDS if counts.get(k)}, unit, units), markup=False)
    con.print(_exact_summary(records))
    quals = Counter(r.get("qualifier") for r in records if r.get("qualifier"))
    if quals:
        con.print("formula qualifiers: " + ", ".join(f"{k}: {v}" for k, v in sorted(
            quals.items())))
    cells = [r for r in records if r.get("level") == "cell"]
    shown = [r for r in cells if r["mark"] != "as-printed"]
    if shown:
        con.print("cells that do not simply hold as printed:")
    for r in shown:
        m = vocab.by_id()[r["mark"]]
        note = f": {cite(r['mark_note'])}" if r.get("mark_note") else ""
        errata = f" (errata: {', '.join(r['errata'])})" if r.get("errata") else ""
        con.print(f"{m.shape} {m.name}: cell {r['claim']}{note}{errata}", markup=False)
    con.print("claims that do not hold as printed, or that a check could not decide "
              "(errata: `rolling errata`):")
    for r in records:
        if r.get("level", "formula") != "formula" or r.get("origin") == "project-correction":
            continue
        if r["mark"] in ("as-printed", "evidence-for", "open", "not-checkable"):
            continue
        res = "n/a" if r["residual"] is None else f"{r['residual']:.2e}"
        num = printed(r["label"]) or r["label"] or ""
        where = f" ({num})" if num else ""
        m = vocab.by_id()[r["mark"]]
        note = cite(r.get("mark_note") or r["message"])
        con.print(f"{m.shape} {m.name}: {r['claim']}{where}: residual {res} — {note}",
                  markup=False)


@cli.command()
def errata(
    as_json: Annotated[bool, typer.Option("--json", help="print errata, conventions and "
                                          "findings as one JSON object")] = False,
    workers: Annotated[int, typer.Option(help="worker processes (0: one per core)")] = 0,
):
    """List the paper's misprints (printed vs corrected form, residuals, exact witness,
    the command that reproduces each), the conventions and the findings."""
    from catalogue.load import load_catalogue
    from solvers.verify import errata as er
    from solvers.verify.parallel import verify_parallel

    _check_workers(workers, zero="one per core")
    cat = load_catalogue()
    records = verify_parallel(workers=workers)
    out = {"errata": er.errata(records, cat), "conventions": er.conventions(records, cat),
           "findings": er.findings(records, cat)}
    if as_json:
        _write_json(out)
        return
    from rich.console import Console

    con = Console(width=max(Console().width, 140))

    def res(x):
        return "n/a" if x is None else f"{x:.2e}"

    con.print(f"[bold]Errata[/bold]: {len(out['errata'])} printed formulas fail; "
              "the project's correction of each holds")
    for e in out["errata"]:
        where = e["number"] or e["where"] or ""
        inh = f" (inherits {e['inherits']})" if e["inherits"] else ""
        con.print(f"✗ [{e['kind']}]{inh} {e['claim']} — {where}"
                  f"{', ' + e['section'] if e['section'] else ''}", markup=False)
        con.print(f"   printed:   {' '.join(e['printed'].split())[:200]}", markup=False)
        con.print(f"   corrected: {e['corrected']}", markup=False)
        if e.get("corrected_display"):
            con.print(f"   display corrected: {e['corrected_display']} — {e['change']}",
                      markup=False)
        con.print(f"   residual printed {res(e['residual_printed'])}, corrected "
                  f"{res(e['residual_corrected'])}", markup=False)
        ex = e.get("exact")
        if ex and ex.get("witness") is not None:
            con.print(f"   exact witness: {ex['witness']}", markup=False)
        con.print(f"   reproduce: {e['reproduce']}", markup=False)
    con.print(f"[bold]Conventions[/bold]: {len(out['conventions'])} printed forms hold "
              "under another convention")
    for e in out["conventions"]:
        con.print(f"✓ {e['claim']} ({e['number'] or e['label']}): {e['convention']}", markup=False)
        con.print(f"   residual under it {res(e['residual_under_convention'])}, with ours "
                  f"{res(e['residual_printed'])}; reproduce: {e['reproduce']}", markup=False)
    con.print(f"[bold]Findings the paper does not have[/bold]: {len(out['findings'])}")
    for e in out["findings"]:
        con.print(f"• [{e['kind']}] {e['title']}", markup=False)
        con.print(f"   {e['finding']}", markup=False)
        num = e["number"] or e["label"]
        con.print(f"   claim {e['claim']} ({num}); reproduce: {e['reproduce']}", markup=False)


def _exact_summary(records) -> str:
    """One line: of the verified formula records, how many are proved symbolically, how
    many certified with a Schwartz-Zippel bound (N and k read from the code), how many
    neither (solvers/verify/exact/report.py gives each one's reason); and how many failing
    records an exact rational witness settles."""
    from solvers.verify.exact.report import exact_counts
    c = exact_counts(records)
    return (f"exact: of {c['verified']} verified formula records, {c['proved']} proved "
            f"symbolically, {c['certified']} certified (Schwartz-Zippel, N = 2^{c['bits']} "
            f"grid values per coordinate, k = {c['k']} points seeded by the claim id), "
            f"{c['neither']} neither; {c['witnessed']} of {c['fails']} failing records settled "
            "exactly (rational witness or certified counter-object)")


@cli.command()
def methods():
    """List the integration methods."""
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


@cli.command()
def serve(
    host: Annotated[str | None, typer.Option(help="address (default 127.0.0.1)")] = None,
    port: Annotated[int | None, typer.Option(help="port (default 8000)")] = None,
    workers: Annotated[int | None, typer.Option(help="worker processes for simulations "
                                                "(default 2)")] = None,
):
    """Start the web explorer (FastAPI + uvicorn) on http://127.0.0.1:8000."""
    import os

    _check_workers(workers)
    if workers is not None:
        os.environ["ROLLING_WORKERS"] = str(workers)
    if host is not None:   # the app derives its Host allow-list from the address it serves
        os.environ["ROLLING_HOST"] = host
    from app.core.config import get_settings

    s = get_settings()
    host, port = host or s.host, port or s.port
    typer.echo(f"rolling-hierarchy explorer on http://{host}:{port}/  (API docs: /docs)")
    from app.core.server import run  # uvicorn with bounds on what a client can hold
    from app.main import STOP_SIGNALS_SEEN

    try:
        run(host, port, log_level=s.log_level)
    except KeyboardInterrupt:
        # Ctrl-C, re-raised by uvicorn once it has shut down: the lifespan has killed the
        # workers and the warm-up (app/main.py), nothing is left to clean up, and the
        # interpreter's own teardown (numba's and LLVM's compiled code) takes seconds more,
        # and the explorer should stop at once. SIGTERM ends the process the same way.
        _interrupted(130)
    if STOP_SIGNALS_SEEN:
        # stopped by a signal whose re-raise did nothing: the process started with SIGINT
        # ignored (a background job of a shell), which uvicorn restores before re-raising
        _interrupted(128 + STOP_SIGNALS_SEEN[0])


def _interrupted(code: int):
    sys.stderr.write("error: interrupted\n")
    sys.stderr.flush()
    sys.stdout.flush()
    os._exit(code)


def _parse_section(text: str) -> float:
    name, sep, value = text.partition("=")
    if name.strip() != "g" or not sep:
        _fail(f"--section {text!r}: expected g=VALUE (the Andoyer-Deprit angle g, radians)")
    try:
        return float(value)
    except ValueError:
        _fail(f"--section {text!r}: {value!r} is not a number")


@cli.command()
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
    from rich.progress import BarColumn, MofNCompleteColumn, Progress, TimeElapsedColumn

    from solvers.errors import InputError
    from solvers.maps.poincare import MapSpec, map_model, starts_for
    from solvers.maps.poincare import poincare as run
    from solvers.models.cases import get_case
    from solvers.simulate import compiled_methods

    _check_seed(seed)
    _check_timeout(timeout)
    _check_bounds("poincare", energy=energy, direction=direction, rtol=rtol, atol=atol)
    if method not in compiled_methods():
        _fail(f"--method {method!r}: choose a compiled method ({', '.join(compiled_methods())})")
    try:
        spec_case = get_case(case)
        params = {**(spec_case.example if example else {}), **_parse_sets(set_)}
        starts = [[float(v) for v in _parse_state(s)] for s in initial] or None
        spec = MapSpec(energy=energy, g0=_parse_section(section), direction=direction,
                       points=points, method=method, rtol=rtol, atol=atol)
        # bad input (a level whose starts overflow, too many trajectories): one line,
        # before a bar is drawn; the map draws the same starts again (the same seed)
        spec.validate()
        starts_for(map_model(case, params, allow_any_inertia=allow_any_inertia), spec,
                   trajectories=trajectories, initial=starts, seed=seed)
        with _timeout(timeout), Progress(
                "[progress.description]{task.description}", BarColumn(),
                MofNCompleteColumn(), TimeElapsedColumn(),
                console=_stderr_console(), transient=as_json) as bar:
            task = bar.add_task("trajectories", total=len(starts) if starts else trajectories)
            res = run(case, params, spec, trajectories=trajectories, initial=starts,
                      seed=seed, allow_any_inertia=allow_any_inertia,
                      progress=lambda done, total: bar.update(task, completed=done,
                                                              total=total))
    except InputError as e:
        _fail(_input_message(e))
    except ValueError as e:
        _fail(str(e))
    out = res.to_json()
    if as_json:
        _write_json(out)
    else:
        _poincare_summary(out)
    if any(t["status"] not in ("ok", "no-return") for t in out["trajectories"]):
        raise typer.Exit(EXIT_SINGULAR)


@cli.command()
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
    from rich.progress import BarColumn, MofNCompleteColumn, Progress, TimeElapsedColumn

    from solvers.errors import InputError
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
        _fail("give exactly one of --vary NAME=v1,v2,... and --energies e1,e2,...")
    _check_workers(workers)     # 0 would start a cluster without workers and wait forever
    _check_seed(seed)
    _check_timeout(timeout)
    try:
        params = {**(get_case(case).example if example else {}), **_parse_sets(set_)}
        kw = {"g0": _parse_section(section), "trajectories": trajectories, "points": points}
        if vary is not None:
            name, sep, vals = vary.partition("=")
            if not sep:
                _fail(f"--vary {vary!r}: expected NAME=v1,v2,...")
            tasks = parameter_tasks(case, params, name.strip(),
                                    [float(v) for v in _parse_state(vals)], energy, **kw)
        else:
            tasks = energy_tasks(case, params, [float(v) for v in _parse_state(energies)],
                                 **kw)
        base = DaskSettings()
        settings = base.model_copy(update={k: v for k, v in
                                           {"workers": workers, "scheduler": scheduler}.items()
                                           if v is not None})
        validate(seeded(tasks, seed))     # bad input: one line, before a bar is drawn
        up = threading.Event()
        with _timeout(timeout, graceful=up), Progress(
                "[progress.description]{task.description}", BarColumn(),
                MofNCompleteColumn(), TimeElapsedColumn(),
                console=_stderr_console(), transient=True) as bar:
            task = bar.add_task("maps", total=len(tasks))
            res = run(tasks, seed=seed, settings=settings,
                      progress=lambda done, total: (up.set(),
                                                    bar.update(task, completed=done)))
    except (InputError, ValueError) as e:
        _fail(str(e))
    if as_json:
        _write_json(res.to_json())
        return
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


def _stderr_console():
    from rich.console import Console

    return Console(stderr=True)


def _poincare_summary(out: dict):
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


# the benchmarks of bench/ (bench/README.md): name -> (script, what it measures); the ones
# in QUICK take --quick (a smoke run whose table goes to a *_quick file, never kept)
BENCHES = {
    "work-precision": ("work_precision.py", "every method vs scipy and heyoka, error against "
                       "cost, 6 cases; writes the front auto reads"),
    "auto-front": ("auto_front.py", "method auto vs heyoka on lean equations at matched "
                   "error"),
    "auto-coverage": ("auto_coverage.py", "whether auto's run meets the requested error over "
                      "random starts"),
    "limit": ("limit.py", "ours vs a hand-written DOP853 and heyoka over many starts (modes: "
              "--work, --extension, --gap, --fronts)"),
    "longrun": ("longrun.py", "T = 1e5: integrals held by projection, drift growth per "
                "method"),
    "ensemble": ("ensemble.py", "compiled ensemble vs thread pool vs Python loop; a map"),
    "batch": ("batch_scaling.py", "batches of initial conditions on 1 and 2 cores"),
    "scenes": ("scenes.py", "each teaching scene's planned model vs the full model"),
    "entry-overhead": ("entry_overhead.py", "the Python cost of a simulate() or integrate() "
                       "call beyond the kernel"),
    "payload": ("payload.py", "serialising a 2000-sample answer (JSON, Arrow) vs "
                "integrating it"),
    "small-compile": ("small_compile.py", "compile time of the small kernels per structure"),
    "warmup": ("warmup_cost.py", "where the cold warm-up's compile time goes"),
    "taylor-compile": ("taylor_compile.py", "a Taylor integrator's compile vs its load from "
                       "the disk cache"),
    "cold-cli": ("cold_cli.py", "a cold `rolling simulate` with warm caches"),
    "cold-start": ("cold_start.py", "a fresh clone to the explorer's first page"),
    "load": ("load.py", "concurrent users against the explorer"),
    "connection-cap": ("connection_cap.py", "what the server's connection cap costs"),
    "exact-cost": ("exact_cost.py", "the exact certificates: fmpq vs Fraction, verify() "
                   "with and without"),
    "paper-figures": ("paper_figures.py", "the paper's 3D point maps recomputed (writes the "
                      "explorer's figure data)"),
    "screenshots": ("screenshots.py", "screenshots of the explorer for docs/screenshots/"),
}
QUICK = ("work-precision", "auto-front", "auto-coverage", "limit", "ensemble", "payload",
         "entry-overhead", "taylor-compile")


@cli.command(context_settings={"allow_extra_args": True, "ignore_unknown_options": True},
             epilog="Benchmarks: " + "; ".join(
                 f"{k}{' [--quick]' if k in QUICK else ''}: {v[1]}"
                 for k, v in BENCHES.items()) + ".")
def bench(
    ctx: typer.Context,
    name: Annotated[str, typer.Argument(help=" | ".join(BENCHES))],
    quick: Annotated[bool, typer.Option("--quick", help="a smoke run of a benchmark that has "
                                        "one (" + ", ".join(QUICK) + ")")] = False,
):
    """Run a benchmark of bench/ in this process (bench/README.md: what each measures, how
    long it takes, where its table goes). Options after the name go to the script, e.g.
    `rolling bench limit -- --extension` or `rolling bench load -- --users 4 --duration 5`
    (`rolling bench NAME -- --help`: the script's own options)."""
    import runpy
    from pathlib import Path

    if name not in BENCHES:
        _fail(f"unknown benchmark {name!r}; choose one of {', '.join(BENCHES)}")
    if quick and name not in QUICK:
        _fail(f"{name} has no --quick; the benchmarks with one: {', '.join(QUICK)}")
    script = Path(__file__).resolve().parent.parent / "bench" / BENCHES[name][0]
    if not script.is_file():
        _fail(f"{script} not found: the benchmarks run from a checkout of the repository")
    saved = sys.argv
    sys.argv = [str(script), *(["--quick"] if quick else []), *ctx.args]
    try:
        runpy.run_path(str(script), run_name="__main__")
    except SystemExit as exc:
        if exc.code not in (0, None):
            raise typer.Exit(int(exc.code) if isinstance(exc.code, int) else 1) from None
    finally:
        sys.argv = saved


def main(argv: list[str] | None = None):
    """The entry point: whatever fails ends as one line on stderr and exit code 2; the
    floating-point warnings of numpy (overflow, invalid value) are not for a person at a
    terminal: what they signal is refused as input or reported in the result."""
    import warnings

    warnings.filterwarnings("ignore", category=RuntimeWarning)
    try:
        cli(args=argv)
    except KeyboardInterrupt:
        sys.stderr.write("error: interrupted\n")
        sys.exit(130)
    except Exception as exc:
        text = " ".join(str(exc).split())[:300] or type(exc).__name__
        sys.stderr.write(f"error: {type(exc).__name__}: {text}\n")
        sys.exit(EXIT_INPUT)


if __name__ == "__main__":
    main()
