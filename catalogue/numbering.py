"""The numbers equations and figures carry in the printed paper, derived from its LaTeX.

The seed cites by internal labels (`eq2b-*1`, `ris-*1`, `an-dp`) that a reader holding the
printed paper cannot find; the paper shows "(2.17)" and "Fig. 3". This module emulates how
the journal class (rcdj) numbers them, walking the seed in order (docs/equation-numbers.md):

* `\\section{...}` (not `\\section*`) steps the section counter and resets the equation
  counter; an equation prints as "(section.n)".
* numbered displays: the class macros `\\eq[label]{...}` and `\\eqc[label]{...}` (one number
  for the whole display, however many lines), `\\begin{equation}` (numbered with or without
  a label), `\\begin{align}` / `\\begin{eqnarray}` one number per line unless the line says
  `\\notag` / `\\nonumber`.
* unnumbered displays: `\\eq*{...}`, `\\eqc*{...}`, `$$...$$`, `\\[...\\]`, starred
  environments, and `gathered` / `aligned` inside another display (they add no number).
* figures: `\\fig` and `\\wfig` each step one counter for the whole paper ("Fig. n"); a label
  is the `\\label{...}` inside the figure's caption. `\\cfig`, the picture pinned into
  the corner of a rotated table (inside a zero-size `picture`), carries no caption and no
  number.

tests/test_printed_numbers_latex.py confirms the result by compiling the seed with TeX Live
against a stand-in class (tests/latex/rcdj.cls; its assumptions in docs/equation-numbers.md).

`scripts/printed_numbers.py` runs this on the seed and writes `printed_numbers.yaml`, which
the package reads at run time, so an installed copy does not need the seed.
"""

from __future__ import annotations

import os
import re
from dataclasses import dataclass
from functools import cache
from pathlib import Path

import yaml

SEED_NAME = "000_c616a4a5e747ad23.txt"
DATA = Path(__file__).with_name("printed_numbers.yaml")

_TOKEN = re.compile(
    r"(?P<section>\\section\s*(?P<star>\*)?\s*\{)"
    r"|(?P<eq>\\eqc?(?![A-Za-z])\s*(?P<eqstar>\*)?\s*(?:\[(?P<eqlabel>[^\]]*)\])?\s*\{)"
    r"|(?P<env>\\begin\{(?P<envname>equation|align|eqnarray|gather|multline)(?P<envstar>\*)?\})"
    r"|(?P<fig>\\w?fig(?![A-Za-z]))"
)
_LABEL = re.compile(r"\\label\s*\{([^}]*)\}")
_NOTAG = re.compile(r"\\(notag|nonumber)(?![A-Za-z])")
_COMMENT = re.compile(r"(?<!\\)%.*")


@dataclass(frozen=True)
class Numbered:
    label: str | None   # None: a numbered display the author never referred to
    kind: str           # "equation" | "figure"
    number: str         # "2.17" or "3"
    line: int           # line of the seed where it starts (1-based)

    @property
    def printed(self) -> str:
        return f"({self.number})" if self.kind == "equation" else f"Fig. {self.number}"


def _matching_brace(text: str, start: int) -> int:
    """Index just after the brace group opening at text[start] == '{'."""
    depth = 0
    for i in range(start, len(text)):
        ch = text[i]
        if ch == "\\":
            continue
        if ch == "{" and text[i - 1] != "\\":
            depth += 1
        elif ch == "}" and text[i - 1] != "\\":
            depth -= 1
            if depth == 0:
                return i + 1
    raise ValueError(f"unbalanced braces from offset {start}")


def _top_level_lines(body: str) -> list[str]:
    """The lines of an align-like body split at `\\\\` outside braces."""
    lines, depth, cur, i = [], 0, [], 0
    while i < len(body):
        ch = body[i]
        if ch == "\\" and body[i:i + 2] == "\\\\" and depth == 0:
            lines.append("".join(cur))
            cur, i = [], i + 2
            continue
        if ch == "\\":
            cur.append(body[i:i + 2])
            i += 2
            continue
        depth += ch == "{"
        depth -= ch == "}"
        cur.append(ch)
        i += 1
    lines.append("".join(cur))
    # a trailing `\\` leaves an empty last line that LaTeX does not number
    return [ln for ln in lines if ln.strip() and not re.fullmatch(r"\s*\[[^\]]*\]\s*", ln)]


