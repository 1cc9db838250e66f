"""The project's Hamiltonian forms on a sphere (solvers/verify/formulas/hamiltonian_sphere.py,
docs/hamiltonian-sphere.md): Table 2's "Hamiltonian form" cells of columns 6-9, which the
paper asserts without printing a bracket.

1. every project claim is verified to round-off and recorded with origin "project", and the
   four cells are decided on it (note: the project's derived formula); the Borisov-Fedorov
   cell (column a = 2R): a bracket that holds on the level F = 0 only, two attempts over
   the whole phase space that decide nothing, so the cell is inconclusive;
2. the checks catch a perturbed bracket, Hamiltonian or multiplier (flow) and a bracket that
   is not Poisson (Jacobi);
3. the lemmas of the derivation: the Jacobi identity of X ^ d/dK3 symbolically for arbitrary
   coefficients; the trace of every linear system vanishes (so 1/N is an invariant density);
   H equals the energy (M, omega)/2 + U.
"""

import numpy as np
import pytest
import sympy as sp

from catalogue.load import load_catalogue
from solvers.models import reduced_systems as rd
from solvers.models.revolution import profile
from solvers.verify.checks import structure as S
from solvers.verify.checks.common import TOL, gradient
from solvers.verify.formulas import hamiltonian_sphere as hs
from solvers.verify.formulas.general import energy
from solvers.verify.params import draw, random_states
from solvers.verify.registry import FORMULAS
from solvers.verify.run import verify
from solvers.verify.variables import to_vars

CAT = load_catalogue()
CASES = ["sphere/body-of-revolution", "sphere/round-disk", "sphere/routh-ball",
         "sphere/flat-base-axisymmetric"]
CLAIMS = [f"{c}/hamiltonian-after-time-change/project{s}" for c in CASES
          for s in ("", "/jacobi", "/gyrostat")]


def _records(record_id):
    return {r["claim"]: r for r in verify(claim=record_id)}


@pytest.mark.parametrize("claim_id", CLAIMS)
def test_project_claim_verified(claim_id):
    rec = _records(claim_id)[claim_id]
    assert rec["verdict"] == "verified", rec["message"]
    assert rec["residual"] <= TOL
    assert rec["origin"] == "project"
    assert CAT.claim(claim_id).origin.value == "project"


@pytest.mark.parametrize("case_id", CASES)
def test_cell_decided_by_the_project_formula(case_id):
    cell = _records(f"{case_id}/cell/hamiltonian_form")[f"{case_id}/cell/hamiltonian_form"]
    assert cell["verdict"] == "verified", cell["message"]
    assert "project's derived formula" in cell["message"]
    # the paper's own claim stays what it is: asserted without a printed formula
    paper = f"{case_id}/hamiltonian-after-time-change"
    assert paper in cell["rests_on"] and f"{paper}/project" in cell["rests_on"]
    assert _records(paper)[paper]["verdict"] == "unchecked"


# --- the checks catch wrong structures -----------------------------------------------------------

def _claim(claim_id):
    return CAT.case(claim_id.split("/hamiltonian")[0]), CAT.claim(claim_id)


MUTATIONS = {   # formula -> a perturbed version (one coefficient, relative 1e-6)
    "sphere_revolution_bracket": lambda f: lambda P, x: f(P, x) * np.array(
        [[1, 1, 1, 1], [1, 1, 1, 1 + 1e-6], [1, 1, 1, 1], [1, 1 + 1e-6, 1, 1]]),
    "sphere_routh_bracket": lambda f: lambda P, x: f(P, x) * np.array(
        [[1, 1, 1, 1], [1, 1, 1, 1], [1, 1, 1, 1 - 1e-6], [1, 1, 1 - 1e-6, 1]]),
    "flat_axisym_bracket": lambda f: lambda P, x: f(P, x) * np.array(
        [[1, 1, 1, 1], [1, 1, 1, 1 + 1e-6], [1, 1, 1, 1], [1, 1 + 1e-6, 1, 1]]),
    "sphere_revolution_hamiltonian": lambda f: lambda P, x: f(P, x) + 1e-6 * x[1] ** 2,
    "flat_axisym_hamiltonian": lambda f: lambda P, x: f(P, x) + 1e-6 * x[1] * x[2],
    "sphere_revolution_time_change": lambda f: lambda P, x: f(P, x) * (1 + 1e-6 * x[0]),
    "flat_axisym_time_change": lambda f: lambda P, x: f(P, x) * (1 + 1e-6),
}
FLOW_CASES = {
    "sphere_revolution_bracket": "sphere/body-of-revolution",
    "sphere_routh_bracket": "sphere/routh-ball",
    "flat_axisym_bracket": "sphere/flat-base-axisymmetric",
    "sphere_revolution_hamiltonian": "sphere/round-disk",
    "flat_axisym_hamiltonian": "sphere/flat-base-axisymmetric",
    "sphere_revolution_time_change": "sphere/routh-ball",
    "flat_axisym_time_change": "sphere/flat-base-axisymmetric",
}


