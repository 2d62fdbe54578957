#!/usr/bin/env python3
"""Wall-clock timing of OpenSees on mbdbench's ``rc_cyclic_c01`` protocol.

Each of ``--runs N`` runs (default 5) builds the ``_c01`` fiber column in a
fresh OpenSees domain exactly as generate.py does (same module, same
constants) and times, with ``time.perf_counter`` around the calls only:

* ``build``: ``generate.build_column`` (nodes, materials, the fiber section,
  the transformation, the element) and the axial load pattern, analysis
  objects and settings of the prelude;
* ``prelude``: the 10 load-control steps of the axial load;
* ``lateral``: the 5880 displacement-control steps of the lateral protocol
  (0.5 mm increments), including the per-leg ``integrator``/``analysis``
  re-issue that flips the increment sign, but no recording.

Printed as one JSON object on stdout: every run's three times (``per_run``,
in run order), the best (smallest) lateral time as ``seconds`` with its
global Newton iteration count (``testIter`` summed over the lateral steps:
the corrector iterations after DisplacementControl's predictor solve) and
step count, the prelude's (LoadControl's: ``testIter`` counts every solve of
its steps), and the OpenSees and openseespy versions.  Python's start-up and
the import of openseespy are outside every time.

Meant to run single-threaded and pinned, e.g.::

    OMP_NUM_THREADS=1 OPENBLAS_NUM_THREADS=1 taskset -c 1 \\
        v/bin/python references/fiber_column/opensees/time_cyclic.py

(the two thread variables are also forced below, before OpenSees loads).
``speed_c01.py`` runs it against mbdbench.
"""

import os

# single-threaded BLAS/LAPACK; must be set before openseespy is imported
os.environ["OMP_NUM_THREADS"] = "1"
os.environ["OPENBLAS_NUM_THREADS"] = "1"

import argparse  # noqa: E402
import json  # noqa: E402
import platform  # noqa: E402
import sys  # noqa: E402
import time  # noqa: E402

# no __pycache__ in the references folder: mbdbench's tests copy the folder file by file
sys.dont_write_bytecode = True
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import generate as gen  # noqa: E402
import openseespy.opensees as ops  # noqa: E402

RUNS = 5                 # runs in fresh domains
SCENE = "rc_cyclic_c01"  # timed scene
MATS = "c01"             # its material set in generate.MATERIALS


def one_run():
    """One fresh-domain run: its build, prelude and lateral times, iterations, steps."""
    t0 = time.perf_counter()
    gen.build_column(MATS)
    ops.timeSeries("Linear", 1)
    ops.pattern("Plain", 1, 1)
    ops.load(2, 0.0, -gen.P_AXIAL, 0.0)
    gen.set_static_solver(algorithm=gen.ALGORITHM[SCENE])
    ops.integrator("LoadControl", 1.0 / gen.AXIAL_STEPS)
    ops.analysis("Static")
    t_build = time.perf_counter() - t0
    prelude_iters = 0
    t0 = time.perf_counter()
    for k in range(gen.AXIAL_STEPS):
        if ops.analyze(1) != 0:
            raise gen.NotConverged("axial step %d" % (k + 1))
        prelude_iters += ops.testIter()
    t_prelude = time.perf_counter() - t0
    ops.loadConst("-time", 0.0)
    ops.timeSeries("Linear", 2)
    ops.pattern("Plain", 2, 2)
    ops.load(2, 1.0, 0.0, 0.0)
    legs = gen.protocol_legs(gen.DU)
    iters = 0
    steps = 0
    t0 = time.perf_counter()
    for sign, n in legs:
        ops.integrator("DisplacementControl", 2, 1, sign * gen.DU)
        ops.analysis("Static")
        for _ in range(n):
            if ops.analyze(1) != 0:
                raise gen.NotConverged("lateral step %d" % (steps + 1))
            iters += ops.testIter()
            steps += 1
    t_lateral = time.perf_counter() - t0
    return {"build": t_build, "prelude": t_prelude, "lateral": t_lateral,
            "iterations": iters, "steps": steps, "prelude_iterations": prelude_iters,
            "prelude_steps": gen.AXIAL_STEPS}


def main():
    ap = argparse.ArgumentParser(description="time OpenSees on rc_cyclic_c01")
    ap.add_argument("--runs", type=int, default=RUNS,
                    help="fresh-domain runs, each reported (default %d)" % RUNS)
    n = ap.parse_args().runs
    if n < 1:
        raise SystemExit("--runs must be at least 1")
    runs = [one_run() for _ in range(n)]
    best = min(runs, key=lambda r: r["lateral"])
    out = {
        "scene": SCENE,
        "runs": n,
        "per_run": runs,
        "seconds": best["lateral"],
        "global_iterations": best["iterations"],
        "steps": best["steps"],
        "prelude_iterations": best["prelude_iterations"],
        "prelude_steps": best["prelude_steps"],
        "seconds_per_global_iteration": best["lateral"] / best["iterations"],
        "algorithm": gen.ALGORITHM[SCENE][0],
        "tol": gen.GLOBAL_TOL,
        "element_tol": gen.ELEMENT_TOL,
        "affinity": sorted(os.sched_getaffinity(0)),
        "opensees": gen.OPENSEES_VERSION,
        "openseespy": gen.OPENSEESPY_VERSION,
        "python": platform.python_version(),
    }
    print(json.dumps(out, indent=1))


if __name__ == "__main__":
    main()
