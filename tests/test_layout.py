"""The solvers package is layered and its imports run one way: a module never imports from a
layer above its own (issue 9, "the house in order").

    kernels, errors  <  integrate  <  models  <  simulate, compile_state  <  maps
        <  scenes  <  verify  <  warmup

Every import statement is read from the source (ast), including imports inside functions, so
a lazy import cannot hide an upward dependency."""

import ast
from pathlib import Path

import pytest

SOLVERS = Path(__file__).resolve().parents[1] / "solvers"

LAYER = {
    "kernels": 0,
    "errors": 0,
    "integrate": 1,
    "models": 2,
    "simulate": 3,
    "compile_state": 3,   # what a run needs compiled: it plans with simulate's routes
    "maps": 4,
    "scenes": 5,
    "verify": 6,
    "warmup": 7,
}


def _room(module: str) -> str | None:
    """'solvers.models.cases' -> 'models'; None for what is not in solvers."""
    parts = module.split(".")
    if parts[0] != "solvers" or len(parts) < 2:
        return None
    return parts[1]


def _imports(path: Path) -> list[tuple[int, str]]:
    out = []
    for node in ast.walk(ast.parse(path.read_text())):
        if isinstance(node, ast.ImportFrom) and node.module and node.level == 0:
            out.append((node.lineno, node.module))
            if node.module == "solvers":
                out += [(node.lineno, f"solvers.{a.name}") for a in node.names]
        elif isinstance(node, ast.Import):
            out += [(node.lineno, a.name) for a in node.names]
    return out


MODULES = sorted(p for p in SOLVERS.rglob("*.py"))


def test_every_module_is_in_a_room():
    rooms = {p.relative_to(SOLVERS).parts[0].removesuffix(".py") for p in MODULES}
    assert rooms - {"__init__"} == set(LAYER)


@pytest.mark.parametrize("path", MODULES, ids=lambda p: str(p.relative_to(SOLVERS)))
def test_imports_run_one_way(path):
    own = path.relative_to(SOLVERS).parts[0].removesuffix(".py")
    if own == "__init__":
        return
    upward = [
        f"line {line}: {mod}"
        for line, mod in _imports(path)
        if (room := _room(mod)) is not None and LAYER[room] > LAYER[own]
    ]
    assert not upward, f"{path.name} ({own}) imports from a layer above: {upward}"


def test_the_check_sees_an_upward_import(tmp_path):
    bad = tmp_path / "bad.py"
    bad.write_text("def f():\n    from solvers.scenes.planner import plan\n")
    assert (2, "solvers.scenes.planner") in _imports(bad)
    assert LAYER[_room("solvers.scenes.planner")] > LAYER["models"]