@pytest.mark.parametrize("fid", sorted(MUTATIONS))
def test_flow_check_catches_a_perturbed_formula(monkeypatch, fid):
    case, claim = _claim(f"{FLOW_CASES[fid]}/hamiltonian-after-time-change/project")
    good = S.hamiltonian_residual(CAT, case, claim)
    assert good <= TOL
    monkeypatch.setitem(FORMULAS, fid, MUTATIONS[fid](FORMULAS[fid]))
    bad = S.hamiltonian_residual(CAT, case, claim)
    assert bad > 10 * TOL, bad          # relative 1e-6 on one term: measured 2.6e-7 .. 1.8e-5


@pytest.mark.parametrize("fid,case_id", [("sphere_revolution_bracket", CASES[0]),
                                         ("sphere_routh_bracket", CASES[2]),
                                         ("flat_axisym_bracket", CASES[3])])
def test_jacobi_check_catches_a_non_poisson_tensor(monkeypatch, fid, case_id):
    """{K1, K3} made to depend on K3 (1e-3 K3^2 added): [X, d/dK3] != 0 in the K1 direction
    while X ^ d/dK3 ^ [X, d/dK3] != 0, so the tensor is not Poisson; the check must see it."""
    case, claim = _claim(f"{case_id}/hamiltonian-after-time-change/project/jacobi")
    assert S.jacobi_residual(CAT, case, claim) <= TOL
    good = FORMULAS[fid]

    def bad(P, x):
        J = good(P, x) + 0.0 * x[3]
        extra = 1e-3 * x[3] ** 2 * (1 + x[2])
        J[1, 3] = J[1, 3] + extra
        J[3, 1] = J[3, 1] - extra
        return J
    monkeypatch.setitem(FORMULAS, fid, bad)
    assert S.jacobi_residual(CAT, case, claim) > 1e-6


# --- the lemmas of the derivation ---------------------------------------------------------------

def test_jacobi_identity_holds_symbolically_for_any_linear_system():
    """J = X ^ d/dK3, X = d/ds + (A(s) K + b(s)) . d/dK: the Jacobiator vanishes
    identically, whatever the functions a_ij(s), b_i(s) (so every bracket of
    hamiltonian_sphere.py is Poisson: a proof, not a sample)."""
    s, K1, K2, _K3 = x = sp.symbols("s K1 K2 K3")
    a = [[sp.Function(f"a{i}{j}")(s) for j in range(2)] for i in range(2)]
    b = [sp.Function(f"b{i}")(s) for i in range(2)]
    c1 = a[0][0] * K1 + a[0][1] * K2 + b[0]
    c2 = a[1][0] * K1 + a[1][1] * K2 + b[1]
    J = sp.zeros(4, 4)
    J[0, 3], J[1, 3], J[2, 3] = 1, c1, c2
    J = J - J.T
    for i in range(4):
        for j in range(4):
            for k in range(4):
                jac = sum(J[i, l] * sp.diff(J[j, k], x[l]) + J[j, l] * sp.diff(J[k, i], x[l])
                          + J[k, l] * sp.diff(J[i, j], x[l]) for l in range(4))
                assert sp.simplify(jac) == 0


def _points(case_id, claim_suffix="/hamiltonian-after-time-change/project", n=3):
    case, claim = _claim(case_id + claim_suffix)
    rng = np.random.default_rng(7)
    for _ in range(2):
        P = draw(case, claim, rng)
        for y in random_states(P, n, rng):
            yield P, y


def _trace(dK, P, x):
    """d(dK1/ds)/dK1 + d(dK2/ds)/dK2 by complex step."""
    t = 0.0
    for i in (0, 1):
        xc = x.astype(np.complex128)
        xc[1 + i] += 1e-30j
        t += np.asarray(dK(P, xc)).imag[1 + i] / 1e-30
    return t


