"""Report on the project's import graph, read with ast (nothing is imported).

It counts the imports of project modules made inside functions, lists the
imports inside functions (of any module) that give no `# lazy:` reason, the
import circles among project modules (module level and inside functions
alike, since a circle hidden in a function is still a circle), the
underscore names one module imports from another, and the files of
solvers/, app/ and catalogue/ over the line limit (Python and the explorer's
JavaScript). `python scripts/import_report.py` prints it (`--unexplained` also lists
the imports without a reason); `--json` gives the same as JSON. tests/test_layers.py
uses the functions here.
"""

from __future__ import annotations

import ast
import json
import re
import sys
from collections.abc import Iterator
from dataclasses import dataclass
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
PACKAGES = ("solvers", "app", "catalogue")
LINE_LIMIT = 500
# a reason: "# lazy:" followed by words (what heavy import it keeps out, of what)
LAZY = re.compile(r"#\s*lazy:\s*\S")


@dataclass(frozen=True)
class Import:
    """One import statement's target, seen from the module that makes it."""

    source: str  # importing module, dotted
    target: str  # imported project module, dotted
    names: tuple[str, ...]  # names taken with `from target import ...`
    in_function: bool
    line: int


def module_name(path: Path) -> str:
    parts = list(path.relative_to(ROOT).with_suffix("").parts)
    if parts[-1] == "__init__":
        parts.pop()
    return ".".join(parts)


def project_files() -> Iterator[Path]:
    for package in PACKAGES:
        yield from sorted((ROOT / package).rglob("*.py"))


def _resolve(module: str, is_package: bool, node: ast.ImportFrom) -> str:
    if node.level == 0:
        return node.module or ""
    base = module.split(".")
    if not is_package:
        base = base[:-1]
    if node.level > 1:
        base = base[: len(base) - (node.level - 1)]
    return ".".join([*base, node.module] if node.module else base)


def _in_project(name: str) -> bool:
    return name.split(".")[0] in PACKAGES


def imports_of(path: Path, modules: set[str]) -> list[Import]:
    """The project imports of one file, each marked as inside a function or not."""
    module = module_name(path)
    is_package = path.name == "__init__.py"
    tree = ast.parse(path.read_text(encoding="utf-8"), filename=str(path))
    found: list[Import] = []

    def visit(node: ast.AST, in_function: bool) -> None:
        for child in ast.iter_child_nodes(node):
            nested = in_function or isinstance(
                child, ast.FunctionDef | ast.AsyncFunctionDef | ast.Lambda
            )
            if isinstance(child, ast.Import):
                for alias in child.names:
                    if _in_project(alias.name):
                        found.append(Import(module, alias.name, (), in_function, child.lineno))
            elif isinstance(child, ast.ImportFrom):
                target = _resolve(module, is_package, child)
                if not _in_project(target):
                    continue
                plain: list[str] = []
                for alias in child.names:
                    # `from package import submodule` imports the submodule
                    sub = f"{target}.{alias.name}"
                    if sub in modules:
                        found.append(Import(module, sub, (), in_function, child.lineno))
                    else:
                        plain.append(alias.name)
                if plain:
                    found.append(Import(module, target, tuple(plain), in_function, child.lineno))
            visit(child, nested)

    visit(tree, False)
    return found


@dataclass(frozen=True)
class FunctionImport:
    """One import statement (of any module) made inside a function."""

    source: str  # importing module, dotted
    line: int
    text: str  # the statement's first line, stripped
    reason: bool  # a `# lazy:` comment explains it


def _statements(tree: ast.AST) -> Iterator[tuple[ast.Import | ast.ImportFrom, bool]]:
    """Every import statement of a module, with whether it sits inside a function."""

    def visit(node: ast.AST, in_function: bool) -> Iterator[tuple[ast.stmt, bool]]:
        for child in ast.iter_child_nodes(node):
            if isinstance(child, ast.Import | ast.ImportFrom):
                yield child, in_function
            nested = in_function or isinstance(
                child, ast.FunctionDef | ast.AsyncFunctionDef | ast.Lambda
            )
            yield from visit(child, nested)

    yield from visit(tree, False)


