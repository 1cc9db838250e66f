"""The `rolling` command line: one entry point per job, one module per group of commands
(run: cases, simulate, methods; checks: verify, errata; serve; maps: poincare, sweep;
benches: bench; kernels: kernels), registered here in the order `rolling --help` lists them.

Errors in the input print one line `error: ...` on stderr and exit with code 2 (no
traceback, whatever fails); a run that reaches a singularity or its step budget prints what
it computed and exits with 3, and so does a run stopped by --timeout. --json output is
strict JSON: a non-finite number is written as null (as the API does).
"""

import sys
import warnings

from app.cli.benches import BENCHES, QUICK, SETTINGS, bench
from app.cli.checks import errata, exact_summary, verify, verify_tables
from app.cli.common import EXIT_INPUT, EXIT_SINGULAR, cli
from app.cli.kernels import kernels
from app.cli.maps import poincare, sweep
from app.cli.run import cases, methods, simulate
from app.cli.serve import serve

for _command in (cases, simulate, verify, errata, methods, serve, poincare, sweep,
                 kernels):
    cli.command()(_command)
cli.command(**SETTINGS)(bench)

__all__ = [
    "BENCHES",
    "EXIT_INPUT",
    "EXIT_SINGULAR",
    "QUICK",
    "cli",
    "exact_summary",
    "main",
    "verify_tables",
]


def main(argv: list[str] | None = None):
    """The entry point: whatever fails ends as one line on stderr and exit code 2; the
    floating-point warnings of numpy (overflow, invalid value) are not for a person at a
    terminal: what they signal is refused as input or reported in the result."""
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
