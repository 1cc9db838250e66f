"""The rubber tables as data (catalogue/rubber_plane.yaml, rubber_sphere.yaml,
rubber_sources.yaml): they validate, every claim's source and check resolves, every case runs
a model, and the facts the cells lean on beyond tests/test_rubber_invariants.py hold."""

import ast
import collections
from pathlib import Path

import numpy as np
import pytest
import sympy as sp

from catalogue.load import load_rubber, read_rubber_raw
from catalogue.schema import BEYOND_MARKS, DERIVED, Access, CheckLevel, MarkedCell, RubberTables
from solvers.models import rubber_bodies as rb
from solvers.models import rubber_lagrange as rl
from solvers.verify import marks as vocab

ROOT = Path(__file__).resolve().parents[1]
RUBBER = load_rubber()
SOURCES, TABLES = RUBBER.sources, RUBBER.tables()
H = 1e-30


def _claims():
    for t in TABLES:
        for case in t.cases:
            for row, cell in case.cells.items():
                for c in cell.claims:
                    yield case, row, cell, c


def test_the_marks_are_the_vocabularys():
    """One vocabulary of marks: a rubber cell's mark is one of solvers/verify/marks.yaml's."""
    assert set(BEYOND_MARKS) <= set(vocab.IDS)


def test_every_case_runs_a_model_and_has_every_row():
    for t in TABLES:
        for case in t.cases:
            assert case.model in rb.CASES
            assert {r.value for r in case.cells} == {"measure", "integrals", "gyrostat", "brun",
                                                     "hamiltonian_form", "integrability"}


def test_every_named_test_exists():
    for _case, _row, _cell, c in _claims():
        if c.check and c.check.startswith("tests/"):
            path, name = c.check.split("::")
            tree = ast.parse((ROOT / path).read_text())
            names = {n.name for n in ast.walk(tree) if isinstance(n, ast.FunctionDef)}
            assert name in names, c.check


def test_every_source_is_cited_and_read_level_is_honest():
    used = {c.source for *_, c in _claims()} - {DERIVED}
    assert used <= set(SOURCES)
    for key, src in SOURCES.items():
        assert src.access != Access.TEXT_READ, f"{key}: no source was read in full"
        for c in src.claims:
            assert c["access"] in {a.value for a in Access}
    for *_, c in _claims():
        if c.source != DERIVED:
            assert c.access is Access.ABSTRACT_ONLY or c.access is Access.PARTIAL, c


def test_counts_by_mark():
    """The summary the home page will show: cells per mark, and that no literature claim
    read in an abstract is the only backing of a proved or checked cell."""
    counts = collections.Counter((cell.mark, cell.level) for t in TABLES for case in t.cases
                                 for cell in case.cells.values())
    assert sum(counts.values()) == 6 * sum(len(t.cases) for t in TABLES)
    assert counts[("project-formula", CheckLevel.EXACT)] >= 8
    for t in TABLES:
        for case in t.cases:
            for cell in case.cells.values():
                if cell.mark != "not-checkable":
                    assert any(c.source == DERIVED and c.check for c in cell.claims)


def test_bad_table_is_refused():
    from pydantic import ValidationError
    abstract = dict(source="ehlers-koiller-2006", place="abstract", access="abstract-only",
                    says="x", agreement="unchecked")
    derived = dict(source="derived-here", place="x", access="derived-here", says="x",
                   agreement="n/a", check="tests/x.py::y", level="numerical")
    x = dict(statement="x", statement_tex="x")   # a statement in both forms: refused for the rest
    refused = [
        dict(mark="project-formula", **x, claims=[abstract]),  # no check of ours
        dict(mark="project-formula", **x, claims=[derived]),   # numerical only
        dict(mark="not-checkable", **x, claims=[derived]),     # it was checked
        dict(mark="as-printed", **x, claims=[derived]),        # no paper prints it
        dict(mark="open", **x, claims=[abstract]),
        dict(mark="evidence-for", **x, claims=[{**derived, "access": "abstract-only"}]),
        dict(mark="evidence-for", **x, claims=[{**derived, "level": None}]),
        dict(mark="evidence-for", **x, claims=[{**derived, "check": "trust me"}]),
        dict(mark="not-checkable", **x, claims=[{**abstract, "level": "exact"}]),
        dict(mark="not-checkable", **x, claims=[{**abstract, "agreement": "confirmed"}]),
    ]
    for bad in refused:
        with pytest.raises(ValidationError):
            MarkedCell(**bad)
    MarkedCell(mark="evidence-for", **x, claims=[derived, abstract])


