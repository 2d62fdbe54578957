#!/usr/bin/env python3
"""Interleaved speed comparison of mbdbench and OpenSees on ``rc_cyclic_c01``.

The whole lateral protocol of ``rc_cyclic_c01`` (5880 displacement-control
steps of 0.5 mm, plain Newton, energy-increment tolerance 1e-20, one
force-based element with 5 Lobatto sections) after the 10-step axial prelude,
both sides single-threaded and pinned to the same core (``--cpu``).  A round
is one pinned process of each side per measurement, the sides alternating
(their order swapped every round, so that a drift of the machine's load falls
on both); the figure of each measurement is the MEDIAN over ``--rounds``
(at least 10) of the per-round ratios OpenSees' time / mbdbench's time, with
their minimum, quartiles and maximum.  Nothing here is needed by the Rust
build or its tests.

What each side times, per round:

1. Analysis only (model building excluded).

   * OpenSees: one process of ``time_cyclic.py --runs 3`` (three fresh
     domains one after another); its figure is the median over the three runs
     of prelude + lateral, timed with ``time.perf_counter`` around the
     ``analyze`` calls only (the 10 prelude steps and the 5880 lateral ones,
     with the per-leg ``integrator``/``analysis`` re-issue; no recording).
   * mbdbench: one process of ``mbdbench run`` of the one variant
     ``so3 / newton_disp / force_based`` (``--jobs 1``), whose timing pass
     (``src/suite.rs``, ``time_run``) runs the scene's ``dt 1`` point
     (the same 0.5 mm increments) three times without observation after the
     results pass; its figure is the record's ``wall_s.median``, the median
     of those three.  The CLI fixes the three repeats (no ``--repeats``), so
     both sides take the median of three runs in one process.  A timed run
     of mbdbench builds the column from the compiled scene (5 fiber sections
     of 82 fibers and the element, microseconds) and then runs the prelude
     and the protocol, all inside ``wall_s``: it times slightly more than
     OpenSees' figure does.

2. Model building included.

   * mbdbench: the wall time of one process of ``mbdbench trajectory`` of the
     same variant at ``--dt 1`` (start-up, reading and checking the embedded
     case files, compiling the scene, building the column, prelude, protocol
     with its 1177 samples kept, the JSON file written), timed around the
     child process here: one run, everything a user waits for.
   * OpenSees: one process of ``time_cyclic.py --runs 1``, two figures:
     ``in_process`` = build + prelude + lateral of that one run (the
     ``build_column`` calls, load pattern and analysis objects included;
     Python's start-up and the import of openseespy excluded), and
     ``process`` = the wall time of the whole child process (Python start-up
     and the import included).  The headline ratio uses ``in_process``
     (conservative for mbdbench, whose side includes its process start-up);
     the process-to-process ratio is printed too.

The CPU time (user + system, from ``wait4``'s resource usage) of every child
process is recorded alongside, a check that a ratio is not the machine's load
(the VM is shared).  The iteration counts are not defined alike: OpenSees'
``testIter`` counts the corrector iterations after DisplacementControl's
predictor solve, mbdbench's ``newton_iters`` counts every solve, the one that
carries the prescribed increment included; ``opensees_solves`` puts OpenSees on
mbdbench's count (iterations + steps).  mbdbench's count includes the 10
prelude steps' solves; ``opensees_solves_with_prelude`` adds OpenSees' (its
LoadControl ``testIter``, which counts every solve of a load step).  The
OpenSees version is that of the pinned wheel (generate.py's constants) and
the installed openseespy's own package version.

Usage (from the repository root, after ``cargo build --release``)::

    v/bin/python references/fiber_column/opensees/speed_c01.py --cpu 1 --rounds 15

Progress goes to stderr, one JSON object to stdout.
"""

