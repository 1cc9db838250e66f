"""Many trajectories in one compiled call: `rk_integrate` (rk.py) for every row of Y0 in a
numba `prange` loop over the trajectories (issue 12, item 4).

Each trajectory is one unchanged call of the serial kernel on its own rows of the
preallocated outputs, so a trajectory of the ensemble takes exactly the steps, and gives
exactly the numbers, of the same trajectory integrated alone (tests/test_ensemble.py checks
it bit for bit): no state is shared between iterations, the kernel allocates its work
arrays per call, and fastmath stays off. The trajectories share the model, p, the method,
atol, the projection codes and the section; each has its own output times (a prefix
T_out[i, :n_out[i]] of a padded table), its own options iopt/fopt (step budget, h_max, ...)
and its own projection values. Statuses, stop times, final states, crossings and stats
come back per trajectory: a singular trajectory stops alone.

The generated twin (the same loop compiled against a case's generated `rk_integrate`,
solvers/kernels/generate.py) is this file with its import line changed; see
solvers/integrate/ensemble.py. parallel=True needs a threading layer; the Python entry
picks one and serialises launches (numba's workqueue layer is not thread-safe).
"""

import numba
from numba import prange

from solvers.kernels.rk import rk_integrate

# the serial kernel's flags (jit.py) and parallel=True: numba's cache stores parallel
# functions too, so a second process loads the machine code instead of compiling
pkernel = numba.njit(cache=True, error_model="numpy", nogil=True, parallel=True)


@pkernel
def rk_ensemble(model, p, Y0, T_out, n_out, A, c, b, E, P, meth, IOPT, FOPT, atol,
                proj_codes, PROJ_VALS, sec_coef, Y, CROSS_T, CROSS_Y, Y_STOP, STATS, STATUS,
                T_STOP, workers):
    """rk_integrate(model, p, Y0[i], T_out[i, :n_out[i]], ..., IOPT[i], FOPT[i], ...,
    PROJ_VALS[i], ..., Y[i], CROSS_T[i], CROSS_Y[i], Y_STOP[i], STATS[i]) for every i, in
    parallel; its (status, t_stop) into STATUS[i], T_STOP[i].

    Every threading layer but tbb hands each thread one contiguous block of a prange, so
    a run of costly neighbours (starts sorted by energy, say) would load one thread only;
    the trajectories are dealt round-robin instead: thread k of `workers` (numba's thread
    count of the launch; an argument, since reading it here would keep the function out of
    numba's cache) takes i = k, k + workers, ..."""
    n_traj = Y0.shape[0]
    w = max(1, min(workers, n_traj))
    for k in prange(w):
        for i in range(k, n_traj, w):
            st, ts = rk_integrate(model, p, Y0[i], T_out[i, :n_out[i]], A, c, b, E, P, meth,
                                  IOPT[i], FOPT[i], atol, proj_codes, PROJ_VALS[i], sec_coef,
                                  Y[i], CROSS_T[i], CROSS_Y[i], Y_STOP[i], STATS[i])
            STATUS[i] = st
            T_STOP[i] = ts
