"""Many trajectories in one compiled call: `rk_integrate` (loop_kernel.py) for every row of Y0 in a
numba `prange` loop over the trajectories.

Each trajectory is one unchanged call of the serial kernel on its own rows of the
preallocated outputs, so a trajectory of the ensemble takes exactly the steps, and gives
exactly the numbers, of the same trajectory integrated alone (tests/test_ensemble.py checks
it bit for bit): no state is shared between iterations, the kernel allocates its work
arrays per call, and fastmath stays off. The trajectories share the model, p, the method,
atol, the projection codes and the section; each has its own output times (a prefix
T_out[i, :n_out[i]] of a padded table), its own options iopt/fopt (step budget, h_max, ...)
and its own projection values. Statuses, stop times, final states, crossings and stats
come back per trajectory: a singular trajectory stops alone.

The generated twin (the same loop compiled against a case's generated `rk_integrate`) is
this module's function bound to that kernel (module_cache.bound_module, solvers/kernels/bind.py);
see solvers/integrate/ensemble.py. parallel=True needs a threading layer; the Python entry
picks one and serialises launches (numba's workqueue layer is not thread-safe).
"""

import numba
from numba import prange, types
from numba.core import cgutils
from numba.extending import intrinsic

from solvers.kernels.loop_kernel import rk_integrate

# the serial kernel's flags (jit.py) and parallel=True: numba's cache stores parallel
# functions too, so a second process loads the machine code instead of compiling
pkernel = numba.njit(cache=True, error_model="numpy", nogil=True, parallel=True)


@intrinsic
def fetch_add(typingctx, counter):
    """counter[0] += 1 atomically; returns the value before (an LLVM atomicrmw add)."""
    if not (isinstance(counter, types.Array) and counter.dtype == types.int64):
        return None

    def codegen(context, builder, sig, args):
        aryty = sig.args[0]
        ary = context.make_array(aryty)(context, builder, args[0])
        ptr = cgutils.get_item_pointer(context, builder, aryty, ary,
                                       [context.get_constant(types.intp, 0)])
        return builder.atomic_rmw("add", ptr, context.get_constant(types.int64, 1),
                                  "monotonic")

    return types.int64(counter), codegen


@pkernel
def rk_ensemble(model, p, Y0, T_out, n_out, A, c, b, E, P, meth, IOPT, FOPT, atol,
                proj_codes, PROJ_VALS, sec_coef, Y, CROSS_T, CROSS_Y, Y_STOP, STATS, STATUS,
                T_STOP, workers, counter):
    """rk_integrate(model, p, Y0[i], T_out[i, :n_out[i]], ..., IOPT[i], FOPT[i], ...,
    PROJ_VALS[i], ..., Y[i], CROSS_T[i], CROSS_Y[i], Y_STOP[i], STATS[i]) for every i, in
    parallel; its (status, t_stop) into STATUS[i], T_STOP[i].

    Scheduling is dynamic: every threading layer but tbb hands each thread a fixed block
    of a prange, so a thread dealt the costly trajectories (or descheduled on a busy
    machine) would leave the other idle. Here the prange is one iteration per worker
    (`workers`: numba's thread count of the launch; an argument, since reading it here
    would keep the function out of numba's cache), and each worker takes the next
    trajectory from a shared counter (counter[0] = 0 on entry) until none is left."""
    n_traj = Y0.shape[0]
    w = max(1, min(workers, n_traj))
    for _worker in prange(w):
        while True:
            i = fetch_add(counter)
            if i >= n_traj:
                break
            st, ts = rk_integrate(model, p, Y0[i], T_out[i, :n_out[i]], A, c, b, E, P, meth,
                                  IOPT[i], FOPT[i], atol, proj_codes, PROJ_VALS[i], sec_coef,
                                  Y[i], CROSS_T[i], CROSS_Y[i], Y_STOP[i], STATS[i])
            STATUS[i] = st
            T_STOP[i] = ts