def function_imports_in(source: str, module: str = "<source>") -> list[FunctionImport]:
    """The imports inside functions of one module's source, each marked with whether it
    carries a `# lazy:` reason: on one of the statement's own lines, or in the comment
    line(s) directly above it, where one comment covers the run of consecutive import
    lines below it."""
    lines = source.splitlines()
    tree = ast.parse(source)
    statements = list(_statements(tree))
    import_lines: set[int] = set()
    for node, _ in statements:
        import_lines.update(range(node.lineno, (node.end_lineno or node.lineno) + 1))

    def explained(node: ast.stmt) -> bool:
        own = lines[node.lineno - 1:(node.end_lineno or node.lineno)]
        if any(LAZY.search(line) for line in own):
            return True
        n = node.lineno - 1  # 1-based number of the line above
        while n >= 1:
            text = lines[n - 1].strip()
            if text.startswith("#"):
                if LAZY.match(text):
                    return True
            elif n not in import_lines:
                return False
            n -= 1
        return False

    return [FunctionImport(module, node.lineno, lines[node.lineno - 1].strip(), explained(node))
            for node, in_function in statements if in_function]


def function_imports() -> list[FunctionImport]:
    """The imports inside functions (any module) across solvers/, app/ and catalogue/."""
    out: list[FunctionImport] = []
    for path in project_files():
        out.extend(function_imports_in(path.read_text(encoding="utf-8"), module_name(path)))
    return out


def unexplained_imports() -> list[FunctionImport]:
    """The imports inside functions that give no `# lazy:` reason."""
    return [i for i in function_imports() if not i.reason]


def private_attributes(path: Path, modules: set[str]) -> list[tuple[str, str, str]]:
    """(module, imported module, name) for each `alias._name` read in a file, where alias
    names a project module it imports (`import a.b as m`, `from a import b`)."""
    module = module_name(path)
    is_package = path.name == "__init__.py"
    tree = ast.parse(path.read_text(encoding="utf-8"), filename=str(path))
    aliases: dict[str, str] = {}
    for node in ast.walk(tree):
        if isinstance(node, ast.Import):
            for a in node.names:
                if a.name in modules and a.asname:
                    aliases[a.asname] = a.name
        elif isinstance(node, ast.ImportFrom):
            target = _resolve(module, is_package, node)
            for a in node.names:
                if f"{target}.{a.name}" in modules:
                    aliases[a.asname or a.name] = f"{target}.{a.name}"
    out = []
    for node in ast.walk(tree):
        if (isinstance(node, ast.Attribute) and isinstance(node.value, ast.Name)
                and node.value.id in aliases and node.attr.startswith("_")
                and not node.attr.startswith("__") and aliases[node.value.id] != module):
            out.append((module, aliases[node.value.id], node.attr))
    return out


def all_imports() -> list[Import]:
    files = list(project_files())
    modules = {module_name(p) for p in files}
    out: list[Import] = []
    for path in files:
        out.extend(imports_of(path, modules))
    return out


def _owner(target: str, modules: set[str]) -> str:
    """The project module an import lands in (a dotted name may overshoot)."""
    while target and target not in modules:
        target = target.rpartition(".")[0]
    return target


def graph(imports: list[Import], modules: set[str]) -> dict[str, set[str]]:
    edges: dict[str, set[str]] = {m: set() for m in modules}
    for imp in imports:
        target = _owner(imp.target, modules)
        if target and target != imp.source:
            edges[imp.source].add(target)
    return edges


