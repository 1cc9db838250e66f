"""Negative statements: evidence (never proof) that no invariant measure or no further
first integral exists, with the numbers in Outcome.evidence.

`negative_measure`
  (1) Densities of the position alone (every density the paper prints is one: rho(gamma),
      rho(r)). div v is linear in M (checked), div v = c(y_pos) . omega, and the Liouville
      equation v . grad ln rho = -div v with rho = rho(position) needs
        full model (M, gamma):  c . gamma = 0 and the 1-form g = (E - k J)(c x gamma) on the
                                sphere closed (gamma' = (E - k J)^-1 gamma x omega);
        flat base (M, r1, r2):  c3 = 0 and g = k (-c2, c1) closed in the (r1, r2) plane
                                (dr/dt = (omega2, -omega1)/k).
      Both are computed with exact derivatives: c by complex step (div v) and exact
      differences (div v is linear in M), the closedness as the circulation of g round a
      small circle by the periodic trapezoidal rule (spectrally accurate), relative to
      the integral of |g|. A residual above TOL is an obstruction (no such density); both
      at round-off at every point mean that such a density exists (the domain is simply
      connected) and the negative claim fails.
  (2) Candidate densities by the pointwise Liouville residual: the one check_args.formula
      names (through checks/pointwise.measure_residual) and the ones in CANDIDATES.
  (3) Attracting sets (Fig. 5, Fig. 6), only where (1) finds an obstruction and the
      energy levels are compact: the spread of an orbit's points on the section
      gamma1 = 0 in ten consecutive windows of a long run. A monotone secular trend
      (Kendall tau >= 0.9) is what an orbit settling on an attractor shows; an invariant
      measure with a smooth positive density forbids it (Poincare recurrence). On the
      controls the spread stays constant to ~1e-3; in chaotic layers with a measure it
      fluctuates without trend (measured on plane/spherical-inertia).
  Each test is repeated on the control, the same body with the change that restores a
  known measure, to show what "no obstruction" looks like.

`negative_integral`
  Orbits of the three-dimensional section map (section gamma3 = 0, at the orbit's energy):
  one more integral confines an orbit to a set of dimension 2 - (integrals already known
  besides H); the check measures the local dimension of each orbit's section points by
  the singular values s1 >= s2 >= s3 of their 24-point neighbourhoods (medians of s2/s1,
  s3/s1) and reports evidence when an orbit is thicker than one more integral allows,
  while the integrable control (CONTROLS) stays thin. Finding no such orbit is reported as
  inconclusive (`unchecked`), never as a verdict on the integral.
"""

from dataclasses import replace

import numpy as np
from scipy.spatial import cKDTree

from solvers.integrate.integrator import Section, integrate
from solvers.kernels import layout as L
from solvers.models.cases import build
from solvers.models.derivatives import field
from solvers.verify.checks.common import TOL, directional, divergence_terms, full_field
from solvers.verify.checks.pointwise import measure_residual
from solvers.verify.params import Params, draw, merged_conditions, random_states
from solvers.verify.registry import Outcome, check

N_POINTS_NEG = 12       # phase points per parameter draw for the position-only test
N_SETTINGS_NEG = 2
LOOP_RADIUS = 0.2       # angular radius (sphere) / radius (flat) of the circulation loops
LOOP_NODES = 48
T_LONG = 30000.0        # section-spread runs
N_DRIFT_ORBITS = 2
N_MAP_ORBITS = 8        # negative_integral: orbits scanned (stops at the first evidence)
N_CONTROL_ORBITS = 3
T_MAP = 10000.0
MAX_CROSSINGS = 3000
MIN_CROSSINGS = 300
NEIGHBOURS = 24
THICK = {2: 0.25, 3: 0.15}   # s2/s1 above THICK[2]: not a curve; s3/s1 above THICK[3]: a layer