def _figure_label(text: str, pos: int) -> tuple[str | None, int]:
    """A \\fig / \\wfig call: optional <bb>, the picture {..}, optional caption [..]."""
    i = pos
    m = re.compile(r"\\w?fig\s*(<[^>]*>)?\s*").match(text, i)
    i = m.end()
    if i < len(text) and text[i] == "{":
        i = _matching_brace(text, i)
    rest = re.compile(r"\s*\[").match(text, i)
    if not rest:
        return None, i
    depth, j = 0, rest.end() - 1
    for j in range(rest.end() - 1, len(text)):
        depth += text[j] == "[" or text[j] == "{"
        depth -= text[j] == "]" or text[j] == "}"
        if depth == 0:
            break
    labels = _LABEL.findall(text[i:j])
    return (labels[-1] if labels else None), j + 1


def derive(seed_text: str) -> list[Numbered]:
    """Every numbered equation and figure of the seed, in the order LaTeX numbers them."""
    text = "\n".join(_COMMENT.sub("", ln) for ln in seed_text.splitlines())
    start = text.find("\\begin{document}")
    pos = max(start, 0)
    section, eq, fig = 0, 0, 0
    out: list[Numbered] = []

    def line_of(p: int) -> int:
        return text.count("\n", 0, p) + 1

    while True:
        m = _TOKEN.search(text, pos)
        if m is None:
            break
        if m["section"]:
            if not m["star"]:
                section, eq = section + 1, 0
            pos = m.end()
        elif m["eq"]:
            end = _matching_brace(text, m.end() - 1)
            if not m["eqstar"]:
                eq += 1
                label = (m["eqlabel"] or "").strip() or None
                out.append(Numbered(label, "equation", f"{section}.{eq}", line_of(m.start())))
            pos = end
        elif m["env"]:
            name = m["envname"] + ("*" if m["envstar"] else "")
            close = text.index(f"\\end{{{name}}}", m.end())
            body = text[m.end():close]
            if not m["envstar"]:
                if m["envname"] in ("align", "eqnarray", "gather"):
                    for ln in _top_level_lines(body):
                        if _NOTAG.search(ln):
                            continue
                        eq += 1
                        labels = _LABEL.findall(ln)
                        out.append(Numbered(labels[0] if labels else None, "equation",
                                            f"{section}.{eq}", line_of(m.start())))
                else:  # equation, multline: one number
                    eq += 1
                    labels = _LABEL.findall(body)
                    out.append(Numbered(labels[0] if labels else None, "equation",
                                        f"{section}.{eq}", line_of(m.start())))
            pos = close + len(name) + 6
        else:  # a figure
            label, end = _figure_label(text, m.start())
            fig += 1
            out.append(Numbered(label, "figure", str(fig), line_of(m.start())))
            pos = end
    return out


_EPS_REF = re.compile(r"\\ref\s*\{([^}]*\.eps)\}")


def name_uncaptioned(seed_text: str, items: list[Numbered]) -> list[Numbered]:
    """Give the uncaptioned figures the label the text cites them by.

    In the seed an uncaptioned figure lost its file name (`\\wfig{ }`), which was also the
    label the text cites (`Fig.~\\ref{ris1.eps}`). Each such label goes to the unlabelled
    figure nearest one of its references, closest pairs first; a figure the text never
    cites keeps no label. These are inferred, not read: `inferred` lists them."""
    refs: dict[str, list[int]] = {}
    for i, ln in enumerate(seed_text.splitlines(), start=1):
        for lab in _EPS_REF.findall(ln):
            refs.setdefault(lab, []).append(i)
    free = [k for k, n in enumerate(items) if n.kind == "figure" and n.label is None]
    pairs = sorted((min(abs(items[k].line - r) for r in lines), lab, k)
                   for lab, lines in refs.items() for k in free)
    out, used_labels, used_figs = list(items), set(), set()
    for _, lab, k in pairs:
        if lab in used_labels or k in used_figs:
            continue
        n = items[k]
        out[k] = Numbered(lab, n.kind, n.number, n.line)
        used_labels.add(lab)
        used_figs.add(k)
    return out


