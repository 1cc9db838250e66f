"""The symbols of a typeset formula, read from its LaTeX: each letter or Greek letter with its
decorations (bold, bar, tilde, hat) and its subscript, as one token (`\\rho_0`, `K_1`,
`\\mathbf{A}`, `\\bar{\\mathbf{A}}`, `\\gamma_3`). catalogue/notation.yaml defines every token
that a case page shows; the pages link each to its definition (/notation).

Only the math of a formula is read, as the pages typeset it (static/js/latex.js
printedHtml): a text with `$...$` gives its math segments, a sentence without them gives
none. The paper's macros are expanded first (the MACROS of latex.js). Words in `\\text`,
`\\mathrm`, `\\operatorname` and references (`\\eqref`, `\\cite`) are no symbols; time
derivatives (a dot, a prime) are the symbol itself.
"""

from __future__ import annotations

import re

GREEK = {
    "alpha": "α", "beta": "β", "gamma": "γ", "delta": "δ", "epsilon": "ϵ",
    "varepsilon": "ε", "zeta": "ζ", "eta": "η", "theta": "θ", "vartheta": "ϑ", "iota": "ι",
    "kappa": "κ", "lambda": "λ", "mu": "μ", "nu": "ν", "xi": "ξ", "pi": "π", "rho": "ρ",
    "sigma": "σ", "tau": "τ", "upsilon": "υ", "phi": "ϕ", "varphi": "φ", "chi": "χ",
    "psi": "ψ", "omega": "ω", "Gamma": "Γ", "Delta": "Δ", "Theta": "Θ", "Lambda": "Λ",
    "Xi": "Ξ", "Pi": "Π", "Sigma": "Σ", "Phi": "Φ", "Psi": "Ψ", "Omega": "Ω",
}

# the paper's macros (static/js/latex.js MACROS) that name symbols or spell commands
MACROS = {
    "bM": r"\boldsymbol{M}", "bK": r"\boldsymbol{K}", "bS": r"\boldsymbol{S}",
    "br": r"\boldsymbol{r}", "ba": r"\boldsymbol{a}", "bv": r"\boldsymbol{v}",
    "bs": r"\boldsymbol", "gam": r"\gamma", "om": r"\omega", "ta": r"\theta",
    "vfi": r"\varphi", "eps": r"\varepsilon", "dl": r"\delta", "fracs": r"\tfrac",
    "const": r"\mathrm{const}", "ctg": r"\operatorname{ctg}", "arctg": r"\operatorname{arctg}",
    "tr": r"\operatorname{tr}", "grad": r"\operatorname{grad}", "pt": r"\partial",
    "q": r"\quad", "qq": r"\qquad", "x": r"\times", "wh": r"\widehat", "wt": r"\widetilde",
    "ol": r"\overline",
}
# commands whose argument is words or a reference, never a symbol
DROP_ARG = {"text", "mathrm", "operatorname", "eqref", "ref", "cite", "label", "emph",
            "textit", "textbf", "begin", "end", "hbox", "mbox"}
# decorations that make another symbol (bold: the vector or matrix; bar, tilde, hat)
DECOR = {"boldsymbol": "bold", "mathbf": "bold", "bm": "bold", "bar": "bar",
         "overline": "bar", "tilde": "tilde", "widetilde": "tilde", "hat": "hat",
         "widehat": "hat"}
# decorations that keep the symbol: a time derivative
SAME = {"dot", "ddot"}

_TOKEN = re.compile(r"\\([A-Za-z]+)|\\(.)|([A-Za-z])|(\S)", re.S)
_WORDS = re.compile(r"\b[a-z]{3,}\s+[a-z]{2,}\s+[a-z]{3,}\b")
_WORD = re.compile(r"(?<![A-Za-z])[A-Za-z]{4,}")
# operators whose limits are indices, not symbols
LIMITS = {"sum", "prod", "int", "det", "max", "min", "lim"}