# The change of parameters that restores a known measure (negative_measure) or makes the
# case integrable (negative_integral), with what is known there.
CONTROLS = {
    "plane/unbalanced-ball": ({"a1": 0.0, "a2": 0.0, "a3": 0.0},
                              "a = 0: the Chaplygin ball, density eq2.17"),
    "sphere/unbalanced-ball": ({"a1": 0.0, "a2": 0.0, "a3": 0.0},
                               "a = 0: the balanced ball on a sphere, density of Table 2"),
    "sphere/flat-base": ({"z": 0.0}, "z = 0: density (I3 + m r^2)^-1/2, eq3.16"),
    "plane/spherical-inertia": ({"k": 0.0}, "the same body on the plane: density "
                                "(mu + m r^2)^-1/2 (eq2.19 / eq2.30)"),
}
MAP_CONTROLS = {
    "plane/ellipsoid": ({"b": "mean"}, "b1 = b2 = b3: a ball with I = (mu + m b) E, the "
                        "integrable Chaplygin ball (H, M^2, (M, gamma))"),
    "plane/spherical-inertia": ({"b": "mean", "a1": 0.0, "a2": 0.0, "a3": 0.0, "c": 0.0},
                                "b1 = b2 = b3, a = 0: the integrable Chaplygin ball with "
                                "spherical inertia"),
    "sphere/chaplygin-ball": ({"case": "sphere/borisov-fedorov"},
                              "the Borisov–Fedorov ball (k = 2/R), third integral eq3.13"),
}
KNOWN_INTEGRALS = {"sphere/chaplygin-ball": 1}   # besides H (and gamma^2): M^2


# --- densities named by the paper for these claims -----------------------------------------

def spherical_inertia_density(P, y):
    """(mu + m r^2)^-1/2 in (M, gamma): the plane measure of (2.31)/(2.41) (lambda = 0)."""
    r = P.r(y[3:6])
    return 1.0 / np.sqrt(P.mu + P.m * (r @ r))


def spherical_inertia_sphere_density(P, y):
    """(mu + m r^2)^-1/2 det(E - k J) in (M, gamma): found by the project (the 1-form test
    above is exact here; this closed form fits it): the generalisation to a sphere of
    curvature k of the plane measure, det(E - k J) = product of (1 - k * principal radius
    of curvature) at the contact point."""
    J = P.J(y[3:6])
    return spherical_inertia_density(P, y) * np.linalg.det(np.eye(3) - P.k * J)


CANDIDATES = {
    "plane/spherical-inertia": (("(mu + m r^2)^-1/2 (the plane measure)",
                                 spherical_inertia_density),
                                ("(mu + m r^2)^-1/2 det(E - k J) (project)",
                                 spherical_inertia_sphere_density)),
}


# --- parameters --------------------------------------------------------------------------

def _with_k(P, k):
    p = P.p.copy()
    p[L.CURV] = k
    p.setflags(write=False)
    return Params(replace(P.model, p=p))


def case_params(case, claim, rng):
    """The claim's parameters; a plane case whose claim asks for k != 0 (the body put on a
    sphere: plane/spherical-inertia, (2.31)) gets a drawn curvature (the case's draw has
    no k, its model has the slot)."""
    P = draw(case, claim, rng)
    if merged_conditions(case, claim).k == "nonzero" and P.k == 0.0:
        P = _with_k(P, rng.choice([-1.0, 1.0]) * rng.uniform(0.1, 0.3))
    return P


def control_params(case, P, table):
    if case.id not in table:
        return None, None
    change, text = table[case.id]
    if "k" in change:
        return _with_k(P, change["k"]), text
    if "case" in change:
        prm = {k: v for k, v in P.model.params.items() if k != "k"}
        return Params(build(change["case"], prm)), text
    prm = dict(P.model.params)
    for key, value in change.items():
        if key == "b":
            b = float(np.mean([P.model.params[n] for n in ("b1", "b2", "b3")]))
            prm.update(b1=b, b2=b, b3=b)
        else:
            prm[key] = value
    return Params(build(case.id, prm)), text


# --- (1) densities of the position alone ----------------------------------------------------

def _cfield(P, y):
    v, _ = field(P.model.model, P.p, y)
    return v


def _div(P, y):
    return divergence_terms(lambda yy: _cfield(P, yy), y)[0]


def _flat(P):
    return P.model.model == L.MODEL_FLAT