@pytest.mark.parametrize("case_id,bracket", [(CASES[0], "sphere_revolution_bracket"),
                                             (CASES[1], "sphere_revolution_bracket"),
                                             (CASES[2], "sphere_routh_bracket"),
                                             (CASES[3], "flat_axisym_bracket")])
def test_linear_systems_are_trace_free_so_1_over_N_is_a_density(case_id, bracket):
    """div (J grad H) = K3 tr A: zero, so the tau-field preserves volume and 1/N is an
    invariant density of the reduced t-field (the reducing multiplier, as 1/k on the plane)."""
    J = FORMULAS[bracket]
    V = "(u, K1, K2, K3)" if "flat" in case_id else "(gamma3, K1, K2, K3)"
    for P, y in _points(case_id, "/hamiltonian-after-time-change/project/gyrostat"):
        x = np.asarray(to_vars(V, P, y)).real
        col = lambda P, xx: J(P, xx)[:, 3]  # noqa: E731
        scale = abs(np.asarray(J(P, x))[1:3, 3]).sum() + 1.0
        assert abs(_trace(col, P, x)) <= 1e-12 * scale


def test_the_k2_coefficient_of_eq3_3_vanishes_by_the_meridian_relation():
    """g3 f2' + sqrt(1-g3^2)(f1 sqrt(1-g3^2))' = 0 identically by eq2.1/2: the printed K2 term
    of eq3.3's second equation is zero (the reason the trace above vanishes)."""
    for P, _ in _points(CASES[0]):
        b = rd.RevBody.from_params(P.p)
        for u in np.linspace(-0.9, 0.9, 7):
            f1, _, f1p, f2p = profile(b.prof, u)[:4]
            sig = np.sqrt(1 - u * u)
            term = u * f2p + sig * (f1p * sig - f1 * u / sig)
            assert abs(term) <= 1e-13 * (abs(u * f2p) + abs(f1) + abs(f1p))


@pytest.mark.parametrize("case_id", CASES)
def test_hamiltonian_is_the_energy(case_id):
    flat = "flat" in case_id
    V = "(u, K1, K2, K3)" if flat else "(gamma3, K1, K2, K3)"
    Hf = hs.flat_axisym_hamiltonian if flat else hs.sphere_revolution_hamiltonian
    for P, y in _points(case_id, "/hamiltonian-after-time-change/project/gyrostat"):
        x = np.asarray(to_vars(V, P, y)).real
        E = energy(P, y)
        assert abs(Hf(P, x) - E) <= 1e-12 * max(abs(E), 1.0)
        # and d x0/dt = N dH/dK3 (the multiplier read off the full field)
        Nf = hs.flat_axisym_time_change if flat else hs.sphere_revolution_time_change
        from solvers.verify.checks.common import directional, full_field
        xd = directional(lambda yy, P=P: to_vars(V, P, yy), y, full_field(P, y))
        g = gradient(lambda xx, P=P: Hf(P, xx), x)
        assert abs(xd[0] - Nf(P, x) * g[3]) <= 1e-12 * abs(xd[0]) + 1e-15
        if not flat:                     # K3 of eq2.4 carries exactly K3^2/2
            assert abs(g[3] - x[3]) <= 1e-12 * abs(x[3]) + 1e-15


# --- Borisov-Fedorov: the plane's bracket carried to k fails; e(3) pulled back holds on F = 0 --

def test_bf_candidate_generates_the_flow_but_is_not_poisson():
    """The k-version of eq2b-*1 reproduces the field of eq3.12 after d tau = rho dt at a = 2R
    (k = -1) to round-off, but violates the Jacobi identity there by O(0.1): it is no
    Hamiltonian form (the claim .../attempt/plane-bracket records it as inconclusive).
    At k = 1 (the plane's Chaplygin ball, same code) it is Poisson."""
    from solvers.verify.checks.common import full_field
    from solvers.verify.formulas.chaplygin import chaplygin_hamiltonian_m
    from solvers.verify.formulas.sphere_bodies import factor_312
    from solvers.verify.variables import chaplygin_rho

    for cid, claim, kval in [("sphere/borisov-fedorov",
                              "sphere/borisov-fedorov/hamiltonian-after-time-change", -1.0),
                             ("plane/chaplygin-ball",
                              "plane/chaplygin-ball/hamiltonian-after-time-change", 1.0)]:
        case, cl = CAT.case(cid), CAT.claim(claim)
        rng = np.random.default_rng(3)
        P = draw(case, cl, rng)
        if cid.startswith("plane"):     # the plane ball with no field: U = 0 in H below
            from solvers.verify.checks.rotations import with_params as _with_p
            P = _with_p(P, GRAV=0.0, BRUN=0.0)
        assert factor_312(P) == pytest.approx(kval)
        worst_flow, jac = 0.0, []
        for y in random_states(P, 6, rng):
            J = lambda xx, P=P: hs.bf_candidate_bracket(P, xx)  # noqa: E731
            rhs = J(y) @ gradient(lambda xx, P=P: chaplygin_hamiltonian_m(P, xx), y)
            v = full_field(P, y) / chaplygin_rho(P, y[3:6])
            worst_flow = max(worst_flow, np.linalg.norm(v - rhs) / np.linalg.norm(v))
            jac.append(S.jacobi_residual_at(J, y))
        assert worst_flow <= 1e-12
        if kval == -1.0:
            assert min(jac) > 1e-2, jac
        else:
            assert max(jac) <= 1e-12, jac


