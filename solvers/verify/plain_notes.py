"""What a reader is told beside an "evidence for", "evidence against" or "inconclusive" mark:
plain words built from the check's own numbers (the record's `evidence` and
`residual`), not the checking code's `message`, which names statistics and programs
(s3/s1, div(ellipsoid_density v), no_measure). The message stays in the record: the JSON
API and the case page's Details toggle show it unchanged.

Each note says what was found, no more: a numerical test is evidence, not a proof, and a
test that could not decide says what it saw. A check whose numbers this module does not
know gets a sentence that says only that, and points to the details."""

from __future__ import annotations


def _tol() -> float:
    # the checks' tolerance
    # lazy: every check (solvers.verify.checks: scipy, flint), not when the marks'
    # levels (solvers.verify.levels) are read without running a check
    from solvers.verify.checks.common import TOL

    return TOL

# the pointwise checks of a negative claim ("the paper says this does NOT hold"):
# what "does not hold" means for each, in words (checks/pointwise.py, checks/structure.py)
NEGATIVE_POINTWISE = {
    "measure_fails": "is not an invariant density of the flow here",
    "integral_fails": "is not conserved along the motion here",
    "jacobi_fails": "does not satisfy the Jacobi identity here",
}

FALLBACK = {
    "evidence-for": "numerical evidence supports it (not a proof); the check's numbers are "
                    "in the details",
    "evidence-against": "numerical evidence goes against it (not a proof); the check's "
                        "numbers are in the details",
    "inconclusive": "the check ran and could not decide; what it measured is in the details",
}


def _e(x) -> str:
    return f"{x:.1e}" if isinstance(x, (int, float)) else "n/a"


def _dims(n: int) -> str:
    return {1: "a curve", 2: "a surface"}.get(n, f"a {n}-dimensional set")


def _negative_integral(r: dict, ev: dict) -> str | None:
    """checks/negative.py check_negative_integral: orbits of the Poincaré map, their
    thickness (median singular-value ratio of point neighbourhoods) against a threshold."""
    known = ev.get("known integrals besides H")
    if not isinstance(known, int):
        return None
    allowed = 2 - known                     # an orbit's dimension under one more integral
    n = ev.get("orbits") or 0
    if not n:
        return "no orbit crossed the Poincaré section often enough to be measured"
    stat = "s2/s1" if allowed == 1 else "s3/s1"
    best, thick = ev.get(f"max median {stat}"), ev.get("threshold")
    ctrl, ctext = ev.get(f"control: max median {stat}"), ev.get("control")
    if not isinstance(best, (int, float)) or not isinstance(thick, (int, float)):
        return None
    control = (f"; in the control case ({ctext}), which has the integral, the orbits "
               f"measure {ctrl:.2f}") if ctext and isinstance(ctrl, (int, float)) else ""
    if best >= thick and not (isinstance(ctrl, (int, float)) and ctrl >= thick):
        return (f"an orbit of the Poincaré map fills more than {_dims(allowed)} (thickness "
                f"{best:.2f}, threshold {thick:g}), which one further integral would not "
                f"allow{control}")
    if best >= thick:
        return (f"an orbit of the Poincaré map is thick ({best:.2f}, threshold {thick:g}), "
                f"but so are the control's, so the test does not tell the cases apart"
                f"{control}")
    return (f"{n} orbit{'s' * (n != 1)} of the Poincaré map, each lying on at most "
            f"{_dims(allowed)} (thickness at most {best:.2f}, below the threshold "
            f"{thick:g}): no chaotic layer was found at these parameters, which is what a "
            f"further integral would also give{control}")


def _negative_measure(r: dict, ev: dict, claim_id: str, TOL: float) -> str | None:
    """checks/negative.py check_negative_measure: the obstruction to a density of the
    position alone, a control that has one, and the drift of orbits on a section."""
    ob = [ev.get(k) for k in ("position-only density: max |c . normal| / |c|",
                              "position-only density: max circulation of the 1-form")]
    if not all(isinstance(x, (int, float)) for x in ob):
        return None
    out = (f"no density depending on the body's position alone is preserved by the flow: "
           f"the obstruction is {max(ob):.1e}, far above the tolerance {TOL:g}")
    ctrl = [ev.get(k) for k in ("control: max |c . normal| / |c|", "control: max circulation")]
    if ev.get("control") and all(isinstance(x, (int, float)) for x in ctrl):
        out += (f"; in the control case ({ev['control']}) the same test finds the density "
                f"({max(ctrl):.1e})")
    case_d = ev.get("section spread per orbit (Kendall tau, relative change), case")
    ctrl_d = ev.get("section spread per orbit (Kendall tau, relative change), control") or []
    if case_d:
        still = max((c for _, c in ctrl_d), default=0.0)
        trending = [c for t, c in case_d if abs(t) >= 0.9 and c > 10 * still]
        out += (f"; {len(trending)} of {len(case_d)} orbits spread or contract steadily on a "
                f"Poincaré section, as orbits do near attracting sets")
    if claim_id.endswith("hamiltonian"):
        out += ("; a Hamiltonian form after a change of time would carry such a density, so "
                "this weighs against one too")
    return out