def _position(P, y):
    return y[3:5] if _flat(P) else y[3:6]


def _state(P, M, pos):
    return np.concatenate([M, pos])


def _r(P, pos):
    return np.array([pos[0], pos[1], P.z]) if _flat(P) else P.r(pos)


def omega_coefficients(P, pos):
    """c with div v = c . omega at the position, and the relative deviation of div v from
    linearity in M (a check of the premise)."""
    d0 = _div(P, _state(P, np.zeros(3), pos))
    cM = np.array([_div(P, _state(P, e, pos)) - d0 for e in np.eye(3)])
    Mt = np.array([0.7, -1.3, 0.4])
    lin = abs(_div(P, _state(P, Mt, pos)) - d0 - cM @ Mt) / (abs(cM) @ abs(Mt) + abs(d0)
                                                               + 1e-300)
    IQ = P.contact_inertia(_r(P, pos))
    return IQ @ cM, float(lin), d0


def _one_form(P, pos):
    c, _, _ = omega_coefficients(P, pos)
    if _flat(P):
        return P.k * np.array([-c[1], c[0]])
    h = np.cross(c, pos)
    return h - P.k * (P.J(pos) @ h)


def normal_residual(P, pos):
    c, lin, _ = omega_coefficients(P, pos)
    nrm = np.linalg.norm(c)
    if nrm == 0.0:
        return max(lin, 0.0)
    n = abs(c[2]) if _flat(P) else abs(c @ pos)
    return max(float(n / nrm), lin)


def circulation_residual(P, pos):
    """|closed-loop integral of g| / integral of |g| |d pos| round a small circle."""
    ph = 2 * np.pi * np.arange(LOOP_NODES) / LOOP_NODES
    if _flat(P):
        rad = LOOP_RADIUS * (1.0 + np.linalg.norm(pos))
        pts = [pos + rad * np.array([np.cos(p), np.sin(p)]) for p in ph]
        tan = [rad * np.array([-np.sin(p), np.cos(p)]) for p in ph]
    else:
        a = np.cross(pos, [1.0, 0.0, 0.0] if abs(pos[0]) < 0.9 else [0.0, 1.0, 0.0])
        a /= np.linalg.norm(a)
        b = np.cross(pos, a)
        d = LOOP_RADIUS
        pts = [np.cos(d) * pos + np.sin(d) * (np.cos(p) * a + np.sin(p) * b) for p in ph]
        tan = [np.sin(d) * (-np.sin(p) * a + np.cos(p) * b) for p in ph]
    num, den = 0.0, 0.0
    for q, t in zip(pts, tan, strict=True):
        g = _one_form(P, q)
        num += g @ t
        den += np.linalg.norm(g) * np.linalg.norm(t)
    return float(abs(num) / den) if den > 0 else 0.0


def position_density_test(P, rng, n):
    """max normal and circulation residuals over n random phase points."""
    worst_n, worst_c = 0.0, 0.0
    for y in random_states(P, n, rng):
        pos = _position(P, y)
        if not _flat(P):
            pos = pos / np.linalg.norm(pos)
        worst_n = max(worst_n, normal_residual(P, pos))
        worst_c = max(worst_c, circulation_residual(P, pos))
    return worst_n, worst_c


# --- (2) candidates ------------------------------------------------------------------------

def liouville_residual(P, rho, rng, n):
    worst = 0.0
    for y in random_states(P, n, rng):
        v = full_field(P, y)
        dln = float(directional(lambda yy: np.log(rho(P, yy)), y, v))
        div, scale = divergence_terms(lambda yy: _cfield(P, yy), y)
        worst = max(worst, abs(dln + div) / max(abs(dln) + scale, 1e-300))
    return worst


# --- (3) attractors on the section ------------------------------------------------------------

def section_points(P, y0, T, coef, max_crossings=MAX_CROSSINGS):

    run = integrate(P.model.model, P.p, y0, np.array([0.0, T]), rtol=1e-10, atol=1e-12,
                    section=Section(coef=coef), max_crossings=max_crossings)
    return run.crossings_y


def _spread(Z):
    return float(np.sqrt(np.mean(np.sum((Z - Z.mean(0)) ** 2, axis=1))))


