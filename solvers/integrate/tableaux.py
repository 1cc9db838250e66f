"""Explicit Runge-Kutta methods as data: a method is its Butcher tableau.

The coefficients live in YAML files beside this module (`solvers/integrate/tableaux/<name>.yaml`),
one per method, as the published decimals or rationals written as *strings*, 1-based and
sparse as in the papers (a_ij, b_i, c_i). Why YAML and strings: the data file is the
registry (CONVENTIONS.md), it keeps every published digit (a YAML float would be rounded
to 17 digits on load), and it holds no code. Each string is parsed exactly to a
`Fraction`; `load_exact` keeps those rationals (the tests check the order conditions in
extended precision with them) and `load` rounds each one once, correctly, to float64.

A `ButcherTableau` checks its own consistency on construction (diffrax style). The
stages are ordered: the `s` stages of a step first, then the stages only needed by the
dense output. Stage `new_stage` is always f(t + h, y_{n+1}) (row of A equal to b, c = 1):
the last stage of a FSAL method, or the first extra stage otherwise; the kernel reuses it
as the first stage of the next step. Dense output is stored in one form for every method,
y(t + theta h) = y_n + h sum_i b_i(theta) k_i with b_i(theta) = sum_j P[i, j] theta^(j+1);
DOP853's Hairer form is converted into it exactly on load, and so is the Chebyshev form
the kernel evaluates (`dense_cheb`, see `_chebyshev`).
"""

import math
from collections.abc import Mapping
from dataclasses import dataclass
from fractions import Fraction
from functools import cache
from pathlib import Path

import numpy as np
import yaml

DATA_DIR = Path(__file__).with_name("tableaux")
METHODS = ("dop853", "vern9", "rk45")
ERROR_ESTIMATES = ("embedded", "dop853")   # index = code passed to the kernel
_KEYS = {"name", "reference", "order", "stages", "fsal", "new_stage", "error_estimate",
         "error_order", "c", "A", "b", "embedded", "dense"}
_TOL = 1e-14


@dataclass(frozen=True, eq=False)
class ButcherTableau:
    """An explicit RK method with embedded error estimate(s) and optional dense output.

    Arrays are float64 (from `load`) or object arrays of `Fraction` (from `load_exact`).
    """

    name: str
    order: int
    error_order: int          # order q of the error estimate: it behaves like h^(q+1)
    c: np.ndarray             # (S,) nodes of all stages
    A: np.ndarray             # (S, S) strictly lower triangular
    b: np.ndarray             # (s,) weights of the step
    b_hat: np.ndarray         # (m, s) embedded weights, one row per embedded formula
    b_hat_order: tuple        # (m,) their orders
    e: np.ndarray             # (m, s) error weights b - b_hat, each rounded once
    error_estimate: str       # "embedded": h |sum e_i k_i|; "dop853": Hairer's combination
    fsal: bool
    new_stage: int            # 0-based index of the stage f(t + h, y_{n+1})
    dense: np.ndarray | None = None   # (S, d) polynomial weights, or None
    dense_cheb: np.ndarray | None = None  # (S, d + 1) the same in Chebyshev form
    dense_order: int = 0
    reference: str = ""

    def __post_init__(self):
        S, s = len(self.c), len(self.b)
        _require(self.A.shape == (S, S), "A must be S x S with S = len(c)")
        _require(s <= S and self.b_hat.shape == (len(self.b_hat_order), s),
                 "b_hat must be (number of embedded formulas) x len(b)")
        _require(self.error_estimate in ERROR_ESTIMATES, "unknown error estimate")
        _require(all(self.A[i, j] == 0 for i in range(S) for j in range(i, S)),
                 "A must be strictly lower triangular (explicit method)")
        for i in range(S):
            _require(_sums_to(self.A[i], self.c[i]), f"row {i + 1} of A must sum to c_i")
        _require(_sums_to(self.b, 1), "the weights b must sum to 1")
        _require(self.e.shape == self.b_hat.shape, "one row of error weights per b_hat")
        for row, e in zip(self.b_hat, self.e, strict=True):
            _require(_sums_to(row, 1), "embedded weights must sum to 1")
            _require(all(_sums_to((x, y), z) for x, y, z in zip(row, e, self.b, strict=True)),
                     "error weights must be e = b - b_hat")
        k = self.new_stage
        _require(0 <= k < S and _close(self.c[k], 1)
                 and all(_close(self.A[k, j], self.b[j] if j < s else 0) for j in range(S)),
                 "stage new_stage must be f(t + h, y_{n+1}) (row of A equal to b)")
        _require(self.fsal == (k < s), "fsal means: new_stage is one of the step's stages")
        if self.dense is not None:
            _require(self.dense.shape[0] == S, "dense weights need one row per stage")
            _require(self.dense_cheb.shape == (S, self.dense.shape[1] + 1),
                     "Chebyshev dense weights: degree + 1 coefficients per stage")
            for i in range(S):
                for row in (self.dense[i], self.dense_cheb[i]):
                    _require(_sums_to(row, self.b[i] if i < s else 0),
                             "dense output must give the step's y_{n+1} at theta = 1")

    @property
    def stages(self) -> int:
        """s: stages evaluated by every step (the dense output may need more)."""
        return len(self.b)


