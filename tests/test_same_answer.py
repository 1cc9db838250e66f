"""The same answer every time (issue 19): a request's numbers do not depend on what happens
to be compiled. The same simulation, Poincare map and scene run in a fresh process with an
empty generated-kernel cache (ROLLING_KERNEL_CACHE: nothing compiled for any structure),
again in a fresh process on the cache the first one left (warm), and in this process; the
bytes of their numbers must be equal.

Before, field="auto" ran the general field on a cold cache and the generated one once it
was compiled: the last bits differed (visibly on long chaotic runs). Now the route depends
on the request only (integrator.is_plain): a plain run takes the small kernel of its
structure, anything else the general field."""

import json
import os
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]

SCRIPT = r"""
import hashlib, json, sys
import numpy as np
from solvers.simulate import simulate
from solvers.maps.poincare import MapSpec, poincare
from solvers.models.kinematics import scene
from solvers.models.cases import registry

def h(*arrays):
    d = hashlib.sha256()
    for a in arrays:
        d.update(np.ascontiguousarray(a, dtype=np.float64).tobytes())
    return d.hexdigest()

out = {}
c = registry()["plane/unbalanced-ball"]
params = {**c.example, "g": 1.0}
r = simulate(c.id, params, c.state, 200.0, samples=401)
out["simulate"] = [h(r.t, r.state), r.stats["field"], r.stats["kernel"],
                   r.stats["steps"], r.stats["rhs_calls"]]
m = poincare("plane/chaplygin-ball", registry()["plane/chaplygin-ball"].example,
              MapSpec(energy=1.0, points=20), trajectories=2)
out["poincare"] = [h(*[tr.states for tr in m.trajectories],
                     *[tr.t for tr in m.trajectories])]
d = registry()["plane/round-disk"]
s = scene(d.id, d.example, d.state, 5.0, frames=50)
out["scene"] = hashlib.sha256(json.dumps(s, sort_keys=True, default=str).encode()
                              ).hexdigest()
print(json.dumps(out))
"""


def _run(cache: Path | None) -> dict:
    env = {**os.environ, "PYTHONPATH": str(ROOT)}
    if cache is not None:
        env["ROLLING_KERNEL_CACHE"] = str(cache)
    out = subprocess.run([sys.executable, "-c", SCRIPT], env=env, cwd=ROOT,
                         capture_output=True, text=True, timeout=1800, check=True)
    return json.loads(out.stdout.strip().splitlines()[-1])


def test_cold_and_warm_give_the_same_bytes(tmp_path):
    cache = tmp_path / "kernels"
    cache.mkdir()
    cold = _run(cache)                       # nothing compiled in this cache
    assert any(cache.iterdir())              # the cold run compiled its small kernel
    warm = _run(cache)                       # the same cache, now holding it
    here = _run(None)                        # the cache of this machine
    assert cold == warm == here, (cold, warm, here)
    assert cold["simulate"][1:3] == ["generated", "small"]