BF = "sphere/borisov-fedorov/hamiltonian-after-time-change"


def _bf_points(n=5, seed=4, level=True):
    """(P, x) at the Borisov-Fedorov ball (k = -1), x moved onto F = 0 when level."""
    from solvers.verify.formulas.sphere_bodies import bf_abar

    rng = np.random.default_rng(seed)
    P = draw(CAT.case("sphere/borisov-fedorov"), CAT.claim(BF), rng)
    for y in random_states(P, n, rng):
        x = np.array(y, dtype=float)
        if level:
            ab = bf_abar(P) * x[3:6]
            x[:3] -= (x[:3] @ ab) * ab / (ab @ ab)
        yield P, x


def _bf_flow(P, x, bracket=hs.bf_level0_bracket, N=hs.bf_level0_time_change):
    from solvers.verify.checks.common import full_field

    rhs = bracket(P, x) @ gradient(lambda xx: hs.bf_level0_hamiltonian(P, xx), x)
    v = full_field(P, x) / N(P, x)
    return np.linalg.norm(v - rhs) / np.linalg.norm(v)


def test_bf_level0_bracket_is_poisson_and_generates_the_flow_on_F_zero():
    """The e(3) pull-back: Jacobi to round-off at any point (it is a pull-back), Casimirs
    gamma^2 and F = (M, Abar gamma) of eq3.13, and (1/N) dx/dt = J grad H on F = 0."""
    from solvers.verify.formulas.general import geometric
    from solvers.verify.formulas.sphere_bodies import bf_integral

    for P, x in _bf_points():
        J = hs.bf_level0_bracket(P, x)
        assert np.max(abs(J + J.T)) <= 1e-13 * np.max(abs(J))
        assert S.jacobi_residual_at(lambda xx, P=P: hs.bf_level0_bracket(P, xx), x) <= 1e-12
        for C in (geometric, bf_integral):
            g = gradient(lambda xx, C=C, P=P: C(P, xx), x)
            assert np.max(abs(J @ g)) <= 1e-12 * np.max(abs(J) @ abs(g))
        assert _bf_flow(P, x) <= 1e-12
        assert np.linalg.matrix_rank(J, tol=1e-9 * np.max(abs(J))) == 4


def test_bf_level0_bracket_fails_off_the_zero_level():
    """Off F = 0 the same bracket, H and N do not give the motion (O(0.01-1)): the cell's
    statement is shown on one level only, which is why the cell stays inconclusive."""
    worst = max(_bf_flow(P, x) for P, x in _bf_points(level=False))
    assert worst > 1e-2


def test_bf_level0_mutations_are_caught(monkeypatch):
    """A relative 1e-6 change of the multiplier, of one bracket entry, or of one entry of the
    map L = K M breaks the flow on F = 0 well above the tolerance; the changed bracket entry
    also breaks the Jacobi identity."""
    bump_entry = np.ones((6, 6))
    bump_entry[0, 4] = bump_entry[4, 0] = 1 + 1e-6

    def N_bad(P, x):
        return hs.bf_level0_time_change(P, x) * (1 + 1e-6 * x[3])

    def J_bad(P, x):
        return hs.bf_level0_bracket(P, x) * bump_entry

    for P, x in _bf_points(n=3):
        assert _bf_flow(P, x, N=N_bad) > 1e-8
        assert _bf_flow(P, x, bracket=J_bad) > 1e-8
        assert _bf_flow(P, x, bracket=J_bad) > 1e-8
        assert S.jacobi_residual_at(lambda xx, P=P: J_bad(P, xx), x) > 1e-8
    Kf, dKf = hs._bf_map()
    bump = np.array([[1, 1, 1], [1, 1 + 1e-6, 1], [1, 1, 1]])
    monkeypatch.setattr(hs, "_bf_map", lambda: (lambda *a: np.asarray(Kf(*a)) * bump, dKf))
    for P, x in _bf_points(n=3):
        assert _bf_flow(P, x) > 1e-8


