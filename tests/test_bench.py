"""bench/: every script is a registered benchmark (`rolling bench`, bench/README.md), the
command passes a script its options, and bench/results/ holds small current tables only."""

import re
from pathlib import Path

from typer.testing import CliRunner

from app.cli import BENCHES, QUICK, cli

ROOT = Path(__file__).resolve().parents[1]
BENCH = ROOT / "bench"


def test_every_script_is_registered_and_indexed():
    scripts = {p.name for p in BENCH.glob("*.py")}
    assert len(scripts) <= 20
    assert {script for script, _ in BENCHES.values()} == scripts
    assert set(QUICK) <= set(BENCHES)
    index = (BENCH / "README.md").read_text()
    for name, (script, _) in BENCHES.items():
        assert f"`{name}`" in index and f"`{script}" in index, name


def test_results_are_small_current_tables():
    kept = [p for p in (BENCH / "results").iterdir() if p.name != ".gitignore"
            and "quick" not in p.name]     # --quick runs: ignored by git
    assert kept
    for p in kept:
        assert p.stat().st_size < 1_000_000, p.name
        assert not re.search(r"\.before|\.best\d|\.batch|\.T\d", p.name), p.name


def test_help_lists_every_benchmark():
    out = CliRunner().invoke(cli, ["bench", "--help"], terminal_width=200).output
    for name in BENCHES:
        assert name in out


def test_options_after_the_name_reach_the_script():
    # `-- --help`: the script's own help (its module doc), nothing run
    r = CliRunner().invoke(cli, ["bench", "cold-cli", "--", "--help"])
    assert r.exit_code == 0 and "Cold `rolling simulate`" in r.output
    r = CliRunner().invoke(cli, ["bench", "auto-coverage", "--", "--help"])
    assert r.exit_code == 0 and "--quick" in r.output


def test_unknown_benchmark_and_quick_without_one_are_refused():
    r = CliRunner().invoke(cli, ["bench", "no-such-bench"])
    assert r.exit_code == 2
    r = CliRunner().invoke(cli, ["bench", "cold-start", "--quick"])
    assert r.exit_code == 2 and "no --quick" in r.output
