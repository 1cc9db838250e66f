"""What every command of `rolling` shares: the exit codes, the one-line errors, the
bounds of the inputs that size the work, --timeout's watchdog, the parsing of NAME=VALUE
and state options."""

import _thread
import contextlib
import os
import signal
import sys
import threading
from typing import Annotated

import typer

# the one Typer app of every command (app.cli registers them on it)
cli = typer.Typer(add_completion=False, no_args_is_help=True, pretty_exceptions_enable=False,
                  help="Rolling bodies on a plane and a sphere (Borisov & Mamaev 2002).")

EXIT_INPUT = 2
EXIT_SINGULAR = 3


def fail(message: str, code: int = EXIT_INPUT):
    typer.echo(f"error: {message}", err=True)
    raise typer.Exit(code)


def input_message(e) -> str:
    """An InputError's message, with the flag of this command line that accepts the input
    anyway where there is one (the message itself names no interface's flag)."""
    option = getattr(e, "option", None)
    flag = f" (--{option.replace('_', '-')} studies such input anyway)" if option else ""
    return f"{e}{flag}"


def check_bounds(request: str, **values) -> None:
    """Options bounded as the API bounds the same fields of its request model, by the
    same types (app.schemas.bounds: "simulate" or "poincare"), refused in the API's words
    (exit 2). Nothing of the solvers is imported: a refusal comes at once."""
    # lazy: pydantic and FastAPI (the API's bounds and words), not at the CLI's start
    from app.core.errors import refusal
    from app.schemas.bounds import PoincareBounds, SimulateBounds

    model = SimulateBounds if request == "simulate" else PoincareBounds
    message = refusal(model, {k: v for k, v in values.items() if v is not None})
    if message:
        fail(message)


def write_json(obj) -> None:
    # lazy: numpy, orjson and FastAPI (the API's JSON encoder), not at the CLI's start
    from app.services.payloads import dumps

    sys.stdout.write(dumps(obj).decode() + "\n")


TimeoutOpt = Annotated[float | None, typer.Option(
    "--timeout", help="stop after this many seconds of wall time (exit 3; at most a week)")]
# bounds of the inputs that size the machine's work (so that no input ties the machine up
# without end): a week of wall time (a
# larger timer overflows the watchdog's wait), 4 worker processes per core, and the seeds
# the API accepts (app/schemas/poincare.py)
MAX_TIMEOUT_S = 7 * 86400.0
MAX_SEED = 2**32 - 1


def max_workers() -> int:
    return 4 * (os.cpu_count() or 1)


def check_workers(n: int | None, zero: str | None = None) -> None:
    """--workers: 1 .. 4 x the cores; 0 only where it has a meaning (`zero`)."""
    if n is None or (n == 0 and zero):
        return
    hi = max_workers()
    if not 1 <= n <= hi:
        also = f"0 ({zero}) or " if zero else ""
        fail(f"--workers {n}: must be {also}a number of processes from 1 to {hi} "
              f"(4 x the {os.cpu_count() or 1} cores)")


def check_seed(seed: int) -> None:
    if not 0 <= seed <= MAX_SEED:
        fail(f"--seed {seed}: must lie in [0, 2**32 - 1] (as in the API)")


def check_timeout(seconds: float | None) -> None:
    if seconds is None:
        return
    if not (seconds > 0 and seconds <= MAX_TIMEOUT_S):     # NaN fails both
        fail(f"--timeout {seconds!r}: must be a positive number of seconds, at most "
              f"{MAX_TIMEOUT_S:g} (a week)")


class _TimedOut(BaseException):
    """Raised in the main thread by --timeout's watchdog (graceful mode), through SIGUSR1:
    not SIGINT, which a process started as a shell's background job ignores, and then
    `_thread.interrupt_main()` does nothing (the sweep then ran its 15 s grace and exited
    hard, leaving the cluster's semaphores to the resource tracker's warning)."""


def _raise_timed_out(signum, frame):
    raise _TimedOut


@contextlib.contextmanager
def time_limit(seconds: float | None, graceful: threading.Event | None = None):
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
    check_timeout(seconds)
    done = threading.Event()
    message = f"stopped by --timeout after {seconds:g} s"
    old = signal.signal(signal.SIGUSR1, _raise_timed_out) if graceful is not None else None

    def watch():
        if done.wait(seconds):
            return
        if graceful is not None and graceful.wait(15.0) and not done.is_set():
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
        fail(message, EXIT_SINGULAR)
    finally:
        done.set()
        if old is not None:
            signal.signal(signal.SIGUSR1, old)


def parse_sets(items: list[str]) -> dict[str, str]:
    params = {}
    for item in items:
        name, sep, value = item.partition("=")
        if not sep or not name.strip():
            fail(f"--set {item!r}: expected NAME=VALUE")
        params[name.strip()] = value.strip()
    return params


def parse_state(text: str) -> list[str]:
    return [v.strip() for v in text.replace(" ", ",").split(",") if v.strip()]


def interrupted(code: int):
    sys.stderr.write("error: interrupted\n")
    sys.stderr.flush()
    sys.stdout.flush()
    os._exit(code)


def stderr_console():
    from rich.console import Console  # lazy: rich, not at the CLI's start

    return Console(stderr=True)
