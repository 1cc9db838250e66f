"""The symbols a rubber cell's statement names, read from its two forms: the plain text
(`statement`, ASCII: `Q^(1/2)`, `|M x gamma|^2`, `I~`, `g3` for the third component of
gamma) and the LaTeX the pages typeset (`statement_tex`, text with `$...$` as the cells of
Tables 1 and 2: `$Q^{1/2}$`, `$|\\bM\\times\\bs\\gamma|^2$`, `\\tilde{\\mathbf I}`).

Both forms are read to the same names (SYMBOLS), so that a cell whose LaTeX drops, adds or
swaps a symbol is refused at load time (catalogue/claims.py MarkedCell). Indices and numbers
are not compared, nor letters that are also English words (`a`, as in `R gamma + a e3`).
"""

from __future__ import annotations

import re

# the names compared; `g` and `w` are the plain text's components of gamma and omega
SYMBOLS = frozenset({
    "M", "gamma", "omega", "I", "I~", "m", "r", "k", "R", "Q", "N", "F", "H", "J", "S", "U",
    "P", "T", "e", "f", "v", "d", "eps", "mu", "lambda", "det", "int", "sum", "log", "div"})
ALIASES = {"g": "gamma", "w": "omega", "varepsilon": "eps", "epsilon": "eps"}
_LETTERS = {s for s in SYMBOLS if len(s) == 1} | {a for a in ALIASES if len(a) == 1}

# the paper's macros (static/js/latex.js MACROS) that spell a symbol
_MACROS = {r"\bM": r"\boldsymbol{M}", r"\bS": r"\boldsymbol{S}", r"\br": r"\boldsymbol{r}",
           r"\bs": r"\boldsymbol", r"\gam": r"\gamma", r"\om": r"\omega",
           r"\eps": r"\varepsilon"}
_TILDE = re.compile(r"\\(?:tilde|widetilde|wt)\s*\{?\s*(?:\\mathbf|\\boldsymbol)?\s*\{?\s*"
                    r"([A-Za-z])\s*\}?\s*\}?")
_NAMED = re.compile(r"\\(gamma|omega|mu|lambda|varepsilon|epsilon|det|int|sum|log)(?![A-Za-z])")
_TOKEN = re.compile(r"[A-Za-z]+~?")


def _names(text: str) -> set[str]:
    """The SYMBOLS among the words of `text`: a word that is a symbol, or a short run of
    symbol letters written together (`kR`, `dg3`)."""
    out: set[str] = set()
    for tok in _TOKEN.findall(text):
        tok = ALIASES.get(tok, tok)
        if tok in SYMBOLS:
            out.add(tok)
        elif len(tok) <= 3 and all(c in _LETTERS for c in tok):
            out.update(ALIASES.get(c, c) for c in tok)
    return out


def plain_symbols(plain: str) -> set[str]:
    """The symbols a plain statement names."""
    return _names(plain)


def tex_symbols(tex: str) -> set[str]:
    """The symbols a LaTeX statement names: macros expanded, a tilde read as `X~`, Greek
    letters and operators by their names, environments and other commands dropped."""
    for macro in sorted(_MACROS, key=len, reverse=True):
        tex = re.sub(re.escape(macro) + r"(?![A-Za-z])", lambda _m, s=_MACROS[macro]: s, tex)
    tex = _TILDE.sub(r" \1~ ", tex)
    tex = re.sub(r"\\(?:begin|end)\{[^{}]*\}", " ", tex)
    tex = re.sub(r"\\(?:operatorname|mathrm)\{([^{}]*)\}", r" \1 ", tex)
    tex = _NAMED.sub(r" \1 ", tex)
    tex = re.sub(r"\\[A-Za-z]+", " ", tex)
    return _names(tex)


def ascii_leftovers(tex: str) -> list[str]:
    """What in a LaTeX statement is still plain-ASCII formula: a `^(` exponent, a Greek letter
    spelled out without its backslash, an `x` for the cross product, an `I~`."""
    bad = re.findall(r"\^\(|(?<![\\A-Za-z])(?:gamma|omega|eps|mu)(?![A-Za-z])|\sx\s|I~", tex)
    return bad


def mismatch(plain: str, tex: str) -> str | None:
    """Why the two forms of a statement do not name the same symbols, or None."""
    p, t = plain_symbols(plain), tex_symbols(tex)
    left = ascii_leftovers(tex)
    if "$" not in tex:
        # words only: nothing to typeset, so the two forms are the same words
        return None if tex == plain and not p else (
            "a statement that names symbols sets them in $...$" if p
            else "a statement without math has the same words in both forms")
    if p == t and not left:
        return None
    parts = []
    if p - t:
        parts.append(f"only in the plain form: {sorted(p - t)}")
    if t - p:
        parts.append(f"only in the LaTeX: {sorted(t - p)}")
    if left:
        parts.append(f"plain-ASCII formula left in the LaTeX: {left}")
    return "; ".join(parts)