def _require(ok, message):
    if not ok:
        raise ValueError(f"inconsistent Butcher tableau: {message}")


def _close(x, y, tol=_TOL):
    return abs(x - y) <= tol


def _sums_to(terms, target):
    """sum(terms) == target within 1e-14 relative to the size of the terms (float64 data:
    each coefficient carries its own rounding; the sum itself is taken exactly by fsum)."""
    terms = list(terms)
    total = sum(terms) if isinstance(terms[0], Fraction) else math.fsum(terms)
    return _close(total, target, _TOL * max(1.0, float(sum(abs(x) for x in terms))))


def _vector(entries, n):
    out = [Fraction(0)] * n
    for i, v in (entries or {}).items():
        out[int(i) - 1] = Fraction(str(v))
    return out


def _poly_mul(p, q):
    out = [Fraction(0)] * (len(p) + len(q) - 1)
    for i, a in enumerate(p):
        for j, b in enumerate(q):
            out[i + j] += a * b
    return out


def _dop853_dense(d_rows, b, S):
    """Hairer's DOP853 continuous extension as polynomial weights (exact).

    y(theta) - y0 = theta (F0 + (1-theta) (F1 + theta (F2 + (1-theta) (F3 + theta (F4
    + (1-theta) (F5 + theta F6)))))) with F_j = h sum_i W[j, i] k_i:
    W0 = b, W1 = e_1 - b, W2 = 2 b - e_1 - e_13, W3..W6 = d_4..d_7 (dop853.f, CONTD8).
    """
    bS = b + [Fraction(0)] * (S - len(b))
    e1 = [Fraction(int(i == 0)) for i in range(S)]
    e13 = [Fraction(int(i == 12)) for i in range(S)]
    W = [bS, [x - y for x, y in zip(e1, bS, strict=True)],
         [2 * x - y - z for x, y, z in zip(bS, e1, e13, strict=True)]]
    W += [_vector(d_rows[i], S) for i in (4, 5, 6, 7)]
    q = [[Fraction(0), Fraction(1)]]                 # q_0 = theta
    for j in range(1, 7):                            # alternately * (1 - theta), * theta
        q.append(_poly_mul(q[-1], [Fraction(1), Fraction(-1)] if j % 2 else [0, 1]))
    P = [[Fraction(0)] * 7 for _ in range(S)]
    for j, Wj in enumerate(W):
        for i in range(S):
            for m, coef in enumerate(q[j][1:8]):
                P[i][m] += Wj[i] * coef
    return P


def _chebyshev(P):
    """Rows sum_j P[j] theta^(j+1) rewritten as sum_k C[k] T_k(2 theta - 1) (exact).

    Why: Verner's monomial coefficients reach 1.3e4 for weights of size <= 1 on [0, 1],
    so evaluating them loses 4 digits to cancellation; the Chebyshev coefficients are
    <= 5 for every method here, and Clenshaw's recurrence evaluates them stably.
    """
    out = []
    for row in P:
        # monomials in x = 2 theta - 1: theta^m = ((x + 1) / 2)^m
        px = [Fraction(0)] * (len(row) + 1)
        power = [Fraction(1)]
        for coef in row:
            power = _poly_mul(power, [Fraction(1, 2), Fraction(1, 2)])
            for k, a in enumerate(power):
                px[k] += coef * a
        # Horner in the Chebyshev basis: x T_0 = T_1, x T_k = (T_{k+1} + T_{k-1}) / 2
        cheb = [Fraction(0)] * len(px)
        for a in reversed(px):
            times_x = [Fraction(0)] * len(px)
            for k, ck in enumerate(cheb):
                if ck == 0:
                    continue
                if k == 0:
                    times_x[1] += ck
                else:
                    times_x[k - 1] += ck / 2
                    if k + 1 < len(px):
                        times_x[k + 1] += ck / 2
            cheb = times_x
            cheb[0] += a
        out.append(cheb)
    return out