def section_drift(P, rng, n_orbits=N_DRIFT_ORBITS, T=T_LONG):
    """Per orbit (up to n_orbits with enough crossings of gamma1 = 0): the spread of its
    section points in ten consecutive windows, summarised by Kendall's tau against the
    window index (+-1: a monotone secular drift, as an orbit settling on an attractor;
    measure-preserving orbits give no trend: constant on tori, random in chaotic layers)
    and the relative change |last - first| / first."""
    from scipy.stats import kendalltau  # lazy: scipy.stats, slow to import, not at server start

    out = []
    for y0 in random_states(P, 10 * n_orbits, rng):
        X = section_points(P, y0, T, (0.0, 0.0, 0.0, 1.0, 0.0, 0.0), 2 * MAX_CROSSINGS)
        if len(X) < MIN_CROSSINGS:
            continue
        m = len(X) // 10
        sp = [_spread(X[i * m:(i + 1) * m]) for i in range(10)]
        out.append((float(kendalltau(np.arange(10), sp).statistic),
                    abs(sp[-1] - sp[0]) / sp[0]))
        if len(out) == n_orbits:
            break
    return out


# --- the checks ----------------------------------------------------------------------------------

@check("negative_measure")
def check_negative_measure(catalogue, case, claim, *, n_points=N_POINTS_NEG,
                           settings=N_SETTINGS_NEG, drift=True):
    rng = np.random.default_rng(11)
    ev: dict = {}
    worst_n, worst_c = 0.0, 0.0
    cand = {name: 0.0 for name, _ in CANDIDATES.get(case.id, ())}
    named = claim.check_args.formula       # a candidate density the claim names, if any
    if named:
        cand[named] = measure_residual(catalogue, case, claim, named)
    drawn = []
    for _ in range(settings):
        P = case_params(case, claim, rng)
        n_, c_ = position_density_test(P, rng, n_points)
        worst_n, worst_c = max(worst_n, n_), max(worst_c, c_)
        for name, rho in CANDIDATES.get(case.id, ()):
            cand[name] = max(cand[name], liouville_residual(P, rho, rng, n_points))
        drawn.append(P)
    ev["position-only density: max |c . normal| / |c|"] = worst_n
    ev["position-only density: max circulation of the 1-form"] = worst_c
    for name, res in cand.items():
        ev[f"Liouville residual of {name}"] = res
    Pc, ctext = control_params(case, drawn[0], CONTROLS)
    if Pc is not None:
        cn, cc = position_density_test(Pc, rng, n_points)
        ev["control"] = ctext
        ev["control: max |c . normal| / |c|"] = cn
        ev["control: max circulation"] = cc
    exists = worst_n <= TOL and worst_c <= TOL
    if exists:
        found = [n for n, r in cand.items() if r <= TOL]
        msg = ("a density of the position alone exists here: the Liouville conditions hold "
               f"to round-off (normal {worst_n:.1e}, circulation {worst_c:.1e})")
        if found:
            msg += f"; it is {found[0]} (Liouville residual {cand[found[0]]:.1e})"
            ev["found density"] = found[0]
        others = [f"{n}: {r:.2e}" for n, r in cand.items() if r > TOL]
        if others:
            msg += "; fails: " + ", ".join(others)
        return Outcome("fails", max(worst_n, worst_c), msg, evidence=ev)
    msg = ("evidence of no invariant measure: no density of the position alone (obstruction "
           f"{max(worst_n, worst_c):.2e} > {TOL:g}")
    if Pc is not None:
        msg += f"; control, {ctext}: {max(cn, cc):.1e}"
    msg += ")"
    if drift and drawn[0].model.model == L.MODEL_FULL:    # compact energy levels only
        case_d = section_drift(drawn[0], rng)
        ev["section spread per orbit (Kendall tau, relative change), case"] = case_d
        ctrl_d = section_drift(Pc, rng) if Pc is not None else []
        ev["section spread per orbit (Kendall tau, relative change), control"] = ctrl_d
        ctrl_change = max((c for _, c in ctrl_d), default=0.0)
        trending = [(t, c) for t, c in case_d if abs(t) >= 0.9 and c > 10 * ctrl_change]
        msg += (f"; {len(trending)} of {len(case_d)} orbits drift monotonically on the "
                f"section over t = {T_LONG:g} (attracting sets)")
        if trending:
            msg += f", by up to {max(c for _, c in trending):.2f}"
        if Pc is not None:
            msg += f" (control orbits change by <= {ctrl_change:.1e})"
    if claim.id.endswith("hamiltonian"):
        msg += "; a Hamiltonian form after a change of time would carry a smooth measure"
    return Outcome("evidence", max(worst_n, worst_c), msg, evidence=ev)