def _returns(r: dict, ev: dict) -> str | None:
    """checks/formula_free.py check_linear_integrals_return: long runs return to the same
    values at crossings of one level; a control with the gyrostat off the axis."""
    spread = ev.get("max spread of (M, gamma), M3 at crossings / scale")
    if not isinstance(spread, (int, float)):
        return None
    out = (f"along {ev.get('runs')} long runs the motion comes back to the same M, γ and "
           f"M3 at each of {ev.get('crossings')} crossings of one level of γ3 (spread "
           f"{spread:.1e}), as two integrals linear in M require")
    c = ev.get("control: max spread")
    if isinstance(c, (int, float)):
        out += (f"; with the gyrostat moved off the axis (the control) the returns "
                f"{'break' if c > spread else 'do not break'} (spread {c:.1e})")
    return out


def note(r: dict, mark: str, what: str) -> str:
    """The plain note of one formula record `r` whose mark is evidence for / against or
    inconclusive; `what` names the printed formula as levels._what does."""
    check, ev = r.get("check"), r.get("evidence") or {}
    text = None
    if check == "negative_integral":
        text = _negative_integral(r, ev)
    elif check == "negative_measure":
        text = _negative_measure(r, ev, r.get("claim", ""), _tol())
    elif check == "linear_integrals_return":
        text = _returns(r, ev)
    elif check in NEGATIVE_POINTWISE and r.get("verdict") == "evidence":
        text = (f"as the paper says, {what} {NEGATIVE_POINTWISE[check]}: its residual "
                f"{_e(r.get('residual'))} is far above the tolerance {_tol():g}")
    elif check == "no_measure" and r.get("verdict") == "evidence":
        text = ("among the points tried, none shows a nonzero obstruction to a smooth "
                "invariant measure: nothing was proved either way")
    elif check == "no_measure" and any(k.startswith("control") for k in ev):
        text = ("the control case, which has an invariant measure, shows a nonzero "
                "obstruction too, so the test does not tell the cases apart here")
    elif check == "no_measure":
        text = ("the exact test rests on homogeneity: it needs a model of this case without "
                "gravity and without a gyrostat, which does not apply here; nothing was "
                "decided")
    elif check == "reduced_agrees" and mark == "inconclusive":
        text = ("the necessary conditions hold (the transformed motion conserves |M̃|² and "
                "(M̃, γ)); the target's inertia and time scale are not printed, so the full "
                "equivalence was not tested")
    elif check == "hamiltonian_attempt" and mark == "inconclusive":
        text = _hamiltonian_attempt(ev, _tol())
    return text or FALLBACK.get(mark, FALLBACK["inconclusive"])


def _hamiltonian_attempt(ev: dict, tol: float) -> str | None:
    """checks/structure.py check_hamiltonian_attempt: a construction the project tried for a
    Hamiltonian form the paper asserts without a formula; what failed, in words."""
    jac, flow = ev.get("Jacobi identity residual"), ev.get("flow residual")
    if not isinstance(jac, (int, float)) or not isinstance(flow, (int, float)):
        return None
    level, on = ev.get("level of"), ev.get("flow residual on the level")
    if jac <= tol and isinstance(on, (int, float)) and on <= tol:
        found = (f"the project's bracket is a Poisson bracket (Jacobi identity residual "
                 f"{_e(jac)}) and, after the change of time, generates the motion on the zero "
                 f"level of the integral {level} (residual {_e(on)}) but not on its other "
                 f"levels (residual {_e(flow)}); whether a Hamiltonian form exists there is "
                 "neither confirmed nor refuted")
    elif jac <= tol:
        found = (f"the project tried a Poisson bracket (Jacobi identity residual {_e(jac)}) "
                 f"that does not generate the motion (residual {_e(flow)})")
    elif flow <= tol:
        found = (f"the project tried a bracket that generates the motion after the change of "
                 f"time (residual {_e(flow)}) but is not a Poisson bracket (Jacobi identity "
                 f"residual {_e(jac)})")
    else:
        found = (f"the project tried a bracket that neither satisfies the Jacobi identity "
                 f"(residual {_e(jac)}) nor generates the motion (residual {_e(flow)})")
    if "neither confirmed" in found:
        return found
    return f"{found}; a failed attempt neither confirms nor refutes that a Hamiltonian form exists"
