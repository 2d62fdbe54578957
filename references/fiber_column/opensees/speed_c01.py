#!/usr/bin/env python3
"""Interleaved speed comparison of mbdbench and OpenSees on ``rc_cyclic_c01``.

The whole lateral protocol of ``rc_cyclic_c01`` (5880 displacement-control
steps of 0.5 mm, plain Newton, energy-increment tolerance 1e-20, one
force-based element with 5 Lobatto sections), both sides single-threaded and
pinned to the same core, in ``--rounds`` interleaved rounds.  Each round runs

* OpenSees: ``time_cyclic.py --runs 3`` (the analysis calls of the protocol
  only, best of 3 fresh domains);
* mbdbench: ``mbdbench run`` of ``so3 / newton_disp / force_based`` at
  ``dt 1`` (the same 0.5 mm increments), whose ``wall_s.min`` is the best of
  the suite's 3 timing repeats of the whole run without observation, the
  10-step axial prelude included (OpenSees' prelude is outside its time).

The best time of each side over all rounds (best of 3 x rounds), their ratio,
and the cost per global iteration are printed as one JSON object.  The two
iteration counts are not defined alike: OpenSees' ``testIter`` counts the
corrector iterations after DisplacementControl's predictor solve, mbdbench's
``newton_iters`` counts every solve, the one that carries the prescribed
increment included; ``solves`` puts both on mbdbench's count.

Usage (from the repository root, after ``cargo build --release``)::

    v/bin/python references/fiber_column/opensees/speed_c01.py --cpu 1
"""

import argparse
import json
import os
import platform
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.normpath(os.path.join(HERE, "..", "..", ".."))


def run_opensees(cpu, runs):
    out = subprocess.run(
        ["taskset", "-c", str(cpu), sys.executable,
         os.path.join(HERE, "time_cyclic.py"), "--runs", str(runs)],
        check=True, capture_output=True, text=True).stdout
    return json.loads(out[out.index("{"):out.rindex("}") + 1])


def run_mbdbench(cpu, binary):
    with tempfile.TemporaryDirectory() as tmp:
        subprocess.run(
            ["taskset", "-c", str(cpu), binary, "run",
             "--case", "fiber_column_cyclic", "--scene", "rc_cyclic_c01",
             "--param", "so3", "--integrator", "newton_disp",
             "--formulation", "force_based", "--jobs", "1",
             "--out", os.path.join(tmp, "out")],
            check=True, capture_output=True, text=True)
        with open(os.path.join(tmp, "out", "summary.json")) as f:
            records = json.load(f)["records"]
    rec = [r for r in records if r["status"] == "ok" and r.get("dt") == 1.0]
    if len(rec) != 1:
        raise SystemExit("mbdbench: no completed dt = 1 record of rc_cyclic_c01")
    return rec[0]


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--cpu", type=int, default=1, help="the core both sides run on")
    ap.add_argument("--rounds", type=int, default=5)
    ap.add_argument("--binary", default=os.path.join(ROOT, "target", "release", "mbdbench"))
    a = ap.parse_args()
    ops, ours = [], []
    for k in range(a.rounds):
        ops.append(run_opensees(a.cpu, 3))
        ours.append(run_mbdbench(a.cpu, a.binary))
        print("round %d: OpenSees %.4f s, mbdbench %.4f s" % (
            k + 1, ops[-1]["seconds"], ours[-1]["wall_s"]["min"]), file=sys.stderr)
    o = min(ops, key=lambda r: r["seconds"])
    m = min(ours, key=lambda r: r["wall_s"]["min"])
    t_o, t_m = o["seconds"], m["wall_s"]["min"]
    it_m = m["stats"]["newton_iters"]
    solves_o = o["global_iterations"] + o["steps"]
    print(json.dumps({
        "scene": "rc_cyclic_c01",
        "rounds": a.rounds,
        "cpu": a.cpu,
        "opensees_seconds": t_o,
        "mbdbench_seconds": t_m,
        "ratio": t_o / t_m,
        "opensees_iterations": o["global_iterations"],
        "opensees_solves": solves_o,
        "mbdbench_solves": it_m,
        "mbdbench_element_iterations": m["stats"].get("element_iters"),
        "opensees_seconds_per_iteration": t_o / o["global_iterations"],
        "opensees_seconds_per_solve": t_o / solves_o,
        "mbdbench_seconds_per_solve": t_m / it_m,
        "opensees_all": [r["seconds"] for r in ops],
        "mbdbench_all": [r["wall_s"]["min"] for r in ours],
        "opensees": o["opensees"],
        "openseespy": o["openseespy"],
        "python": platform.python_version(),
        "machine": platform.processor() or platform.machine(),
    }, indent=1))


if __name__ == "__main__":
    main()