def _read(name):
    path = DATA_DIR / f"{name}.yaml"
    if not path.exists():
        raise KeyError(f"unknown method {name!r}; known: {', '.join(METHODS)}")
    data = yaml.safe_load(path.read_text())
    extra = set(data) - _KEYS
    _require(not extra, f"unknown keys {sorted(extra)} in {path.name}")
    return data


@cache
def load_exact(name: str) -> ButcherTableau:
    """The tableau of `name` with every coefficient an exact Fraction (object arrays)."""
    d = _read(name)
    S = len(d["c"]) + 1
    c = _vector(d["c"], S)
    b = _vector(d["b"], d["stages"])
    A = [[Fraction(0)] * S for _ in range(S)]
    for i, row in d["A"].items():
        A[int(i) - 1] = b + [Fraction(0)] * (S - len(b)) if row == "b" else _vector(row, S)
    b_hat, orders = [], []
    for emb in d["embedded"]:
        if "weights" in emb:
            b_hat.append(_vector(emb["weights"], len(b)))
        elif "e" in emb:          # e = b - b_hat
            b_hat.append([x - y for x, y in zip(b, _vector(emb["e"], len(b)), strict=True)])
        else:                     # d = b_hat - b
            b_hat.append([x + y for x, y in zip(b, _vector(emb["d"], len(b)), strict=True)])
        orders.append(int(emb["order"]))
    dense, dense_order = None, 0
    if "dense" in d:
        dense_order = int(d["dense"]["order"])
        if d["dense"]["form"] == "dop853":
            dense = _dop853_dense(d["dense"]["d"], b, S)
        else:
            deg = max(len(v) for v in d["dense"]["p"].values())
            dense = [[Fraction(0)] * deg for _ in range(S)]
            for i, coefs in d["dense"]["p"].items():
                dense[int(i) - 1] = [Fraction(str(v)) for v in coefs]

    def arr(x):
        return np.array(x, dtype=object)

    return ButcherTableau(
        name=d["name"], order=int(d["order"]), error_order=int(d["error_order"]),
        c=arr(c), A=arr(A), b=arr(b), b_hat=arr(b_hat), b_hat_order=tuple(orders),
        e=arr([[x - y for x, y in zip(b, row, strict=True)] for row in b_hat]),
        error_estimate=d["error_estimate"], fsal=bool(d["fsal"]),
        new_stage=int(d["new_stage"]) - 1,
        dense=None if dense is None else arr(dense),
        dense_cheb=None if dense is None else arr(_chebyshev(dense)), dense_order=dense_order,
        reference=d.get("reference", ""))


class _Registry(Mapping):
    """name -> float64 tableau, every method of METHODS, loaded on first access."""

    def __getitem__(self, name):
        if name not in METHODS:
            raise KeyError(name)
        return load(name)

    def __iter__(self):
        return iter(METHODS)

    def __len__(self):
        return len(METHODS)


TABLEAUX = _Registry()


@cache
def load(name: str) -> ButcherTableau:
    """The float64 tableau of `name`: each published coefficient rounded once."""
    ex = load_exact(name)

    def f64(x):
        return np.array([float(v) for v in x.ravel()], dtype=np.float64).reshape(x.shape)

    return ButcherTableau(
        name=ex.name, order=ex.order, error_order=ex.error_order, c=f64(ex.c), A=f64(ex.A),
        b=f64(ex.b), b_hat=f64(ex.b_hat), b_hat_order=ex.b_hat_order, e=f64(ex.e),
        error_estimate=ex.error_estimate, fsal=ex.fsal, new_stage=ex.new_stage,
        dense=None if ex.dense is None else f64(ex.dense),
        dense_cheb=None if ex.dense is None else f64(ex.dense_cheb), dense_order=ex.dense_order,
        reference=ex.reference)