import argparse
import importlib.metadata
import json
import os
import platform
import statistics
import subprocess
import sys
import tempfile
import time

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.normpath(os.path.join(HERE, "..", "..", ".."))
VARIANT = ["--case", "fiber_column_cyclic", "--scene", "rc_cyclic_c01",
           "--param", "so3", "--integrator", "newton_disp",
           "--formulation", "force_based"]


def run_child(argv, cpu):
    """Runs ``argv`` pinned to ``cpu``; returns (stdout, wall s, CPU s of the child)."""
    env = dict(os.environ, OMP_NUM_THREADS="1", OPENBLAS_NUM_THREADS="1")
    with tempfile.TemporaryFile("w+") as out, tempfile.TemporaryFile("w+") as err:
        t0 = time.perf_counter()
        p = subprocess.Popen(["taskset", "-c", str(cpu)] + argv, env=env,
                             stdout=out, stderr=err, text=True)
        _, status, usage = os.wait4(p.pid, 0)
        wall = time.perf_counter() - t0
        p.returncode = os.waitstatus_to_exitcode(status)
        out.seek(0)
        err.seek(0)
        if p.returncode != 0:
            raise SystemExit("%s exited %d:\n%s" % (" ".join(argv), p.returncode,
                                                     err.read()))
        return out.read(), wall, usage.ru_utime + usage.ru_stime


def opensees(cpu, runs):
    """One pinned process of time_cyclic.py; its JSON, wall and CPU time."""
    out, wall, cpu_s = run_child(
        [sys.executable, os.path.join(HERE, "time_cyclic.py"), "--runs", str(runs)], cpu)
    doc = json.loads(out[out.index("{"):out.rindex("}") + 1])
    return doc, wall, cpu_s


def mbdbench_run(cpu, binary):
    """One pinned ``mbdbench run`` of the variant; its dt 1 record."""
    with tempfile.TemporaryDirectory() as tmp:
        run_child([binary, "run"] + VARIANT + ["--jobs", "1", "--out",
                                               os.path.join(tmp, "out")], cpu)
        with open(os.path.join(tmp, "out", "summary.json")) as f:
            records = json.load(f)["records"]
    rec = [r for r in records if r["status"] == "ok" and r.get("dt") == 1.0]
    if len(rec) != 1:
        raise SystemExit("mbdbench: no completed dt = 1 record of rc_cyclic_c01")
    return rec[0]


def mbdbench_trajectory(cpu, binary):
    """One pinned ``mbdbench trajectory`` of the variant at dt 1: wall and CPU time."""
    with tempfile.TemporaryDirectory() as tmp:
        _, wall, cpu_s = run_child([binary, "trajectory"] + VARIANT + [
            "--dt", "1", "--out", os.path.join(tmp, "t.json")], cpu)
    return wall, cpu_s


def spread(xs):
    """Median, minimum, quartiles and maximum of a list."""
    q = statistics.quantiles(xs, n=4, method="inclusive")
    return {"median": statistics.median(xs), "min": min(xs), "q1": q[0],
            "q3": q[2], "max": max(xs)}


