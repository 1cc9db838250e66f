"""`rolling bench NAME`: a benchmark script of bench/ run in this process."""

import runpy
import sys
from pathlib import Path
from typing import Annotated

import typer

from app.cli.common import fail

# the benchmarks of bench/ (bench/README.md): name -> (script, what it measures); the ones
# in QUICK take --quick (a smoke run whose table goes to a *_quick file, never kept)
BENCHES = {
    "work-precision": ("work_precision.py", "every method vs scipy and heyoka, error against "
                       "cost, 6 cases; writes the front auto reads"),
    "auto-starts": ("auto_starts.py", "method auto over 20 starts per case: its cost against "
                    "the cheapest single run and heyoka-lean at matched error, its coverage; "
                    "writes the choice data auto reads"),
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
QUICK = ("work-precision", "auto-coverage", "limit", "ensemble", "payload",
         "entry-overhead", "taylor-compile")


# the command's settings (app.cli registers it with them): the script's own options
# pass through, and the epilog lists the benchmarks
SETTINGS = {"context_settings": {"allow_extra_args": True, "ignore_unknown_options": True},
            "epilog": "Benchmarks: " + "; ".join(
                f"{k}{' [--quick]' if k in QUICK else ''}: {v[1]}"
                for k, v in BENCHES.items()) + "."}


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
    if name not in BENCHES:
        fail(f"unknown benchmark {name!r}; choose one of {', '.join(BENCHES)}")
    if quick and name not in QUICK:
        fail(f"{name} has no --quick; the benchmarks with one: {', '.join(QUICK)}")
    script = Path(__file__).resolve().parents[2] / "bench" / BENCHES[name][0]
    if not script.is_file():
        fail(f"{script} not found: the benchmarks run from a checkout of the repository")
    saved = sys.argv
    sys.argv = [str(script), *(["--quick"] if quick else []), *ctx.args]
    try:
        runpy.run_path(str(script), run_name="__main__")
    except SystemExit as exc:
        if exc.code not in (0, None):
            raise typer.Exit(int(exc.code) if isinstance(exc.code, int) else 1) from None
    finally:
        sys.argv = saved