def label_map(seed_text: str) -> dict[str, str]:
    """label -> printed number ("(2.17)", "Fig. 3") for every labelled item."""
    out: dict[str, str] = {}
    for n in name_uncaptioned(seed_text, derive(seed_text)):
        if n.label is None:
            continue
        if n.label in out:
            raise ValueError(f"label {n.label!r} is defined twice in the seed")
        out[n.label] = n.printed
    return out


def find_seed(path: str | Path | None = None) -> Path | None:
    """The seed file (the paper's LaTeX): `path` when given, else the setting ROLLING_SEED,
    else None. The repository holds no default location: the tests that read the paper's
    text look for it beside the clone (tests/conftest.py)."""
    if path:
        return Path(path)
    env = os.environ.get("ROLLING_SEED")
    return Path(env) if env else None


@cache
def printed_numbers() -> dict[str, str]:
    """The committed map (printed_numbers.yaml): label -> "(2.17)" / "Fig. 3"."""
    data = yaml.safe_load(DATA.read_text(encoding="utf-8"))
    return {**data["equations"], **data["figures"], **data["figures_inferred"]}


def printed(label: str | None) -> str | None:
    """The printed number of one label; None when the paper prints no number for it."""
    if label is None:
        return None
    nums = printed_numbers()
    # the catalogue also writes the seed's `2-14*` as `eq2-14*`
    return nums.get(label) or nums.get(label.removeprefix("eq").strip())


# a label as it appears in free text: the catalogue's own labels, longest first so that
# `eq2.1/2` wins over `eq2.1`, delimited so `eq2.17` never matches inside `eq2.171`. Labels
# that do not start with "eq" are also written "eq an-dp", "eq2-14*" in the catalogue, and
# figures "Fig. ris-*1": the prefix goes with the label.
@cache
def _label_re() -> re.Pattern:
    labels = sorted(printed_numbers(), key=len, reverse=True)
    alt = "|".join(re.escape(x) for x in labels)
    return re.compile(rf"(?<![A-Za-z0-9.*])(?:eq\.?\s*(?=[a-z0-9]+[-*])|Figs?\.?\s*(?=ris))?"
                      rf"(?P<label>{alt})(?![A-Za-z0-9*]|\.[0-9]|/[0-9])")


def cite(text: str | None) -> str | None:
    """Free text with every internal label replaced by its printed number
    ("eq2.17 and ris-*1" -> "(2.17) and Fig. 3"); a range "eq1.1-eq1.2" -> "(1.1)-(1.2)"."""
    if not text:
        return text
    out = _label_re().sub(lambda m: printed_numbers()[m.group("label")], text)
    # "(eq2.17)" would read "((2.17))"
    return re.sub(r"\((\([0-9]+\.[0-9]+\))\)", r"\1", out)


_REF = re.compile(r"\\(?P<cmd>eqref|ref)\s*\{(?P<label>[^{}]*)\}")


def cite_latex(tex: str | None) -> str | None:
    """Printed LaTeX with `\\eqref{eq2.9}` -> `\\eqref{2.17}` and `\\ref{ris-*1}` -> `\\ref{3}`:
    what the reader of the printed paper sees between the parentheses or after "Fig."."""
    if not tex:
        return tex

    def one(m: re.Match) -> str:
        num = printed(m["label"].strip())
        if num is None:
            return m.group(0)
        return f"\\{m['cmd']}{{{num.strip('()').removeprefix('Fig. ')}}}"

    return _REF.sub(one, tex)
