"""Compile every kernel specialization once so later processes load it from numba's cache.

Run by the README's commands (`./dev ...`) after installation: `python -m solvers.warmup`.
"""

import time

import numpy as np


def warm() -> float:
    t0 = time.perf_counter()
    from solvers.kernels.integrals import ENERGY
    from solvers.models.cases import registry
    from solvers.models.derivatives import field_jacobian, integral_gradient
    from solvers.simulate import compiled_methods, simulate, symmetric_methods

    seen = set()
    for cid, case in registry().items():
        key = (case.body == "flat",)
        if key in seen:
            continue
        seen.add(key)
        for method in compiled_methods():
            r = simulate(cid, case.example, case.state, 0.01, method=method, samples=3)
            simulate(cid, case.example, case.state, 0.01, method=method, samples=3,
                     project=True)
        simulate(cid, case.example, case.state, 0.01, method=symmetric_methods()[0],
                 samples=3, step=0.005)
        from solvers.models.cases import build
        m = build(cid, case.example)
        y = np.asarray(r.state[0])
        field_jacobian(m.model, m.p, y)
        integral_gradient(ENERGY, m.model, m.p, y)
    warm_ensembles()
    return time.perf_counter() - t0


def warm_ensembles() -> None:
    """The compiled ensemble (solvers/kernels/ensemble.py: one specialization serves every
    model on the general field), and, where integrate() runs the generated field by
    default, its twin for every case structure (one compile each), so that the first
    Poincare map of a server does not compile in a request."""
    from solvers.integrate.ensemble import _default_generated, integrate_ensemble
    from solvers.kernels import generate
    from solvers.models.cases import build, registry

    gen = _default_generated()
    seen = set()
    for cid, case in registry().items():
        m = build(cid, case.example)
        key = generate.structure(m.model, m.p) if gen else (m.model,)
        if key in seen:
            continue
        seen.add(key)
        integrate_ensemble(m.model, m.p, [case.state], [0.0, 0.01], generated=gen)


if __name__ == "__main__":
    print(f"kernels ready in {warm():.1f} s")
