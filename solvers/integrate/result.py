"""What a compiled run returns: `IntegrationResult`, the kernel's status as a message, and
`result()`, which makes the record from a kernel's output arrays (the integrator's entries
and the ensembles share it: solvers/integrate/integrator.py, ensemble.py)."""

from dataclasses import dataclass, field

import numpy as np

from solvers.kernels import gauss, rk
from solvers.kernels import layout as L


@dataclass(slots=True)   # not frozen: a frozen init costs more per call (the thin entry)
class IntegrationResult:
    t: np.ndarray                 # output times reached (a prefix of t_out)
    y: np.ndarray                 # (len(t), n) states there
    status: int
    message: str
    t_stop: float                 # where the integration stopped
    y_stop: np.ndarray
    steps: int
    rejected: int
    rhs_calls: int
    wall_s: float
    method: str
    crossings_t: np.ndarray = field(default_factory=lambda: np.empty(0))
    crossings_y: np.ndarray = field(default_factory=lambda: np.empty((0, 0)))
    vector_field: str = "general"   # what the kernel ran: generated | general
    kernel: str = "rk"              # which compiled form: small | rk (the loop kernel, general
                                    # or generated) | gauss

    @property
    def success(self) -> bool:
        return self.status in rk.SUCCESS

    @property
    def budget_exhausted(self) -> bool:
        return self.status == rk.MAX_STEPS


_INTEGRATOR_STATUS_TEXT = {**rk.STATUS_TEXT, **gauss.STATUS_TEXT}


def status_message(status: int) -> str:
    if 0 <= status < len(L.STATUS_TEXT):
        return L.STATUS_TEXT[status]
    return _INTEGRATOR_STATUS_TEXT.get(status, f"unknown status {status}")


OK_TEXT = L.STATUS_TEXT[L.OK]


_S_ORDER = (rk.S_ACCEPTED, rk.S_REJECTED, rk.S_RHS, rk.S_SAMPLES, rk.S_CROSSINGS)
if _S_ORDER != (0, 1, 2, 3, 4):     # result() unpacks the counters in this order
    raise ImportError(f"rk.py's stats indices changed: {_S_ORDER}")


def result(t_out, Y, y_stop, stats, status, t_stop, wall, method, cross_t, cross_y, used,
            kernel, copy_crossings=True) -> IntegrationResult:
    # the counters as Python ints in one call, the fields positional, Y whole when every
    # sample was reached: shorter than five int() of NumPy scalars, keywords and views
    # (a short plain run's entry, bench/limit.py --gap)
    accepted, rejected, calls, m, k = stats.tolist()      # rk.py's S_* order (_S_ORDER)
    if copy_crossings:
        cross_t, cross_y = cross_t[:k].copy(), cross_y[:k].copy()
    message = status_message(status)
    if status != L.OK:
        message += f" (stopped at t = {t_stop:.17g})"
    whole = m == t_out.shape[0]
    # IntegrationResult(t, y, status, message, t_stop, y_stop, steps, rejected, rhs_calls,
    # wall_s, method, crossings_t, crossings_y, vector_field, kernel)
    return IntegrationResult(
        t_out.copy() if whole else t_out[:m].copy(), Y if whole else Y[:m], int(status),
        message, float(t_stop), y_stop, accepted, rejected, calls, wall, method, cross_t,
        cross_y, used, kernel)
