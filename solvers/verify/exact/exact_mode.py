"""A context in which the formulas' np.linalg.solve / inv / det (and np.result_type) and the
models' revolution bodies accept object arrays of jets.

The formulas of solvers/verify/formulas are written with NumPy so that complex states give
complex-step derivatives; the same code then runs on object arrays of `Jet`s, except for
np.linalg, which is LAPACK (floats only). `exact_linalg()` swaps in Gaussian elimination
over the jets (linalg.py) for object arrays and leaves every other dtype to NumPy's own
routines.
"""

from contextlib import contextmanager

import numpy as np

import solvers.verify.variables as V
from solvers.kernels import layout as L
from solvers.models.reduced_systems import RevBody
from solvers.models.revolution import Profile, check_revolution
from solvers.verify.exact.linalg import det, inv, is_exact, solve
from solvers.verify.exact.model import to_reduced


@contextmanager
def exact_linalg():
    """np.linalg.solve/inv/det dispatch object arrays to the exact routines above."""
    orig = np.linalg.solve, np.linalg.inv, np.linalg.det

    def _solve(A, b):
        return solve(A, b) if is_exact(A, b) else orig[0](A, b)

    def _inv(A):
        return inv(A) if is_exact(A) else orig[1](A)

    def _det(A):
        return det(A) if is_exact(A) else orig[2](A)

    result_type = np.result_type

    def _result_type(*args):
        # a formula that sizes its arrays by np.result_type(x, ...) gets object arrays
        if any(type(a).__name__ in ("Jet", "Radical", "Angle") for a in args):
            return np.dtype(object)
        return result_type(*args)

    np.linalg.solve, np.linalg.inv, np.linalg.det = _solve, _inv, _det
    np.result_type = _result_type
    try:
        with _exact_bodies():
            yield
    finally:
        np.linalg.solve, np.linalg.inv, np.linalg.det = orig
        np.result_type = result_type


@contextmanager
def _exact_bodies():
    """Profile / RevBody (solvers/models) read their numbers with float(p[...]); from an
    object array of jets they keep the exact numbers instead (same fields, same checks)."""
    prof0, rev0 = Profile.__dict__["from_params"], RevBody.__dict__["from_params"]

    def prof(cls, p):
        if not is_exact(p):
            return prof0.__get__(None, cls)(p)
        check_revolution(p)
        return cls(p[L.B11], p[L.B33], p[L.BALL_C], p[L.DISK_D], p[L.A3])

    def rev(cls, p):
        if not is_exact(p):
            return rev0.__get__(None, cls)(p)
        return cls(p[L.I1], p[L.I3], p[L.MASS], p[L.CURV], p[L.S3], Profile.from_params(p))

    red0 = V.to_reduced

    def red(p, y):
        return to_reduced(p, y) if is_exact(p) else red0(p, y)

    Profile.from_params, RevBody.from_params = classmethod(prof), classmethod(rev)
    V.to_reduced = red
    try:
        yield
    finally:
        Profile.from_params, RevBody.from_params = prof0, rev0
        V.to_reduced = red0
