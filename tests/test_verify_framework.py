"""The verification framework itself: records, readings of densities, cell verdicts."""

import json
import subprocess
import sys

import numpy as np
import pytest

from catalogue.load import load_catalogue
from solvers.errors import InputError
from solvers.verify import verify
from solvers.verify.checks.common import TOL
from solvers.verify.checks.pointwise import measure_residual
from solvers.verify.registry import FORMULAS
from solvers.verify.table import cell_verdict, table_marks
from solvers.verify.variables import chaplygin_rho


def test_records_have_the_interface_fields():
    recs = verify("plane/chaplygin-ball")
    assert recs
    for r in recs:
        for key in ("case", "claim", "kind", "verdict", "residual", "printed"):
            assert key in r
        assert r["verdict"] in ("verified", "fails", "evidence", "unchecked")
        assert r["residual"] is None or np.isfinite(r["residual"])


def test_unknown_case_is_an_input_error():
    with pytest.raises(InputError, match="unknown case"):
        verify("plane/nope")


def test_density_is_pulled_back_from_omega_variables(monkeypatch):
    """A density written in (omega, gamma) equals rho_M * det I_Q there (the paper's remark
    after eq2.2): read in (omega, gamma) it verifies, read in (M, gamma) it does not."""
    cat = load_catalogue()
    case = cat.case("plane/chaplygin-ball")
    claim = case.claim("plane/chaplygin-ball/measure")

    def rho_omega(P, x):
        return chaplygin_rho(P, x[3:6]) * np.linalg.det(P.contact_inertia(P.r(x[3:6])))

    monkeypatch.setitem(FORMULAS, "chaplygin_density", rho_omega)
    assert measure_residual(cat, case, claim, "chaplygin_density",
                            variables="(omega, gamma)") < TOL
    assert measure_residual(cat, case, claim, "chaplygin_density") > 1e-3


def test_borisov_fedorov_map_is_checked_not_assumed():
    (rec,) = verify(claim="sphere/borisov-fedorov/reduction/to-chaplygin")
    assert rec["verdict"] == "fails"
    assert rec["evidence"]["rate (M~, gamma)"] < TOL < rec["evidence"]["rate |M~|^2"]


def test_cell_verdicts():
    by = {"a": {"verdict": "verified", "check": "integral"},
          "b": {"verdict": "unchecked", "check": "integral"},
          "c": {"verdict": "unchecked", "check": "open_problem"},
          "d": {"verdict": "fails", "check": "measure"},
          "e": {"verdict": "evidence", "check": "negative_measure"}}
    assert cell_verdict(["a", "c"], by) == "verified"       # open problems are neutral
    assert cell_verdict(["a", "b"], by) == "unchecked"      # not implemented blocks a tick
    assert cell_verdict(["a", "d"], by) == "fails"
    assert cell_verdict(["e", "c"], by) == "evidence"
    assert cell_verdict([], by) == ""


def test_table_marks_cover_every_cell():
    cat = load_catalogue()
    recs = verify("plane/chaplygin-ball")
    marks = table_marks(cat.plane, recs)
    assert marks["plane/chaplygin-ball"]["measure"] == "verified"
    assert set(marks) == {c.id for c in cat.plane.cases}


def test_cli_verify_json_and_table():
    proc = subprocess.run([sys.executable, "-m", "app.cli", "verify", "--case",
                           "plane/routh-ball", "--json"], capture_output=True, text=True,
                          timeout=600)
    assert proc.returncode == 0, proc.stderr
    recs = json.loads(proc.stdout)
    assert {r["case"] for r in recs} == {"plane/routh-ball"}
    proc = subprocess.run([sys.executable, "-m", "app.cli", "verify", "--case",
                           "plane/routh-ball"], capture_output=True, text=True, timeout=600)
    assert proc.returncode == 0
    assert "Table 1" in proc.stdout and "routh-ball" in proc.stdout and "claims:" in proc.stdout
    proc = subprocess.run([sys.executable, "-m", "app.cli", "verify", "--case", "x/y"],
                          capture_output=True, text=True, timeout=600)
    assert proc.returncode == 2 and proc.stderr.startswith("error: unknown case")
