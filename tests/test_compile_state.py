"""solvers/compile_state.py, the one owner of what is compiled: plan(request) names the
kernels from the request alone, is_compiled reads numba's index (no marker file), compile
compiles them; a kernel's name comes from the content hash of the kernels' sources (and the
tableau's), with no version number bumped by hand."""

import os
import re
import shutil
import subprocess
import sys
import textwrap
from pathlib import Path

import numpy as np
import pytest

from solvers import compile_state as cs
from solvers.kernels import baked
from solvers.models.cases import build, registry

ROOT = Path(__file__).resolve().parents[1]
BALL = "plane/chaplygin-ball"


def _req(case=BALL, **over):
    c = registry()[case]
    return cs.request(case, c.example, c.state, **over)


def test_plan_names_the_kernel_of_each_route():
    m = build(BALL, registry()[BALL].example)
    slots = cs.structure(m.model, m.p)[1]
    assert cs.plan(_req()) == [("small", m.model, slots, "dop853")]
    assert cs.plan(_req(method="vern9")) == [("small", m.model, slots, "vern9")]
    assert cs.plan(_req(project=True)) == [("general", m.model, "dop853", True, False)]
    assert cs.plan(_req(method="rk45")) == [("general", m.model, "rk45", False, False)]
    assert cs.plan(_req(field="general")) == [("general", m.model, "dop853", False, False)]
    assert cs.plan(_req(field="generated", project=True)) == [("generated", m.model, slots)]
    assert cs.plan(_req(method="gauss4", step=0.01)) == \
        [("general", m.model, "gauss4", False, True)]


def test_plan_of_a_taylor_run_names_its_precision_and_tol():
    from solvers.integrate import taylor_backend as tb

    m = build(BALL, registry()[BALL].example)
    keys = cs.plan(_req(method="taylor", rtol=1e-10, t_end=1.0))
    assert len(keys) == 1 and keys[0][0] == "taylor"
    (model, slots, _), k_positive, precision, tol = keys[0][1:]
    assert (model, slots) == cs.structure(m.model, m.p) and k_positive is False
    assert precision == tb.choose_precision(1e-10, 1.0) and tol == tb.snap_tol(1e-10)


def test_a_structure_key_does_not_depend_on_the_parameter_values():
    c = registry()[BALL]
    a = build(BALL, c.example)
    b = build(BALL, {k: 2.0 * v for k, v in c.example.items()})
    assert cs.small_key(a.model, a.p, "dop853") == cs.small_key(b.model, b.p, "dop853")


def test_an_unknown_key_is_an_error():
    with pytest.raises(ValueError, match="unknown kernel key"):
        cs.is_compiled(("nonsense", 1))


def test_no_hand_bumped_cache_version_is_left():
    found = [f"{p.relative_to(ROOT)}: {m.group(0)}"
             for p in (ROOT / "solvers").rglob("*.py")
             for m in re.finditer(r"^\w*VERSION\s*=.*$", p.read_text(), re.M)]
    assert found == []


def test_a_changed_tableau_coefficient_changes_the_stamp():
    tabs = baked.baked_tableaux(("dop853",))
    A, c, b, E, P, meth = tabs["dop853"]
    b2 = b.copy()
    b2[0] = np.nextafter(b2[0], 1.0)
    assert baked.tableaux_stamp({"dop853": (A, c, b2, E, P, meth)}) != baked.tableaux_stamp(tabs)


NAMES = textwrap.dedent('''
    from solvers.kernels import field_modules, module_cache, small
    from solvers.integrate import integrator  # noqa: F401  (provides the tableaux)
    from solvers.models.cases import build, registry

    c = registry()["plane/chaplygin-ball"]
    m = build(c.id, c.example)
    print(module_cache.sources_hash(), field_modules.module_name(m.model, m.p),
          small.module_name(m.model, m.p, "dop853"))
''')


def _names(src: Path) -> list[str]:
    out = subprocess.run([sys.executable, "-c", NAMES], cwd=src, capture_output=True,
                         text=True, timeout=300, env={**os.environ, "PYTHONPATH": str(src)})
    assert out.returncode == 0, out.stderr[-2000:]
    return out.stdout.split()


def test_editing_a_kernel_source_changes_every_key(tmp_path):
    """A copy of the sources, then one line added to a kernel's source (rk.py): the content
    hash, the generated field's module name and the small kernel's all change, so nothing
    compiled from the old text is loaded for the new one."""
    src = tmp_path / "src"
    for pkg in ("solvers", "catalogue"):
        shutil.copytree(ROOT / pkg, src / pkg, ignore=shutil.ignore_patterns(
            "__pycache__", "*.pyc", "*.nbi", "*.nbc"))
    before = _names(src)
    assert before == _names(ROOT)
    with open(src / "solvers" / "kernels" / "rk.py", "a") as f:
        f.write("\n# an edit\n")
    after = _names(src)
    assert len(after) == 3 and all(a != b for a, b in zip(before, after, strict=True))


PROBE = textwrap.dedent('''
    import json, sys
    from solvers import compile_state as cs
    from solvers.models.cases import registry

    c = registry()["sphere/flat-base"]
    req = cs.request(c.id, c.example, c.state)
    keys = cs.plan(req)
    before = [cs.is_compiled(k) for k in keys]
    done = cs.compile(keys, req) if sys.argv[1] == "compile" else 0
    print(json.dumps({"keys": [k[0] for k in keys], "before": before, "done": done,
                      "after": [cs.is_compiled(k) for k in keys]}))
''')


def _probe(cache: Path, what: str) -> dict:
    import json

    env = {**os.environ, "PYTHONPATH": str(ROOT), "ROLLING_KERNEL_CACHE": str(cache)}
    out = subprocess.run([sys.executable, "-c", PROBE, what], cwd=ROOT, env=env,
                         capture_output=True, text=True, timeout=900)
    assert out.returncode == 0, out.stderr[-2000:]
    return json.loads(out.stdout.strip().splitlines()[-1])


@pytest.mark.slow
def test_compile_then_is_compiled_across_processes_and_not_after_a_wipe(tmp_path):
    """An empty kernel cache: the plain run's small kernel is not compiled; compile()
    compiles it; a later process finds it compiled in numba's index (no marker file); with
    numba's files of the cache gone it is not compiled any more."""
    cache = tmp_path / "kernels"
    first = _probe(cache, "compile")
    assert first == {"keys": ["small"], "before": [False], "done": 1, "after": [True]}
    assert _probe(cache, "look")["before"] == [True]
    assert not list(cache.glob("*.ready"))
    shutil.rmtree(cache / "__pycache__")
    assert _probe(cache, "look")["before"] == [False]


def test_a_warm_server_prepares_a_generated_integrator_but_not_the_warmed_kernels():
    """The explorer's rule (app/services/kernel_prepare.py needed) on compile_state's keys:
    after the warm-up, a run needing the generated integrator (field = "generated" with a
    projection, which the warm-up does not compile) is prepared before its deadline; a
    plain run of an example structure and a general run are not."""
    from app.services import kernel_prepare
    from app.services.kernel_warmup import KernelWarmup

    warm = KernelWarmup()
    warm.state = "done"
    assert kernel_prepare.needed(warm, True, cs.plan(_req(field="generated", project=True)))
    assert not kernel_prepare.needed(warm, True, cs.plan(_req()))
    assert not kernel_prepare.needed(warm, True, cs.plan(_req(project=True)))