def test_bf_cell_is_inconclusive_with_what_was_shown():
    """The cell: the paper's claim has no formula (not checkable); the project's bracket holds
    on F = 0 (project-formula, with Jacobi and Casimirs); the two attempts over the whole
    phase space decide nothing (inconclusive), so the cell is inconclusive and its note says
    in plain words what held and where."""
    cid = "sphere/borisov-fedorov/cell/hamiltonian_form"
    recs = _records(cid)
    cell = recs[cid]
    assert cell["mark"] == "inconclusive" and cell["verdict"] == "unchecked"
    for c in (f"{BF}/project", f"{BF}/project/jacobi", f"{BF}/project/casimirs"):
        assert recs[c]["verdict"] == "verified" and recs[c]["mark"] == "project-formula"
        assert recs[c]["residual"] <= 1e-12
    assert "zero level of the integral (3.11) only" in recs[f"{BF}/project"]["mark_note"]
    assert recs[BF]["mark"] == "not-checkable"
    for c in (f"{BF}/attempt/all-levels", f"{BF}/attempt/plane-bracket"):
        assert recs[c]["verdict"] == "unchecked" and recs[c]["mark"] == "inconclusive"
    ev = recs[f"{BF}/attempt/all-levels"]["evidence"]
    assert ev["Jacobi identity residual"] <= TOL < ev["flow residual"]
    assert ev["flow residual on the level"] <= TOL
    ev = recs[f"{BF}/attempt/plane-bracket"]["evidence"]
    assert ev["flow residual"] <= TOL < ev["Jacobi identity residual"]
    note = cell["mark_note"]
    assert "(3.11)" in note and "neither confirmed nor refuted" in note
    assert "not a Poisson bracket" in note
    assert cell["notes"] == []        # no "holds with the project's formula" on this cell
    for word in ("bf_", "eq3.", "_bracket", ".py"):
        assert word not in note


# --- the Brun generalizations (Table 2, generalizations row, columns 1-2) ----------------------

BRUN = ["sphere/chaplygin-ball/brun/integral/project",
        "sphere/borisov-fedorov/brun/integral/project-F",
        "sphere/borisov-fedorov/brun/integral/project-kozlov",
        "sphere/borisov-fedorov/brun/integral/project-measure"]


@pytest.mark.parametrize("claim_id", BRUN)
def test_brun_project_claims_verified(claim_id):
    rec = _records(claim_id)[claim_id]
    assert rec["verdict"] == "verified" and rec["residual"] <= TOL, rec["message"]
    assert rec["origin"] == "project"


@pytest.mark.parametrize("case_id", ["sphere/chaplygin-ball", "sphere/borisov-fedorov"])
def test_generalizations_cells_rest_on_the_whole_statement(case_id):
    cid = f"{case_id}/cell/generalizations"
    cell = _records(cid)[cid]
    assert cell["verdict"] == "verified", cell["message"]
    assert [c for c in cell["rests_on"] if c.endswith("/project") or "/project-" in c]
    if case_id == "sphere/chaplygin-ball":     # "one integral and measure": both rested on
        assert {"sphere/chaplygin-ball/brun/measure",
                "sphere/chaplygin-ball/brun/integral/project"} <= set(cell["rests_on"])


def test_brun_integrals_need_the_brun_identity(monkeypatch):
    """Kozlov's coefficient -eps/det A is the only one that works: scaled by 1 + 1e-6 the
    integral check fails (on the sphere, k of eq3.12 arbitrary)."""
    from solvers.verify.checks.pointwise import integral_residual
    claim_id = "sphere/chaplygin-ball/brun/integral/project"
    case, claim = CAT.case("sphere/chaplygin-ball"), CAT.claim(claim_id)
    good = FORMULAS["kozlov_brun_F3"]
    assert integral_residual(CAT, case, claim, "kozlov_brun_F3") <= TOL

    def bad(P, x):
        M = x[:3]
        return (1 + 1e-6) * good(P, x) - 1e-6 * (M @ M)
    monkeypatch.setitem(FORMULAS, "kozlov_brun_F3", bad)
    assert integral_residual(CAT, case, claim, "kozlov_brun_F3") > 1e-8