def math_segments(src: str, text: bool = False) -> list[str]:
    """The math a page typesets from a printed text (latex.js printedHtml): the `$...$`
    segments of a text, the whole of a formula, nothing of a sentence without math.
    `text`: a table cell, always text with `$...$` (latex.js textHtml)."""
    if "$" in src or text:
        src = src.replace(r"\$", "")
        return [m[1] or m[2] for m in re.finditer(r"\$\$(.+?)\$\$|\$(.+?)\$", src, re.S)]
    return [] if is_prose(src) else [src]


def is_prose(src: str) -> bool:
    """A printed statement without `$...$` that is words, not a formula (latex.js
    isProse): three words in a row, or one word of four letters outside braces and
    commands ("unknown", "S. A. Chaplygin (1897)")."""
    words = re.sub(r"\{[^{}]*\}", " ", re.sub(r"\\[A-Za-z]+", " ", src))
    return bool(_WORDS.search(words) or _WORD.search(words))


def _lex(tex: str) -> list[tuple[str, str]]:
    out: list[tuple[str, str]] = []
    for m in _TOKEN.finditer(tex):
        if m[1]:
            name = m[1]
            if name in MACROS:
                out.extend(_lex(MACROS[name]))
            else:
                out.append(("cmd", name))
        elif m[2]:
            out.append(("sym", m[2]))          # \, \; \{ ...: spacing and delimiters
        elif m[3]:
            out.append(("letter", m[3]))
        else:
            out.append(("char", m[4]))
    return out


class _Parser:
    def __init__(self, toks: list[tuple[str, str]]):
        self.t, self.i, self.found = toks, 0, []

    def peek(self):
        return self.t[self.i] if self.i < len(self.t) else (None, None)

    def take(self):
        tok = self.peek()
        self.i += 1
        return tok

    def skip_group(self) -> None:
        """Skip one argument: a {...} group or a single token."""
        kind, val = self.take()
        if (kind, val) == ("char", "{"):
            depth = 1
            while depth and self.i < len(self.t):
                k, v = self.take()
                depth += (k, v) == ("char", "{")
                depth -= (k, v) == ("char", "}")

    def group_tokens(self) -> list[tuple[str, str]]:
        """One argument's tokens: a {...} group's content or a single token."""
        kind, val = self.take()
        if kind == "cmd" and (val in DECOR or val in SAME):   # \dot\boldsymbol{r}
            return [(kind, val), ("char", "{"), *self.group_tokens(), ("char", "}")]
        if (kind, val) != ("char", "{"):
            return [(kind, val)] if kind else []
        out, depth = [], 1
        while self.i < len(self.t):
            k, v = self.take()
            depth += (k, v) == ("char", "{")
            depth -= (k, v) == ("char", "}")
            if depth == 0:
                break
            out.append((k, v))
        return out

    def run(self, decor: tuple[str, ...] = ()) -> list[str]:
        while self.i < len(self.t):
            kind, val = self.peek()
            if (kind, val) == ("char", "}"):
                return self.found
            self.take()
            if (kind, val) == ("char", "{"):
                self._attach(_Parser(self._rest_of_group()).run(decor))
            elif kind == "cmd" and val == "bf":           # {\bf A}: bold to the group's end
                decor = (*decor, "bold") if "bold" not in decor else decor
            elif kind == "cmd" and val in DROP_ARG:
                self.skip_group()
                if val == "begin" and self.peek() == ("char", "{"):
                    self.skip_group()            # \begin{array}{c}
            elif kind == "cmd" and (val in DECOR or val in SAME):
                inner = self.group_tokens()
                add = (DECOR[val],) if val in DECOR else ()
                sub = _Parser(inner).run(tuple(dict.fromkeys((*decor, *add))))
                self._attach(sub)
            elif kind == "letter" or (kind == "cmd" and val in GREEK):
                self.found.append(self._symbol(val, decor))
            elif kind == "cmd" and val in LIMITS:
                while self.peek() in (("char", "^"), ("char", "_")):
                    self.take()
                    self.skip_group()
            elif (kind, val) in (("char", "^"), ("char", "_")):
                self.found += _Parser(self.group_tokens()).run(())
        return self.found

    def _rest_of_group(self) -> list[tuple[str, str]]:
        self.i -= 1
        return self.group_tokens()

    def _attach(self, inner: list[str]) -> None:
        """A decorated group (\\dot\\gamma_3, \\bar{\\mathbf A}) followed by a subscript:
        the subscript belongs to its one symbol."""
        if len(inner) == 1 and self.peek() == ("char", "_"):
            self.take()
            self.found.append(_with_sub(inner[0], self._sub()))
        else:
            self.found += inner

    def _sub(self) -> str:
        toks = self.group_tokens()
        return "".join(("\\" + v + " ") if k == "cmd" else v for k, v in toks).strip()

    def _symbol(self, base: str, decor: tuple[str, ...]) -> str:
        name = ("\\" + base) if base in GREEK else base
        while self.peek() == ("char", "'"):
            self.take()
        if self.peek() == ("char", "^") and self._power_then_sub():
            self.take()
            self.found += _Parser(self.group_tokens()).run(())   # \gamma^2_3: a power
        sub = self._sub() if self.peek() == ("char", "_") and self.take() else ""
        return canonical(name, decor, sub) + self._label()

    def _power_then_sub(self) -> bool:
        save = self.i
        self.take()
        self.group_tokens()
        after = self.peek()
        self.i = save
        return after == ("char", "_")

    def _label(self) -> str:
        """A superscript that names, not a power: K_1^{p}, K_1^{(part)}."""
        if self.peek() != ("char", "^"):
            return ""
        save = self.i
        self.take()
        toks = self.group_tokens()
        word = "".join(v for _, v in toks)
        if toks and all(k in ("letter", "char") for k, _ in toks) and \
                re.fullmatch(r"\(?[A-Za-z]+\)?", word):
            return f"^{{{word}}}"
        self.i = save
        return ""


