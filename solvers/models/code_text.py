"""A module's code as a proof's fingerprint reads it: the syntax tree without docstrings, so
a reworded comment or docstring keeps a stored proof current and any change to the code does
not (solvers/verify/exact/proofs.py, solvers/models/rubber_proofs.py)."""

import ast


def code_text(source: str) -> str:
    """The module's syntax tree without its docstrings (comments are not in the tree)."""
    tree = ast.parse(source)
    for node in ast.walk(tree):
        if isinstance(node, ast.Module | ast.ClassDef | ast.FunctionDef | ast.AsyncFunctionDef):
            body = node.body
            if body and isinstance(body[0], ast.Expr) and isinstance(body[0].value, ast.Constant) \
                    and isinstance(body[0].value.value, str):
                node.body = body[1:] or [ast.Pass()]
    return ast.dump(tree)
