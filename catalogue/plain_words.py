"""The catalogue's conditions in the words a reader of the paper uses.

The data keeps compact values (`I: "I1!=I2!=I3!=I1"`, `S: zero`, `potential: any`) that the
checks read; the pages show each condition as a phrase ("I1 ≠ I2 ≠ I3 ≠ I1", "no gyrostat
(S = 0)", "any potential U(γ)"), never the key: value pair of the data. A free-text
condition (`text`) is shown with printed equation numbers.
"""

from __future__ import annotations

import re

from catalogue.load import load_catalogue
from catalogue.numbering import cite

# the symbol each condition key stands for on the page
SYMBOL = {"lambda_": "λ", "lambda": "λ", "S": "S", "a": "a", "k": "k", "z": "z", "I": "I"}

POTENTIAL = {
    "any": "any potential U(γ)",
    "none": "no potential (U = 0)",
    "brun": "Brun field U = ½ k (Iγ, γ)",
    "gravity": "gravity",
    "axisymmetric": "an axisymmetric potential U(γ3)",
}

GYROSTAT = {"zero": "no gyrostat (S = 0)", "any": "with or without a gyrostat S",
            "axial": "a gyrostat along the symmetry axis, S = (0, 0, S3)"}

INERTIA_ANY = "any tensor of inertia"

_OPS = [("!=", " ≠ "), ("<=", " ≤ "), (">=", " ≥ "), ("=", " = "), ("<", " < "),
        (">", " > ")]
_GREEK = [(r"\bmu\b", "μ"), (r"\blambda\b", "λ")]


def _expression(text: str) -> str:
    """"I1!=I2!=I3!=I1" -> "I1 ≠ I2 ≠ I3 ≠ I1"; "I=mu*E+lambda*m*B" -> "I = μE + λmB"."""
    out = text
    for pat, greek in _GREEK:
        out = re.sub(pat, greek, out)
    out = out.replace("*", "")
    out = re.sub(r"(?<=[A-Za-z0-9μλ)])\+(?=[A-Za-z0-9μλ(])", " + ", out)
    for op, shown in _OPS:
        # "!=" before "=": replace each operator once, never inside an earlier replacement
        out = re.sub(rf"\s*(?<![!<>=≠≤≥]){re.escape(op)}(?!=)\s*", shown, out) \
            if op == "=" else re.sub(rf"\s*{re.escape(op)}\s*", shown, out)
    return re.sub(r"\s+", " ", out).strip()


def phrase(key: str, value) -> str:
    """One condition as the page shows it."""
    v = str(value).strip()
    if key == "text":
        return cite(v) or ""
    if key == "potential":
        return POTENTIAL.get(v, f"potential: {v}")
    if key == "S" and v in GYROSTAT:
        return GYROSTAT[v]
    if key == "I":
        return INERTIA_ANY if v == "any" else _expression(v)
    sym = SYMBOL.get(key, key)
    if v == "any":
        return f"any {sym}"
    if v in ("0", "zero"):
        return f"{sym} = 0"
    if v == "nonzero":
        return f"{sym} ≠ 0"
    if v.startswith("not "):
        return f"{sym} ≠ " + v.removeprefix("not ").replace(" or ", ", ")
    return f"{sym} = {_expression(v)}"


def phrases(conditions: dict | None) -> list[str]:
    """Every set condition, as phrases, in the data's order."""
    return [phrase(k, v) for k, v in (conditions or {}).items()
            if v is not None and str(v).strip() != ""]


_CITE = re.compile(r"\\cite\s*\{([^{}]*)\}")


def _surnames(authors: list[str]) -> str:
    names = [a.replace(".", ". ").split()[-1] for a in authors if a.strip()]
    return ", ".join(names) if len(names) <= 2 else f"{names[0]} et al."


def cite_names(tex: str | None) -> str | None:
    """Printed LaTeX with each `\\cite{key}` naming the authors ("\\cite{Borisov, Mamaev}"):
    the key (`bormam-2`) is the seed's, not the reader's; the seed has no bibliography to
    number the references by. A key whose authors the paper does not name stays a key."""
    if not tex or "\\cite" not in tex:
        return tex

    refs = {r.id: r for r in load_catalogue().references}

    def one(m: re.Match) -> str:
        keys = [k.strip() for k in m.group(1).split(",")]
        shown = [_surnames(refs[k].authors) if k in refs and refs[k].authors else k
                 for k in keys]
        return "\\cite{" + "; ".join(shown) + "}"

    return _CITE.sub(one, tex)


# the integrals a run reports (solvers' integral names) as a reader names them
INVARIANTS = {
    "energy": "energy H",
    "gamma2": "γ² = 1",
    "area": "(M, γ)",
    "M2": "M²",
    "jellett": "Jellett's integral (M, r)",
    "routh": "Routh's integral",
    "unbalanced_F": "F = M² − m r² (M, ω)",
    "borisov_fedorov": "the Borisov–Fedorov integral",
}


def invariant_name(name: str) -> str:
    return INVARIANTS.get(name, name.replace("_", " "))