def circles(edges: dict[str, set[str]]) -> list[list[str]]:
    """Strongly connected components of more than one module (Tarjan)."""
    index: dict[str, int] = {}
    low: dict[str, int] = {}
    stack: list[str] = []
    on_stack: set[str] = set()
    result: list[list[str]] = []
    counter = 0
    sys.setrecursionlimit(max(10000, sys.getrecursionlimit()))

    def strong(v: str) -> None:
        nonlocal counter
        index[v] = low[v] = counter
        counter += 1
        stack.append(v)
        on_stack.add(v)
        for w in sorted(edges.get(v, ())):
            if w not in index:
                strong(w)
                low[v] = min(low[v], low[w])
            elif w in on_stack:
                low[v] = min(low[v], index[w])
        if low[v] == index[v]:
            component = []
            while True:
                w = stack.pop()
                on_stack.discard(w)
                component.append(w)
                if w == v:
                    break
            if len(component) > 1:
                result.append(sorted(component))

    for v in sorted(edges):
        if v not in index:
            strong(v)
    return sorted(result)


def underscore_imports(imports: list[Import],
                       attributes: bool = True) -> list[tuple[str, str, str]]:
    """(importer, module, name) for each private name taken from another module, imported
    by name or read as an attribute of the imported module."""
    out = []
    if attributes:
        files = list(project_files())
        modules = {module_name(p) for p in files}
        for path in files:
            out.extend(private_attributes(path, modules))
    for imp in imports:
        for name in imp.names:
            if name.startswith("_") and not name.startswith("__"):
                out.append((imp.source, imp.target, name))
    return sorted(set(out))


def long_files(limit: int = LINE_LIMIT) -> list[tuple[str, int]]:
    out = []
    for package in PACKAGES:
        for path in sorted((ROOT / package).rglob("*")):
            if path.suffix not in (".py", ".js") or "vendor" in path.parts:
                continue
            n = len(path.read_text(encoding="utf-8").splitlines())
            if n > limit:
                out.append((str(path.relative_to(ROOT)), n))
    return out


def report() -> dict:
    imports = all_imports()
    modules = {module_name(p) for p in project_files()}
    in_function = [i for i in imports if i.in_function]
    per_file: dict[str, int] = {}
    for imp in in_function:
        per_file[imp.source] = per_file.get(imp.source, 0) + 1
    inside = function_imports()
    unexplained = [i for i in inside if not i.reason]
    unexplained_by_package: dict[str, int] = {package: 0 for package in PACKAGES}
    for imp in unexplained:
        unexplained_by_package[imp.source.split(".")[0]] += 1
    return {
        "imports_in_functions_any_module": len(inside),
        "imports_in_functions_without_reason": len(unexplained),
        "imports_in_functions_without_reason_by_package": unexplained_by_package,
        "imports_in_functions_without_reason_list": [
            [i.source, i.line, i.text] for i in unexplained],
        "imports_in_functions": len(in_function),
        "imports_in_functions_by_module": dict(sorted(per_file.items(), key=lambda kv: -kv[1])),
        "circles": circles(graph(imports, modules)),
        "underscore_imports": [list(t) for t in underscore_imports(imports)],
        "files_over_limit": [list(t) for t in long_files()],
    }


def main(argv: list[str]) -> int:
    data = report()
    if "--json" in argv:
        print(json.dumps(data, indent=1))
        return 0
    print(f"imports inside functions (any module): {data['imports_in_functions_any_module']}")
    print("imports inside functions without a reason: "
          f"{data['imports_in_functions_without_reason']}")
    for package, n in data["imports_in_functions_without_reason_by_package"].items():
        print(f"  {n:4d}  {package}/")
    if "--unexplained" in argv:
        for source, line, text in data["imports_in_functions_without_reason_list"]:
            print(f"    {source}:{line}  {text}")
    print(f"imports of project modules inside functions: {data['imports_in_functions']}")
    for module, n in list(data["imports_in_functions_by_module"].items())[:15]:
        print(f"  {n:4d}  {module}")
    print(f"import circles: {len(data['circles'])}")
    for circle in data["circles"]:
        print("  " + " <-> ".join(circle))
    print(f"underscore names imported across modules: {len(data['underscore_imports'])}")
    for source, target, name in data["underscore_imports"]:
        print(f"  {source} <- {target}.{name}")
    print(f"files over {LINE_LIMIT} lines: {len(data['files_over_limit'])}")
    for path, n in data["files_over_limit"]:
        print(f"  {n:5d}  {path}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
