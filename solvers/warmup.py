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
    return time.perf_counter() - t0


if __name__ == "__main__":
    print(f"kernels ready in {warm():.1f} s")