def canonical(name: str, decor: tuple[str, ...] = (), sub: str = "") -> str:
    """One token: `\\bar{\\mathbf{A}}`, `K_{1}`, `\\rho_{0}`."""
    s = name
    if "bold" in decor:
        s = f"\\mathbf{{{s}}}"
    for d in ("bar", "tilde", "hat"):
        if d in decor:
            s = f"\\{d}{{{s}}}"
    return f"{s}_{{{sub}}}" if sub else s


def _with_sub(token: str, sub: str) -> str:
    return token if "_{" in token else f"{token}_{{{sub}}}"


def symbols_of_math(tex: str) -> list[str]:
    """The symbol tokens of one math formula, in order, each once."""
    return list(dict.fromkeys(_Parser(_lex(tex)).run()))


def symbols(src: str, text: bool = False) -> list[str]:
    """The symbol tokens of a printed text or formula as a page typesets it (`text`: a
    table cell)."""
    out: list[str] = []
    for seg in math_segments(src, text):
        out += symbols_of_math(seg)
    return list(dict.fromkeys(out))


_ACCENT = {"bar": "\u0304", "tilde": "\u0303", "hat": "\u0302"}


def plain(token: str) -> str:
    """A token in plain letters, for a screen reader's link name: `\\rho_{0}` -> "ρ0",
    `\\bar{\\mathbf{A}}` -> "Ā", `K_{1}^{(part)}` -> "K1(part)"."""
    s = re.sub(r"\\mathbf\{([^{}]*)\}", r"\1", token)
    for name, mark in _ACCENT.items():
        s = re.sub(r"\\" + name + r"\{([^{}]*)\}", lambda m, mark=mark: m[1] + mark, s)
    s = re.sub(r"\\([A-Za-z]+)", lambda m: GREEK.get(m[1], m[1]), s)
    return s.replace("_", "").replace("^", "").replace("{", "").replace("}", "")
