"""The output times of a run, checked once: `checked_times` (finite, strictly increasing),
and `output_times`, the linspace of simulate() that the integrator's entries trust without
checking it again (their kernels read its private writable twin)."""

import math
import operator

import numpy as np

CACHE_MAX = 1024        # memoized grids (twice this many entries) before the memo is cleared


def f64(x) -> np.ndarray:
    """x as a fresh 1-D writable C float64 array (the one type the kernels are compiled
    for: a read-only or strided input would be another numba specialization, compiled
    anew); a 1-D input's copy as it is (ravel only where there is something to flatten)."""
    a = np.array(x, dtype=np.float64)
    return a if a.ndim == 1 else a.ravel()


def checked_times(t_out) -> np.ndarray:
    """t_out as a fresh float64 array, checked finite and strictly increasing."""
    if type(t_out) is list and len(t_out) <= FEW_TIMES:
        # a short list of Python floats (a run to T: [t0, T]) checked as it stands, before
        # any array exists, in place of the array, its list and the checks below: with p's
        # bytes as the plan's key, the plain entry is shorter at a short run
        # (docs/performance.md)
        prev = -math.inf
        for x in t_out:
            if type(x) is not float or not x > prev:
                break
            prev = x
        else:
            if t_out and prev < math.inf:
                return np.array(t_out)
    t = f64(t_out)
    # strictly increasing (a NaN fails the comparison) with finite ends: all finite. A few
    # times (a run to T: [t0, T]) are compared as Python floats: NumPy's slices, ufunc and
    # reduction cost most of a short run's entry (bench/limit.py --gap; docs/performance.md)
    if t.size <= FEW_TIMES:
        v = t.tolist()
        ok = bool(v) and math.isfinite(v[0]) and math.isfinite(v[-1]) \
            and all(map(operator.lt, v, v[1:]))
    else:
        ok = math.isfinite(t[0]) and math.isfinite(t[-1]) and bool((t[1:] > t[:-1]).all())
    if not ok:
        raise ValueError("t_out must be finite and strictly increasing; t_out[0] is t0")
    return t


FEW_TIMES = 8


# output times validated once: id -> (the read-only array handed out, a private writable
# twin for the kernel, which only reads it); the strong reference keeps the id unique
TRUSTED_TIMES: dict = {}


def output_times(t_end: float, samples: int) -> np.ndarray | None:
    """linspace(0, t_end, samples) as a read-only array that integrate() trusts without
    checking it again, memoized; None if the samples are not distinct."""
    key = (float(t_end), int(samples))
    hit = TRUSTED_TIMES.get(key)
    if hit is not None:
        return hit
    t = np.linspace(0.0, float(t_end), int(samples))
    if not (math.isfinite(t[-1]) and bool((t[1:] > t[:-1]).all())):
        return None
    twin = t.copy()
    t.setflags(write=False)
    if len(TRUSTED_TIMES) > 2 * CACHE_MAX:
        TRUSTED_TIMES.clear()
    TRUSTED_TIMES[key] = t
    TRUSTED_TIMES[id(t)] = (t, twin)
    return t


def trusted_or_checked(t_out) -> np.ndarray:
    """The kernel's twin of times made by output_times, else t_out checked."""
    hit = TRUSTED_TIMES.get(id(t_out))
    if hit is not None and hit[0] is t_out:
        return hit[1]
    return checked_times(t_out)