def test_a_claim_cannot_say_more_was_read_than_was():
    """A claim that says the text of an abstract-only source was read, or names a source
    that is not listed, is refused at load time and the data is left as it was."""
    from pydantic import ValidationError
    raw = read_rubber_raw()
    cell = raw["plane"]["cases"][0]["cells"]["measure"]
    before = repr(cell)
    for change in ({"access": "text-read"}, {"source": "nobody-2099"}):
        bad = {**raw, "plane": {**raw["plane"], "cases": [
            {**raw["plane"]["cases"][0], "cells": {**raw["plane"]["cases"][0]["cells"],
             "measure": {**cell, "claims": [cell["claims"][0], {**cell["claims"][1],
                                                                 **change}]}}},
            *raw["plane"]["cases"][1:]]}}
        with pytest.raises(ValidationError, match=r"nobody-2099|cannot say"):
            RubberTables.model_validate(bad)
    assert repr(cell) == before


# --- facts behind cells --------------------------------------------------------------------

def _nose2(b, g):
    r, _ = b.support_grad_hess(g)
    return b.I[0] * g[2] ** 2 + b.I[2] * (g[0] ** 2 + g[1] ** 2) + b.m * (r @ g) ** 2


def _grad(f, y):
    return np.array([f(y.astype(complex) + 1j * H * e).imag / H for e in np.eye(6)])


INTEGRALS = {
    "rubber-plane/chaplygin-ball":
        lambda b, y: (lambda M, g: M @ M - (M @ g) ** 2)(y[:3], y[3:]),
    "rubber-plane/routh-ball":
        lambda b, y: np.sqrt(_nose2(b, y[3:])) * rl.omega(b, y)[2],
    "rubber-plane/body-of-revolution":
        lambda b, y: np.sqrt(_nose2(b, y[3:])) * rl.omega(b, y)[2],
    "rubber-plane/ellipsoid-of-revolution":
        lambda b, y: np.sqrt(_nose2(b, y[3:])) * rl.omega(b, y)[2],
    "rubber-plane/round-disk":
        lambda b, y: np.sqrt(_nose2(b, y[3:])) * rl.omega(b, y)[2],
}


def _gyro_F(b, y):
    K = y[:3] + np.array(b.S)
    return K @ K - (K @ y[3:]) ** 2


def _brun_F(b, y):
    J = np.array(b.I) + b.m * b.c ** 2
    M, g = y[:3], y[3:]
    return M @ M - (M @ g) ** 2 - b.eps * np.prod(J) * np.sum(g * g / J)


def _shell_F(b, y):
    J = np.array(b.I) + b.m * b.c ** 2
    J1, J2, J3 = J
    P = np.array([[J1 * J3 * (J1 - J3), J1 * J3 * (J1 - J3), J1 * J2 * (J1 - J3)],
                  [J2 * J3 * (J2 - J3), J2 * J3 * (J2 - J3), J1 * J2 * (J2 - J3)],
                  [0.0, 0.0, J3 * (J1 - J3) * (J2 - J3)]])
    w, g = rl.omega(b, y), y[3:]
    return (w ** 2) @ P @ (g ** 2) / np.sum(g * g / J)


VARIANTS = {"rubber-plane/chaplygin-ball+gyrostat": (dict(S=(0.3, -0.2, 0.5)), _gyro_F),
            "rubber-plane/chaplygin-ball+brun": (dict(eps=0.7), _brun_F),
            "rubber-sphere/shell-over-half-ball+": ({}, _shell_F)}


