#!/usr/bin/env python3
"""Wall-clock timing of OpenSees on mbdbench's ``rc_cyclic_c01`` protocol.

Builds the ``_c01`` fiber column exactly as generate.py does (same module,
same constants), then times only the analysis calls:

* ``prelude_seconds``: the 10 load-control steps of the axial load;
* ``seconds``: the 5880 displacement-control steps of the lateral protocol
  (0.5 mm increments), including the per-leg ``integrator``/``analysis``
  re-issue that flips the increment sign, but no recording.

Model building and the prelude are outside ``seconds``.  The whole is
repeated ``RUNS`` times (``--runs N``) in fresh domains and the best (smallest) time is
reported, together with the global Newton iteration count of that protocol
and the seconds per global iteration, as one JSON object on stdout.

Meant to run single-threaded and pinned, e.g.::

    OMP_NUM_THREADS=1 OPENBLAS_NUM_THREADS=1 taskset -c 1 \\
        v/bin/python references/fiber_column/opensees/time_cyclic.py

(the two thread variables are also forced below, before OpenSees loads).
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

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import generate as gen  # noqa: E402
import openseespy.opensees as ops  # noqa: E402

RUNS = 5                 # best of RUNS
SCENE = "rc_cyclic_c01"  # timed scene
MATS = "c01"             # its material set in generate.MATERIALS


def one_run():
    gen.build_column(MATS)
    # axial prelude (timed separately)
    ops.timeSeries("Linear", 1)
    ops.pattern("Plain", 1, 1)
    ops.load(2, 0.0, -gen.P_AXIAL, 0.0)
    gen.set_static_solver(algorithm=gen.ALGORITHM[SCENE])
    ops.integrator("LoadControl", 1.0 / gen.AXIAL_STEPS)
    ops.analysis("Static")
    t0 = time.perf_counter()
    for k in range(gen.AXIAL_STEPS):
        if ops.analyze(1) != 0:
            raise gen.NotConverged("axial step %d" % (k + 1))
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
    return t_lateral, t_prelude, iters, steps


def main():
    ap = argparse.ArgumentParser(description="time OpenSees on rc_cyclic_c01")
    ap.add_argument("--runs", type=int, default=RUNS,
                    help="fresh-domain runs, the best reported (default %d)" % RUNS)
    n = ap.parse_args().runs
    runs = [one_run() for _ in range(n)]
    best = min(runs, key=lambda r: r[0])
    out = {
        "scene": SCENE,
        "runs": n,
        "seconds": best[0],
        "global_iterations": best[2],
        "steps": best[3],
        "seconds_per_global_iteration": best[0] / best[2],
        "prelude_seconds_best": min(r[1] for r in runs),
        "all_seconds": [r[0] for r in runs],
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
