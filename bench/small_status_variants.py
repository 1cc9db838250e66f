"""What the small kernel's status tests cost per call (issue 19 item 4: the time per call
over the limit on the same field).

The small kernel of a structure (solvers/kernels/small.py) tests the field's status after
every stage: a stage whose field is singular or not finite rejects the step at once. The
limit (bench/limit.py) drops the status, and LLVM with it the field's finite check. Here
the plane ball's small kernel source, as generated, is copied into a temporary directory
in three forms and compiled:
  as-is       the kernel as integrate() runs it;
  no-tests    the stages' status tests replaced by `if False:` (LLVM then drops the
              field's status computation too): not a valid kernel (a singular stage would
              go on), a yardstick only;
  one-branch  the statuses OR-ed over the stages and tested once before the new state
              (the same decision for a step whose stages are all regular);
and timed against limit-gen (bench/limit.py's DOP853 on the same generated field) on three
of the many-start mode's starts (a long one and two short ones), T = 1000, rtol 1e-6 and
1e-10: ns per rhs call, CPU time, best of 7 batches of back-to-back calls (3 ms each).
Each form must end on the same bits as the kernel as-is (checked).

    PYTHONPATH=$PWD .venv/bin/python bench/small_status_variants.py
        -> bench/results/small_status_variants.txt
"""

import importlib
import math
import os
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
sys.path[:0] = [str(ROOT), str(ROOT / "bench")]

import limit as B  # noqa: E402

import solvers.integrate.integrator as I  # noqa: E402
from solvers.kernels import small  # noqa: E402

OUT = ROOT / "bench" / "results" / "small_status_variants.txt"
CASE = "plane/chaplygin-ball"
STARTS = (1, 8, 4)          # |M| = 7.11, 0.134, 0.165
STAGE_TEST = """        if st != 0:
            status = st
            n_rej += 1
            rejected_last = True
            h = 0.25 * h
            continue
"""


def variants(src: str) -> dict:
    """The kernel's source in its three forms (module doc)."""
    n = src.count(STAGE_TEST)
    if n < 11:      # dop853's eleven stages after the first (the FSAL one is indented more)
        raise RuntimeError(f"the generated kernel's stage tests not found ({n})")
    one = src.replace(STAGE_TEST, "        sacc |= st\n")
    one = one.replace("        status = 0\n        z1_0", "        status = 0\n        sacc = 0\n"
                      "        z1_0", 1)
    i = one.index("        dd0 = lin")
    one = (one[:i] + STAGE_TEST.replace("st != 0", "sacc != 0").replace("status = st",
                                                                         "status = sacc")
           + one[i:])
    return {"as-is": src, "no-tests": src.replace(STAGE_TEST, STAGE_TEST.replace(
        "if st != 0:", "if False:")), "one-branch": one}


def main() -> None:
    # the many-start mode's case, parameters and draws (bench/limit.py's seed 19)
    _, starts, model, p = B._drawn(B.work_precision_case(CASE)[0], np.random.default_rng(19))
    p = np.array(p)     # writable, as integrate() passes it (one numba specialization)
    mod = small.small_kernel(model.model, p, "dop853")
    src = Path(mod.__file__).read_text()
    tmp = Path(tempfile.mkdtemp(prefix="small-status-"))
    sys.path[:0] = [str(tmp), str(Path(mod.__file__).parent)]   # the ops module beside it
    runs = {}
    for k, text in variants(src).items():
        name = "status_" + k.replace("-", "_")
        (tmp / f"{name}.py").write_text(text)
        runs[k] = importlib.import_module(name).run
    lim = B.make_scalar_dop853(*B._gen_field(model.model, p))
    n_state = len(starts[0])
    control = I.integrate.__kwdefaults__["control"]
    T = 1000.0
    t_out = np.array([0.0, T])
    load0 = os.getloadavg()
    lines = [f"bench/small_status_variants.py: {CASE}'s small kernel (dop853) in three forms "
             "against limit-gen, ns per rhs call, CPU time, best of 7 batches of 3 ms; "
             f"T = {T:g}; load average at the start: {load0[0]:.2f} {load0[1]:.2f} "
             f"{load0[2]:.2f}",
             "  as-is: as integrate() runs it; no-tests: the stages' status tests removed "
             "(a yardstick, not a valid kernel); one-branch: the statuses OR-ed, one test "
             "per step"]
    for i in STARTS:
        y0 = starts[i]
        for rt in (1e-6, 1e-10):
            fopt, atol = I._plain_fopt(rt, control), I._plain_atol(rt, n_state)

            def kern(run, y0=y0, fopt=fopt, atol=atol):
                Y, ys = np.empty((2, n_state)), np.empty(n_state)
                st = np.zeros(5, dtype=np.int64)
                run(p, y0, t_out, 10_000_000, False, fopt, atol, Y, ys, st)
                return int(st[2]), Y[1]

            fns = {k: (lambda r=r: kern(r)) for k, r in runs.items()}
            fns["limit-gen"] = lambda y0=y0, rt=rt: (int(lim(y0, p, T, rt, rt)[2]), None)
            outs = {k: f() for k, f in fns.items()}
            same = all(np.array_equal(o[1], outs["as-is"][1]) and o[0] == outs["as-is"][0]
                       for k, o in outs.items() if o[1] is not None)
            if not same:
                raise RuntimeError(f"start {i} rtol {rt:g}: a form ended on other bits")
            t0 = time.perf_counter()
            fns["as-is"]()
            n = max(1, math.ceil(0.003 / max(time.perf_counter() - t0, 1e-7)))
            best = dict.fromkeys(fns, math.inf)
            for _ in range(7):
                for k, f in fns.items():      # interleaved
                    c0 = time.process_time()
                    for _ in range(n):
                        f()
                    best[k] = min(best[k], (time.process_time() - c0) / n)
            ns = {k: best[k] / outs[k][0] * 1e9 for k in fns}
            lines.append(
                f"start {i:2d} |M| = {np.linalg.norm(y0[:3]):5.3f} rtol {rt:.0e}: calls "
                f"{outs['as-is'][0]} (limit-gen {outs['limit-gen'][0]}), the same bits in "
                "every form; ns per call " + ", ".join(f"{k} {v:.1f}" for k, v in ns.items())
                + f"; as-is / limit-gen {ns['as-is'] / ns['limit-gen']:.3f}, no-tests / "
                f"limit-gen {ns['no-tests'] / ns['limit-gen']:.3f}")
    load1 = os.getloadavg()
    lines.append(f"load average at the end: {load1[0]:.2f} {load1[1]:.2f} {load1[2]:.2f}")
    text = "\n".join(lines) + "\n"
    print(text, end="")
    OUT.write_text(text)


if __name__ == "__main__":
    main()