@pytest.mark.parametrize("case_id", sorted(INTEGRALS) + sorted(VARIANTS))
def test_integrals_are_independent(case_id):
    """dH, dF, d(gamma^2), d(omega, gamma) have rank 4 at random points of N: with the
    measure, the Euler-Jacobi theorem applies on the 4-dimensional N."""
    if case_id in VARIANTS:
        override, F = VARIANTS[case_id]
        b = rb.body(case_id.split("+")[0], **override)
    else:
        b = rb.body(case_id)
        F = INTEGRALS[case_id]
    rng = np.random.default_rng(4)
    for _ in range(5):
        g = rng.normal(size=3)
        if b.d:
            g[2] *= 0.3
        y = rl.state_on_manifold(b, rng.normal(size=3), g)
        rows = [_grad(lambda z: rl.energy(b, z), y), _grad(lambda z: F(b, z), y),
                _grad(lambda z: z[3:] @ z[3:], y), _grad(lambda z: rl.spin(b, z), y)]
        s = np.linalg.svd(np.array(rows) / np.linalg.norm(rows, axis=1, keepdims=True),
                          compute_uv=False)
        assert s[-1] > 1e-6, s
        v = rl.field(b, y)         # and F is the integral the cell names
        assert abs(rows[1] @ v) < 1e-12 * np.linalg.norm(rows[1]) * np.linalg.norm(v)


def test_legendre_reading_of_ehlers_koiller():
    """The reading under which Ehlers-Koiller's abstract agrees with the density found here:
    the reduced Legendre transform on T*S^2 is J restricted to the tangent plane, whose
    determinant is det J (gamma, J^-1 gamma) = det J Q for |gamma| = 1; a density Q^p in
    momenta is Q^(p + 1) in velocities; with b/a = -kR, p + 1 = (1 - kR)/2."""
    rng = np.random.default_rng(5)
    for _ in range(5):
        J = np.diag(rng.uniform(0.5, 3.0, size=3))
        g = rng.normal(size=3)
        g /= np.linalg.norm(g)
        t1 = np.cross(g, rng.normal(size=3))
        t1 /= np.linalg.norm(t1)
        T = np.stack([t1, np.cross(g, t1)], axis=1)
        assert np.isclose(np.linalg.det(T.T @ J @ T),
                          np.linalg.det(J) * (g @ np.linalg.solve(J, g)), rtol=1e-13)
    kR = sp.Symbol("kR")
    p_ek = ((-kR) - 1) / 2
    assert sp.simplify(p_ek + 1 - (1 - kR) / 2) == 0


def test_every_named_module_runs():
    import importlib.util
    for *_, c in _claims():
        if c.check and c.check.startswith("python -m "):
            assert importlib.util.find_spec(c.check.removeprefix("python -m ")), c.check


def test_the_guide_states_the_tables_as_the_data_does():
    """docs/rubber.md's "Where each cell comes from": one line per case with each cell's
    mark, level and sources, as the YAML has them (a cell changed in the data and not in the
    guide fails here)."""
    text = (ROOT / "docs" / "rubber.md").read_text(encoding="utf-8")
    for t in TABLES:
        for case in t.cases:
            cells = []
            for r in t.rows:
                mc = case.cells[r.key]
                info = vocab.by_id()[mc.mark]
                srcs: list[str] = []
                for cl in mc.claims:
                    s = ("derived here" if cl.source == DERIVED
                         else f"{SOURCES[cl.source].short}, {cl.access.value}")
                    if s not in srcs:
                        srcs.append(s)
                level = f" ({mc.level.value})" if mc.level else ""
                cells.append(f"{info.shape} {info.word}{level}"
                             + (f"; {'; '.join(srcs)}" if srcs else ""))
            line = f"| {case.id.split('/', 1)[1]} | " + " | ".join(cells) + " |"
            assert line in text, line


def test_every_measure_cell_rests_on_an_exact_check():
    """A measure cell that states something (a density, or that none depends on gamma alone)
    rests on an exact check: a Liouville residual reduced to zero, or an exact non-zero
    obstruction with its scope stated in the cell."""
    for t in TABLES:
        for case in t.cases:
            cell = case.cells["measure"]
            if cell.mark != "not-checkable":
                assert cell.mark == "project-formula" and cell.level is CheckLevel.EXACT, case.id
                if cell.statement.startswith("no "):
                    assert "not excluded" in cell.statement, case.id    # its scope