def orbit_thickness(X, drop):
    """Medians of s2/s1 and s3/s1 over the 24-point neighbourhoods of the section points X
    (the section coordinate `drop` removed, each coordinate scaled by its spread, floored
    at 1% of the largest)."""
    Y = np.delete(X, drop, axis=1)
    sd = Y.std(0)
    Y = (Y - Y.mean(0)) / np.maximum(sd, 1e-2 * sd.max())    # no blow-up of flat coordinates
    _, idx = cKDTree(Y).query(Y, NEIGHBOURS)
    s = np.array([np.linalg.svd(Y[i] - Y[i].mean(0), compute_uv=False)[:3] for i in idx])
    return float(np.median(s[:, 1] / s[:, 0])), float(np.median(s[:, 2] / s[:, 0]))


def map_scan(P, rng, n_orbits, stop_at=None, T=T_MAP):
    """(s2/s1, s3/s1) of up to n_orbits orbits with enough crossings of gamma3 = 0."""
    out = []
    for y0 in random_states(P, 4 * n_orbits, rng):
        X = section_points(P, y0, T, (0.0, 0.0, 0.0, 0.0, 0.0, 1.0))
        if len(X) < MIN_CROSSINGS:
            continue
        out.append(orbit_thickness(X, 5))
        if stop_at is not None and stop_at(out[-1]):
            break
        if len(out) == n_orbits:
            break
    return out


@check("negative_integral")
def check_negative_integral(catalogue, case, claim, *, n_orbits=N_MAP_ORBITS):
    rng = np.random.default_rng(12)
    P = case_params(case, claim, rng)
    known = KNOWN_INTEGRALS.get(case.id, 0)
    allowed = 2 - known                   # dimension of an orbit under one more integral
    stat = (lambda t: t[0]) if allowed == 1 else (lambda t: t[1])
    thick = THICK[allowed + 1]
    orbits = map_scan(P, rng, n_orbits, stop_at=lambda t: stat(t) >= thick)
    Pc, ctext = control_params(case, P, MAP_CONTROLS)
    ctrl = map_scan(Pc, rng, N_CONTROL_ORBITS) if Pc is not None else []
    name = "s2/s1" if allowed == 1 else "s3/s1"
    ev = {"orbits": len(orbits), f"max median {name}": max(map(stat, orbits), default=None),
          "orbit (s2/s1, s3/s1)": orbits, "threshold": thick,
          "known integrals besides H": known}
    if Pc is not None:
        ev["control"] = ctext
        ev[f"control: max median {name}"] = max(map(stat, ctrl), default=None)
    if not orbits:
        return Outcome("unchecked", None, "no orbit crossed the section often enough",
                       evidence=ev)
    best = max(map(stat, orbits))
    ctrl_best = max(map(stat, ctrl), default=0.0)
    if best >= thick and ctrl_best < thick:
        return Outcome("evidence", best, (
            f"evidence of no further integral: an orbit of the section map is "
            f"{allowed + 1}-dimensional (median {name} = {best:.2f} >= {thick}), thicker "
            f"than one more integral allows; control ({ctext}): {ctrl_best:.2f}"),
            evidence=ev)
    return Outcome("unchecked", best, (
        f"inconclusive: {len(orbits)} orbits of the section map, all at most "
        f"{allowed}-dimensional (max median {name} = {best:.2f} < {thick}; control "
        f"{ctrl_best:.2f}): no chaotic layer found at these parameters"), evidence=ev)