def one_round(k, a):
    """One round: each side's two measurements, the order swapped on odd rounds."""
    sides = {
        "o_analysis": lambda: opensees(a.cpu, 3),
        "m_analysis": lambda: mbdbench_run(a.cpu, a.binary),
        "o_built": lambda: opensees(a.cpu, 1),
        "m_built": lambda: mbdbench_trajectory(a.cpu, a.binary),
    }
    order = ["o_analysis", "m_analysis", "o_built", "m_built"]
    if k % 2 == 1:
        order = ["m_analysis", "o_analysis", "m_built", "o_built"]
    got = {name: sides[name]() for name in order}
    o_doc = got["o_analysis"][0]
    o_an = statistics.median(r["prelude"] + r["lateral"] for r in o_doc["per_run"])
    m_rec = got["m_analysis"]
    m_an = m_rec["wall_s"]["median"]
    b_doc, b_wall, b_cpu = got["o_built"]
    r0 = b_doc["per_run"][0]
    o_in = r0["build"] + r0["prelude"] + r0["lateral"]
    m_wall, m_cpu = got["m_built"]
    return {
        "opensees_analysis_s": o_an,
        "opensees_analysis_runs_s": [r["prelude"] + r["lateral"] for r in o_doc["per_run"]],
        "opensees_analysis_process_cpu_s": got["o_analysis"][2],
        "mbdbench_analysis_s": m_an,
        "mbdbench_analysis_min_s": m_rec["wall_s"]["min"],
        "opensees_built_in_process_s": o_in,
        "opensees_built_process_s": b_wall,
        "opensees_built_process_cpu_s": b_cpu,
        "mbdbench_built_process_s": m_wall,
        "mbdbench_built_process_cpu_s": m_cpu,
        "ratio_analysis": o_an / m_an,
        "ratio_built": o_in / m_wall,
        "ratio_built_process": b_wall / m_wall,
        "ratio_built_process_cpu": b_cpu / m_cpu,
        "_counts": (o_doc, m_rec),
    }


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--cpu", type=int, default=1, help="the core both sides run on")
    ap.add_argument("--rounds", type=int, default=15, help="rounds (at least 10)")
    ap.add_argument("--binary", default=os.path.join(ROOT, "target", "release", "mbdbench"))
    a = ap.parse_args()
    if a.rounds < 10:
        raise SystemExit("--rounds must be at least 10 (the figure is a median of ratios)")
    rounds = []
    for k in range(a.rounds):
        r = one_round(k, a)
        rounds.append(r)
        print("round %2d: analysis OpenSees %.4f s, mbdbench %.4f s (%.3fx); "
              "built OpenSees %.4f s, mbdbench %.4f s (%.3fx)" % (
                  k + 1, r["opensees_analysis_s"], r["mbdbench_analysis_s"],
                  r["ratio_analysis"], r["opensees_built_in_process_s"],
                  r["mbdbench_built_process_s"], r["ratio_built"]), file=sys.stderr)
    o_doc, m_rec = rounds[0]["_counts"]
    for r in rounds:
        del r["_counts"]
    it_m = m_rec["stats"]["newton_iters"]
    solves_o = o_doc["global_iterations"] + o_doc["steps"]
    col = lambda key: [r[key] for r in rounds]  # noqa: E731
    print(json.dumps({
        "scene": "rc_cyclic_c01",
        "variant": "so3 / newton_disp / force_based, dt 1",
        "rounds": a.rounds,
        "cpu": a.cpu,
        "binary": a.binary,
        "ratio_analysis": spread(col("ratio_analysis")),
        "ratio_built": spread(col("ratio_built")),
        "ratio_built_process": spread(col("ratio_built_process")),
        "ratio_built_process_cpu": spread(col("ratio_built_process_cpu")),
        "opensees_analysis_s": spread(col("opensees_analysis_s")),
        "mbdbench_analysis_s": spread(col("mbdbench_analysis_s")),
        "opensees_built_in_process_s": spread(col("opensees_built_in_process_s")),
        "opensees_built_process_s": spread(col("opensees_built_process_s")),
        "mbdbench_built_process_s": spread(col("mbdbench_built_process_s")),
        "opensees_iterations": o_doc["global_iterations"],
        "opensees_steps": o_doc["steps"],
        "opensees_solves": solves_o,
        "opensees_prelude_iterations": o_doc["prelude_iterations"],
        "opensees_prelude_steps": o_doc["prelude_steps"],
        "opensees_solves_with_prelude": solves_o + o_doc["prelude_iterations"],
        "mbdbench_solves": it_m,
        "mbdbench_element_iterations": m_rec["stats"].get("element_iters"),
        "opensees": o_doc["opensees"],
        "openseespy": o_doc["openseespy"],
        "openseespy_installed": importlib.metadata.version("openseespy"),
        "python": platform.python_version(),
        "machine": platform.processor() or platform.machine(),
        "per_round": rounds,
    }, indent=1))


if __name__ == "__main__":
    main()
