"""What every job of a worker process (app.core.pool) does first: lower its CPU priority,
and the one way a job runs a simulate request (the run jobs of jobs.py and the prepare
jobs of kernel_prepare.py share it)."""

from __future__ import annotations

import os

# Worker processes run at a lower CPU priority than the server's event loop, so that on a
# busy machine (2 cores, 2 workers) the loop still answers /api/health and parses requests
# at once; the runs themselves lose little, as they have the cores to themselves otherwise.
WORKER_NICE = 5
_niced = False


def lower_priority() -> None:
    """Lower this process's priority once (a no-op where the system refuses)."""
    global _niced
    if not _niced:
        _niced = True
        try:
            os.nice(WORKER_NICE)
        except OSError:
            pass


def run_request(req: dict, max_steps: int):
    """The run of a simulate request (a dict of SimulateRequest's fields), at the worker's
    priority."""
    lower_priority()
    # lazy: numba and the kernels (solvers.simulate), imported at the worker's lower
    # priority, not at its start (unpickling a job of app.services.jobs imports this module)
    from solvers.simulate import simulate

    return simulate(req["case"], req["params"], req["state"], req["t_end"],
                    method=req["method"], rtol=req["rtol"], atol=req["atol"],
                    samples=req["samples"], project=req["project"], max_steps=max_steps,
                    allow_any_inertia=req["allow_any_inertia"], step=req.get("step"),
                    field=req.get("field", "auto"), precision=req.get("precision"))
