#!/usr/bin/env python3
"""External OpenSees reference generator for mbdbench's ``fiber_column`` family.

What this is
------------
This script drives OpenSees (through openseespy 3.7.1.2, OpenSees 3.7.1) to
produce the reference records that mbdbench's Rust fiber-column model is
compared against.  It writes, into the directory holding this file:

* ``rc_cyclic_c01.json`` -- RC cantilever, Concrete01/Steel01, cyclic drift
  protocol under displacement control;
* ``rc_cyclic_c02.json`` -- same column, Concrete02/Steel02;
* ``rc_pulse.json``      -- the ``_c01`` column with a lumped top mass under a
  one-second sine ground-acceleration pulse (Newmark, average acceleration);
* ``elastica.json``      -- elastic cantilever under a tip dead load
  perpendicular to the undeformed axis (large-deflection check of the
  corotational formulation for three OpenSees element kinds);
* ``MANIFEST.json``      -- SHA-256 of every output, of this script and of
  its companions.

Every record carries a ``provenance`` block (tool, command, script, accuracy
claim, cross-check) as every stored reference of mbdbench does.  This script
writes the block of the three column records (``record_provenance``): the
accuracy claim from the record's own half-increment rerun, the cross-check
from ``CROSS_CHECK``, mbdbench's agreement with the record as mbdbench measured
it (quoted, not computed here: OpenSees cannot run mbdbench).  The blocks of
``MANIFEST.json`` and ``elastica.json`` were written by hand after generation;
this script copies them from the file it overwrites (``carried_provenance``),
so a regeneration keeps them.  mbdbench refuses a record whose model is not its
case's, field by field (src/model/fiber_column/opensees_model.rs), so every
input of a run is written into the record's ``model`` and ``settings`` as a
number or a fixed convention string.

Every scene is also rerun at half the increment (0.25 mm, or dt/2) and the
differences at the common points are stored in the record
(``half_increment``) as the accuracy claim of the reference.

The model
---------
A 2-D (ndm = 2, ndf = 3) reinforced-concrete cantilever: base node 1 at
(0, 0) fully fixed, top node 2 at (0, H), H = 3 m, the column along global Y,
lateral direction X.  One ``forceBeamColumn`` element, 5 Gauss-Lobatto
sections, corotational geometric transformation.  The fiber section is a
0.5 m x 0.5 m square (local y = depth, along global X), 0.04 m cover to the
core edge, 16 core fibers through the depth, covers as in the constants
below, ten 4.91 cm^2 bars (4 at y = +0.21, 4 at y = -0.21, 2 at y = 0; bars
do not displace concrete).  Axial load P = 750 kN is applied first in 10
load-control steps and then held constant.

Solution settings: plain Newton (no fallback, no step cutting: a step that
does not converge stops the script with an error naming it), EnergyIncr
test, BandGeneral system, Plain numberer and constraints.  Exception:
rc_cyclic_c02 runs every step with KrylovNewton, because plain Newton
cycles at one step of its protocol (see ALGORITHM below; ``--strict-newton``
reproduces the failure).  The number of
global Newton iterations of every step is recorded.

Conventions of the records
--------------------------
* ``t``: cyclic scenes -- cumulative lateral path length / 0.5 mm (t = 0 after
  the axial prelude, t = 5880 at the end); pulse -- time in s after the
  prelude.
* ``top_displacement``: X displacement of the top node (m); for the pulse it
  is relative to the ground.
* ``top_axial``: Y displacement of the top node (m, negative when shortening).
* ``top_rotation``: rotation of the top node, positive when the top tilts
  toward +X, i.e. minus OpenSees' 2-D rz (rad).
* ``base_shear``: minus the horizontal base reaction (N).
* ``axial_force``: minus the vertical base reaction (N, compression negative).

Run ``python generate.py`` to regenerate everything (a few minutes on one
core).  ``--only NAME`` restricts to one scene, ``--omega1`` prints the
first circular frequency computed from the condensed tangent, ``--probe-tol``
searches the tightest global tolerance, ``--manifest`` only rewrites
MANIFEST.json.
"""

import argparse
import hashlib
import json
import math
import os
import platform
import sys

import openseespy.opensees as ops

# ---------------------------------------------------------------------------
# Paths and provenance
# ---------------------------------------------------------------------------
HERE = os.path.dirname(os.path.abspath(__file__))
SCRIPT_REL = "references/fiber_column/opensees/generate.py"  # path in the repo
SCHEMA = "mbdbench.opensees_reference/1"
OPENSEES_VERSION = "3.7.1"       # OpenSees inside the pinned wheel
OPENSEESPY_VERSION = "3.7.1.2"   # pinned in references/fiber_column/requirements.txt
REGENERATE = ("python3 -m venv v && v/bin/pip install -r "
              "references/fiber_column/requirements.txt && "
              "v/bin/python references/fiber_column/opensees/generate.py")

# ---------------------------------------------------------------------------
# Column geometry (m)
# ---------------------------------------------------------------------------
H = 3.0                  # column height, base (0,0) -> top (0,H)
SEC_HALF = 0.25          # half side of the 0.5 x 0.5 m square section
CORE_HALF = 0.21         # half side of the core (0.25 - 0.04 cover)
COVER = 0.04             # cover thickness to the core edge
N_CORE_DEPTH = 16        # core fibers through the depth (local y)
N_TB_COVER_DEPTH = 2     # fibers through the depth of top / bottom covers
N_SIDE_COVER_DEPTH = 16  # fibers through the depth of each side cover
N_ACROSS = 1             # fibers across the width (irrelevant in 2-D)
BAR_AREA = 4.91e-4       # area of one bar (m^2)
# bar rows: (depth coordinate y, number of bars); z positions only cosmetic
BAR_ROWS = ((CORE_HALF, 4), (-CORE_HALF, 4), (0.0, 2))
N_SECTIONS = 5           # Gauss-Lobatto integration points of the element

# ---------------------------------------------------------------------------
# Materials (Pa, -): the OpenSees argument lists, in order
# ---------------------------------------------------------------------------
MATERIALS = {
    "c01": {
        # core: fpc, epsc0, fpcu, epsU
        "core": ("Concrete01", (-36e6, -0.004, -30e6, -0.014)),
        # cover: fpc, epsc0, fpcu, epsU
        "cover": ("Concrete01", (-30e6, -0.002, 0.0, -0.006)),
        # bars: Fy, E0, b
        "steel": ("Steel01", (420e6, 200e9, 0.01)),
    },
    "c02": {
        # core: fpc, epsc0, fpcu, epsU, lambda, ft, Ets
        "core": ("Concrete02", (-36e6, -0.004, -7.2e6, -0.02, 0.1, 3e6, 1.5e9)),
        # cover: fpc, epsc0, fpcu, epsU, lambda, ft, Ets
        "cover": ("Concrete02", (-30e6, -0.002, -6e6, -0.006, 0.1, 3e6, 1.5e9)),
        # bars: Fy, E0, b, R0, cR1, cR2
        "steel": ("Steel02", (420e6, 200e9, 0.01, 18.0, 0.925, 0.15)),
    },
}
MAT_TAG = {"core": 1, "cover": 2, "steel": 3}

# ---------------------------------------------------------------------------
# Loading
# ---------------------------------------------------------------------------
P_AXIAL = 750e3          # axial load at the top, downward (N)
AXIAL_STEPS = 10         # equal load-control steps of the axial prelude
DRIFTS_PCT = (0.25, 0.5, 1.0, 1.5, 2.0, 3.0, 4.0)   # drift amplitudes (% of H)
CYCLES_PER_AMPLITUDE = 2  # full cycles 0 -> +A -> -A -> 0 per amplitude
DU = 0.0005              # lateral displacement increment of the record (m)
T_UNIT = 0.0005          # path length per unit of the record's pseudo-time (m)

G0 = 9.80665             # standard gravity (m/s^2), defines mass and pulse
TOP_MASS = P_AXIAL / G0  # lumped top mass in X and Y (kg); rotation massless
PULSE_AMPLITUDE = 0.5 * G0   # ground-acceleration amplitude (m/s^2)
PULSE_PERIOD = 0.5       # period of the sine pulse (s)
PULSE_END = 1.0          # the pulse acts for 0 <= t <= 1 s, then a_g = 0
PULSE_T_END = 5.0        # end of the pulse record (s)
# analysis time step (s); the half run uses DT/2.  Half-step differences
# relative to the peaks (measured): dt = 1e-3: top_displacement 4.1e-4,
# top_axial 8.6e-3, axial_force 1.9e-2 (the lightly damped axial mode,
# omega = 164 rad/s, is excited by crack opening); dt = 5e-4: 1.2e-4, 2.1e-3,
# 4.7e-3, so every column is within 1 %.
PULSE_DT = 5.0e-4
PULSE_RECORD_DT = 0.005  # record interval (s)
NEWMARK_GAMMA = 0.5      # average-acceleration Newmark
NEWMARK_BETA = 0.25
DAMPING_RATIO = 0.02     # mass-proportional Rayleigh damping, zeta at omega1
# omega1 (rad/s): smallest sqrt(eig(K_c / m)) with K_c the tangent of the free
# top node after the axial prelude of the _c01 column, rotation condensed out
# statically (computed by omega1_by_condensation(), --omega1 prints it; the
# script recomputes it at every run and stops if it drifts from this value).
OMEGA1 = 14.820708227335706
# a0 = 2 * DAMPING_RATIO * OMEGA1 (1/s): the literal the case file carries
RAYLEIGH_A0 = 0.5928283290934282

# ---------------------------------------------------------------------------
# Solution settings
# ---------------------------------------------------------------------------
GLOBAL_TOL = 1e-20       # EnergyIncr tolerance (N m): tightest decade passing every
                         # step of all runs (1e-22 fails c01 at step 13; --probe-tol)
GLOBAL_MAX_ITER = 50     # Newton iterations per step before failing
ELEMENT_MAX_ITER = 50    # forceBeamColumn internal iterations ('-iter')
ELEMENT_TOL = 1e-20      # forceBeamColumn tolerance on |dv . kv dv| (N m)
# Global algorithm per scene, used for every step (never as a fallback).
# Plain Newton everywhere except rc_cyclic_c02: there plain Newton enters a
# period-2 limit cycle (a core fiber of the base section flips between its
# loading and unloading branches each iteration; EnergyIncr stalls at 0.027 N m)
# at lateral step 4154 (du = 0.5 mm; step 8307 at 0.25 mm), for every global and
# element tolerance tried.  NewtonLineSearch passes at 0.5 mm but cycles at
# 0.25 mm step 8307; KrylovNewton (Newton with Krylov subspace acceleration,
# current tangent at every iteration) converges at every step of both runs.
# Where both converge (c01: Newton vs KrylovNewton, c02: NewtonLineSearch vs
# KrylovNewton) the records agree to < 1e-11 of the peaks.
# ``--strict-newton`` runs c02 with plain Newton and reproduces the failure.
ALGORITHM = {
    "rc_cyclic_c01": ("Newton",),
    "rc_cyclic_c02": ("KrylovNewton", "-iterate", "current",
                      "-increment", "current", "-maxDim", 3),
    "rc_pulse": ("Newton",),
}
ALGORITHM_NOTE = {
    "rc_cyclic_c02": (
        "KrylovNewton (current tangent every iteration, maxDim 3) for every "
        "step: plain Newton falls into a period-2 cycle at lateral step 4154 "
        "(du 0.5 mm) / 8307 (du 0.25 mm), EnergyIncr stalling at 2.7e-2 N m; "
        "NewtonLineSearch passes at 0.5 mm only.  KrylovNewton and "
        "NewtonLineSearch records agree to < 1e-11 of the peaks at 0.5 mm."),
}

# ---------------------------------------------------------------------------
# Elastica (comparison criterion for the corotational formulation)
# ---------------------------------------------------------------------------
EL_L = 1.0               # cantilever length
EL_E = 1.0e6             # Young's modulus; EA = 1e6
EL_A = 1.0               # area
EL_I = 1.0e-6            # second moment; EI = 1
EL_ALPHAS = (1.0, 2.0, 5.0, 10.0)   # P L^2 / EI
EL_MESHES = (10, 40)     # elements along the cantilever
EL_KINDS = ("elasticBeamColumn", "forceBeamColumn", "dispBeamColumn")
EL_STEPS = 20            # equal load-control steps (path independent)
EL_FORCE_POINTS = 5      # Lobatto points of forceBeamColumn
EL_DISP_POINTS = 5       # Legendre points of dispBeamColumn
EL_TOL = 1e-24           # EnergyIncr tolerance of the elastica runs (tightest
                         # decade passing all 24 cases; 1e-26 fails 8)

COLUMNS = ["t", "top_displacement", "top_axial", "top_rotation",
           "base_shear", "axial_force"]


class NotConverged(RuntimeError):
    """A Newton step failed; the message names the scene and step."""


# ---------------------------------------------------------------------------
# Model building
# ---------------------------------------------------------------------------
def build_column(mats, with_mass=False, element_tol=None):
    """Create the fiber column model in a fresh OpenSees domain."""
    etol = ELEMENT_TOL if element_tol is None else element_tol
    ops.wipe()
    ops.model("basic", "-ndm", 2, "-ndf", 3)
    ops.node(1, 0.0, 0.0)
    ops.node(2, 0.0, H)
    ops.fix(1, 1, 1, 1)
    if with_mass:
        ops.mass(2, TOP_MASS, TOP_MASS, 0.0)
    for role, tag in MAT_TAG.items():
        kind, args = MATERIALS[mats][role]
        ops.uniaxialMaterial(kind, tag, *args)
    sec = 1
    ops.section("Fiber", sec)
    c, h = CORE_HALF, SEC_HALF
    core, cover, steel = MAT_TAG["core"], MAT_TAG["cover"], MAT_TAG["steel"]
    # patch rect: mat, nDepth (y), nWidth (z), yI, zI, yJ, zJ
    ops.patch("rect", core, N_CORE_DEPTH, N_ACROSS, -c, -c, c, c)
    ops.patch("rect", cover, N_TB_COVER_DEPTH, N_ACROSS, c, -h, h, h)
    ops.patch("rect", cover, N_TB_COVER_DEPTH, N_ACROSS, -h, -h, -c, h)
    ops.patch("rect", cover, N_SIDE_COVER_DEPTH, N_ACROSS, -c, c, c, h)
    ops.patch("rect", cover, N_SIDE_COVER_DEPTH, N_ACROSS, -c, -h, c, -c)
    for y, n in BAR_ROWS:
        for k in range(n):
            z = -c + 2.0 * c * k / (n - 1)
            ops.fiber(y, z, BAR_AREA, steel)
    ops.beamIntegration("Lobatto", 1, sec, N_SECTIONS)
    ops.geomTransf("Corotational", 1)
    ops.element("forceBeamColumn", 1, 1, 2, 1, 1,
                "-iter", ELEMENT_MAX_ITER, etol)


def set_static_solver(system="BandGeneral", tol=None, algorithm=("Newton",)):
    ops.system(system)
    ops.numberer("Plain")
    ops.constraints("Plain")
    ops.test("EnergyIncr", GLOBAL_TOL if tol is None else tol, GLOBAL_MAX_ITER)
    ops.algorithm(*algorithm)


def step(scene, label):
    """One analysis step; raise naming the step if Newton fails."""
    if ops.analyze(1) != 0:
        raise NotConverged("%s: %s did not converge (%s, EnergyIncr, "
                           "%d iterations; last norms %s)"
                           % (scene, label, ALGORITHM.get(scene, ("Newton",))[0],
                              GLOBAL_MAX_ITER,
                              ["%.3g" % x for x in
                               ops.testNorm()[GLOBAL_MAX_ITER - 4:GLOBAL_MAX_ITER]]))
    return ops.testIter()


def axial_prelude(scene, system="BandGeneral", tol=None):
    """Apply P in AXIAL_STEPS load-control steps; return iterations/step."""
    ops.timeSeries("Linear", 1)
    ops.pattern("Plain", 1, 1)
    ops.load(2, 0.0, -P_AXIAL, 0.0)
    set_static_solver(system, tol, ALGORITHM.get(scene, ("Newton",)))
    ops.integrator("LoadControl", 1.0 / AXIAL_STEPS)
    ops.analysis("Static")
    iters = [step(scene, "axial step %d" % (k + 1)) for k in range(AXIAL_STEPS)]
    ops.loadConst("-time", 0.0)
    return iters


def state():
    """Current record row except t (see the module docstring)."""
    ops.reactions()
    return [ops.nodeDisp(2, 1), ops.nodeDisp(2, 2), -ops.nodeDisp(2, 3),
            -ops.nodeReaction(1, 1), -ops.nodeReaction(1, 2)]


# ---------------------------------------------------------------------------
# Cyclic scenes
# ---------------------------------------------------------------------------
def protocol_legs(du):
    """List of (direction, steps) legs of the drift protocol for increment du."""
    legs = []
    for d in DRIFTS_PCT:
        n = round(d / 100.0 * H / du)
        assert abs(n * du - d / 100.0 * H) < 1e-12, "amplitude not a multiple"
        for _ in range(CYCLES_PER_AMPLITUDE):
            legs += [(+1, n), (-1, 2 * n), (+1, n)]
    return legs


def run_cyclic(scene, mats, du, tol=None, element_tol=None):
    build_column(mats, element_tol=element_tol)
    prelude = axial_prelude(scene, tol=tol)
    ops.timeSeries("Linear", 2)
    ops.pattern("Plain", 2, 2)
    ops.load(2, 1.0, 0.0, 0.0)       # reference lateral load (1 N in X)
    rows = [[0.0] + state()]
    iters = [0]
    k = 0
    target = 0
    for sign, n in protocol_legs(du):
        ops.integrator("DisplacementControl", 2, 1, sign * du)
        ops.analysis("Static")
        for _ in range(n):
            k += 1
            target += sign
            it = step(scene, "lateral step %d (du = %g m)" % (k, du))
            row = state()
            if abs(row[0] - target * du) > 1e-12:
                raise RuntimeError("%s: step %d top displacement %r != %r"
                                   % (scene, k, row[0], target * du))
            rows.append([k * du / T_UNIT] + row)
            iters.append(it)
    return {"rows": rows, "iters": iters, "prelude_iters": prelude}


# ---------------------------------------------------------------------------
# Pulse scene
# ---------------------------------------------------------------------------
def condensed_tangent_after_prelude():
    """3x3 tangent of the free top node after the prelude, FullGeneral."""
    build_column("c01", with_mass=True)
    axial_prelude("omega1", system="FullGeneral")
    # one zero-increment step: Newton forms the tangent at the converged
    # state, the EnergyIncr test is met at once (zero correction)
    ops.integrator("LoadControl", 0.0)
    ops.analysis("Static")
    step("omega1", "zero-increment tangent step")
    a = ops.printA("-ret")
    return [a[0:3], a[3:6], a[6:9]]


def omega1_by_condensation():
    k = condensed_tangent_after_prelude()
    kc = [[k[i][j] - k[i][2] * k[2][j] / k[2][2] for j in range(2)]
          for i in range(2)]
    tr = (kc[0][0] + kc[1][1]) / TOP_MASS
    det = (kc[0][0] * kc[1][1] - kc[0][1] * kc[1][0]) / TOP_MASS ** 2
    disc = math.sqrt(tr * tr / 4.0 - det)
    w2 = sorted([tr / 2.0 - disc, tr / 2.0 + disc])
    # cross-check with OpenSees' own generalized eigen solver (same state)
    try:
        lam = ops.eigen("-fullGenLapack", 1)
        eig = math.sqrt(lam[0])
    except Exception as exc:  # noqa: BLE001 - report any failure
        eig = "failed: %s" % exc
    return {"omega1": math.sqrt(w2[0]), "omega2": math.sqrt(w2[1]),
            "tangent": k, "condensed": kc, "omega1_eigen_fullGenLapack": eig}


def run_pulse(dt, tol=None):
    scene = "rc_pulse"
    build_column("c01", with_mass=True)
    prelude = axial_prelude(scene, tol=tol)
    ops.wipeAnalysis()
    ops.rayleigh(RAYLEIGH_A0, 0.0, 0.0, 0.0)
    # a_g(t) = PULSE_AMPLITUDE sin(2 pi (t - 0) / PULSE_PERIOD), 0 <= t <= 1
    ops.timeSeries("Trig", 3, 0.0, PULSE_END, PULSE_PERIOD,
                   "-factor", PULSE_AMPLITUDE)
    ops.pattern("UniformExcitation", 3, 1, "-accel", 3)
    set_static_solver(tol=tol, algorithm=ALGORITHM[scene])
    ops.integrator("Newmark", NEWMARK_GAMMA, NEWMARK_BETA)
    ops.analysis("Transient")
    n_steps = round(PULSE_T_END / dt)
    every = round(PULSE_RECORD_DT / dt)
    assert abs(n_steps * dt - PULSE_T_END) < 1e-12
    assert abs(every * dt - PULSE_RECORD_DT) < 1e-15
    rows = [[0.0] + state()]
    iters = [0]
    series = [0.0]
    for k in range(1, n_steps + 1):
        if ops.analyze(1, dt) != 0:
            raise NotConverged("%s: time step %d (t = %.6f s, dt = %g s) did "
                               "not converge" % (scene, k, k * dt, dt))
        iters.append(ops.testIter())
        if k % every == 0:
            rows.append([round(k * dt, 9)] + state())
            series.append(ops.getTime())
    return {"rows": rows, "iters": iters, "prelude_iters": prelude,
            "domain_time_at_records": series}


def check_trig_series():
    """Max |Trig series - closed form| over 0 <= t <= 1.2 s (step 1 ms).

    The series drives a Plain pattern on a one-spring 1-D model, stepped in
    pseudo-time by LoadControl, and getLoadFactor reads its value."""
    ops.wipe()
    ops.model("basic", "-ndm", 1, "-ndf", 1)
    ops.node(1, 0.0)
    ops.node(2, 0.0)
    ops.fix(1, 1)
    ops.uniaxialMaterial("Elastic", 1, 1.0)
    ops.element("zeroLength", 1, 1, 2, "-mat", 1, "-dir", 1)
    ops.timeSeries("Trig", 1, 0.0, PULSE_END, PULSE_PERIOD,
                   "-factor", PULSE_AMPLITUDE)
    ops.pattern("Plain", 1, 1)
    ops.load(2, 1.0)
    set_static_solver()
    ops.integrator("LoadControl", 0.001)
    ops.analysis("Static")
    worst = 0.0
    for _ in range(1200):
        step("trig check", "pseudo-time step")
        t = ops.getTime()
        want = (PULSE_AMPLITUDE * math.sin(2.0 * math.pi * t / PULSE_PERIOD)
                if t <= PULSE_END else 0.0)
        worst = max(worst, abs(ops.getLoadFactor(1) - want))
    return worst


# ---------------------------------------------------------------------------
# Elastica
# ---------------------------------------------------------------------------
def run_elastica(kind, n_el, alpha):
    ops.wipe()
    ops.model("basic", "-ndm", 2, "-ndf", 3)
    for i in range(n_el + 1):
        ops.node(i + 1, EL_L * i / n_el, 0.0)
    ops.fix(1, 1, 1, 1)
    ops.geomTransf("Corotational", 1)
    if kind != "elasticBeamColumn":
        ops.section("Elastic", 1, EL_E, EL_A, EL_I)
        if kind == "forceBeamColumn":
            ops.beamIntegration("Lobatto", 1, 1, EL_FORCE_POINTS)
        else:
            ops.beamIntegration("Legendre", 1, 1, EL_DISP_POINTS)
    for e in range(n_el):
        if kind == "elasticBeamColumn":
            ops.element(kind, e + 1, e + 1, e + 2, EL_A, EL_E, EL_I, 1)
        elif kind == "forceBeamColumn":
            ops.element(kind, e + 1, e + 1, e + 2, 1, 1,
                        "-iter", ELEMENT_MAX_ITER, ELEMENT_TOL)
        else:
            ops.element(kind, e + 1, e + 1, e + 2, 1, 1)
    tip = n_el + 1
    p = alpha * 1.0 / EL_L ** 2     # EI = 1
    ops.timeSeries("Linear", 1)
    ops.pattern("Plain", 1, 1)
    ops.load(tip, 0.0, p, 0.0)      # dead load in +Y, perpendicular to X axis
    ops.system("BandGeneral")
    ops.numberer("Plain")
    ops.constraints("Plain")
    ops.test("EnergyIncr", EL_TOL, GLOBAL_MAX_ITER)
    ops.algorithm("Newton")
    ops.integrator("LoadControl", 1.0 / EL_STEPS)
    ops.analysis("Static")
    iters = [step("elastica %s n=%d alpha=%g" % (kind, n_el, alpha),
                  "load step %d" % (k + 1)) for k in range(EL_STEPS)]
    return {"along": EL_L + ops.nodeDisp(tip, 1),
            "across": ops.nodeDisp(tip, 2),
            "rotation": ops.nodeDisp(tip, 3),
            "iterations": iters}


def elastica_exact(alpha, n=4000):
    """Tip of the inextensible elastica by shooting (RK4, n steps).

    theta'' = -alpha cos(theta), theta(0) = 0, theta'(1) = 0; returns
    (x_tip, y_tip, theta_tip).  Independent of OpenSees; for orientation only.
    """
    def integrate(k0):
        h = 1.0 / n
        y = [0.0, k0, 0.0, 0.0]     # theta, theta', x, y

        def f(s):
            return [s[1], -alpha * math.cos(s[0]), math.cos(s[0]),
                    math.sin(s[0])]
        for _ in range(n):
            a = f(y)
            b = f([y[i] + 0.5 * h * a[i] for i in range(4)])
            c = f([y[i] + 0.5 * h * b[i] for i in range(4)])
            d = f([y[i] + h * c[i] for i in range(4)])
            y = [y[i] + h / 6.0 * (a[i] + 2 * b[i] + 2 * c[i] + d[i])
                 for i in range(4)]
        return y
    lo, hi = 0.0, alpha             # theta'(0) = alpha x_tip <= alpha
    for _ in range(80):
        mid = 0.5 * (lo + hi)
        if integrate(mid)[1] > 0.0:
            hi = mid
        else:
            lo = mid
    y = integrate(0.5 * (lo + hi))
    return {"along": y[2], "across": y[3], "rotation": y[0]}


# ---------------------------------------------------------------------------
# Output helpers
# ---------------------------------------------------------------------------
def sha256_file(path):
    h = hashlib.sha256()
    with open(path, "rb") as fh:
        h.update(fh.read())
    return h.hexdigest()


def header(scene):
    return {
        "schema": SCHEMA,
        "scene": scene,
        "generator": {
            "script": SCRIPT_REL,
            "script_sha256": sha256_file(os.path.abspath(__file__)),
            "opensees": OPENSEES_VERSION,
            "openseespy": OPENSEESPY_VERSION,
            "python": platform.python_version(),
            "regenerate": REGENERATE,
        },
    }


# mbdbench's agreement with each column record, as measured by ``mbdbench run``
# on fiber_column_cyclic and fiber_column_dynamic (stop 22): quoted, not computed.
CROSS_CHECK_BY = ("mbdbench's own fiber column (src/model/fiber_column/, "
                  "independent code: 3-D corotational frame, own materials and "
                  "force-based element) reproduces this run: ")
CROSS_CHECK = {
    "rc_cyclic_c01": "base shear to 7.0e-14 of its peak (variant newton_disp)",
    "rc_cyclic_c02": "base shear to 1.2e-12 of its peak (variant "
                     "newton_disp_krylov)",
    "rc_pulse": "top displacement to 1.9e-12 of its peak (variant newmark, "
                "dt 5e-4)",
}
CLAIM_OF = {"rc_cyclic_c01": "base_shear", "rc_cyclic_c02": "base_shear",
            "rc_pulse": "top_displacement"}


def record_provenance(scene, half, rerun):
    """The ``provenance`` block of a column record: the tool and the command
    that made it, the accuracy claim read from its half-increment rerun
    ``half`` (``rerun`` says what was halved), and the cross-check."""
    rel = half["relative_to_peak"]
    per_column = ", ".join("%s %.2g" % (c, rel[c]) for c in COLUMNS[1:])
    return {
        "tool": "OpenSees %s through openseespy %s (Python %s), pinned in "
                "references/fiber_column/requirements.txt"
                % (OPENSEES_VERSION, OPENSEESPY_VERSION,
                   platform.python_version()),
        "command": REGENERATE,
        "script": SCRIPT_REL,
        "accuracy_claim": "half_increment.relative_to_peak: the largest "
                          "difference from the same run at %s, relative to "
                          "each column's peak (%s; the scored column %s %.2g)"
                          % (rerun, per_column, CLAIM_OF[scene],
                             rel[CLAIM_OF[scene]]),
        "cross_check": CROSS_CHECK_BY + CROSS_CHECK[scene] + "; measured by "
                       "mbdbench run on fiber_column_cyclic and "
                       "fiber_column_dynamic (stop 22)",
    }


def section_model(mats):
    mat = {role: {"type": MATERIALS[mats][role][0],
                  "args": list(MATERIALS[mats][role][1]),
                  "tag": MAT_TAG[role]} for role in MAT_TAG}
    return {
        "H": H,
        "nodes": {"base": [0.0, 0.0], "top": [0.0, H]},
        "element": {"type": "forceBeamColumn", "count": 1,
                    "integration": "Lobatto", "sections": N_SECTIONS,
                    "geom_transf": "Corotational"},
        "section": {
            "type": "Fiber (2-D; local y = depth along global X)",
            "width": 2 * SEC_HALF, "depth": 2 * SEC_HALF, "cover": COVER,
            "patches": [
                {"mat": "core", "y": [-CORE_HALF, CORE_HALF],
                 "z": [-CORE_HALF, CORE_HALF], "n_depth": N_CORE_DEPTH,
                 "n_width": N_ACROSS},
                {"mat": "cover", "y": [CORE_HALF, SEC_HALF],
                 "z": [-SEC_HALF, SEC_HALF], "n_depth": N_TB_COVER_DEPTH,
                 "n_width": N_ACROSS},
                {"mat": "cover", "y": [-SEC_HALF, -CORE_HALF],
                 "z": [-SEC_HALF, SEC_HALF], "n_depth": N_TB_COVER_DEPTH,
                 "n_width": N_ACROSS},
                {"mat": "cover", "y": [-CORE_HALF, CORE_HALF],
                 "z": [CORE_HALF, SEC_HALF], "n_depth": N_SIDE_COVER_DEPTH,
                 "n_width": N_ACROSS},
                {"mat": "cover", "y": [-CORE_HALF, CORE_HALF],
                 "z": [-SEC_HALF, -CORE_HALF], "n_depth": N_SIDE_COVER_DEPTH,
                 "n_width": N_ACROSS},
            ],
            "bars": {"area": BAR_AREA, "mat": "steel",
                     "rows": [{"y": y, "count": n} for y, n in BAR_ROWS],
                     "displace_concrete": False},
        },
        "materials": mat,
        "P": P_AXIAL,
        "P_direction": "-Y at the top node",
        "axial_steps": AXIAL_STEPS,
    }


def settings(scene, extra):
    algo = ALGORITHM[scene]
    s = {"algorithm": algo[0], "algorithm_args": list(algo[1:]),
         "algorithm_note": ALGORITHM_NOTE.get(scene, "plain Newton"),
         "fallback": None, "step_cutting": False,
         "test": "EnergyIncr", "tol": GLOBAL_TOL, "max_iter": GLOBAL_MAX_ITER,
         "system": "BandGeneral", "numberer": "Plain", "constraints": "Plain",
         "element_iter": ELEMENT_MAX_ITER, "element_tol": ELEMENT_TOL,
         "element_tol_measures": (
             "ForceBeamColumn2d state determination: |dv . (kv dv)| of the "
             "basic-deformation residual dv = v_target - integral(b^T vs) "
             "(energy, N m) must fall below element_tol"),
         "element_subdivide": "OpenSees default (4 subdivisions, factor 10)",
         "axial_steps": AXIAL_STEPS}
    s.update(extra)
    return s


CONVENTIONS = {
    "top_displacement": "X displacement of the top node (m)",
    "top_axial": "Y displacement of the top node (m, negative when shortening)",
    "top_rotation": ("top rotation (rad), positive when the top tilts toward "
                     "+X = minus OpenSees 2-D rz"),
    "base_shear": "minus the horizontal base reaction (N)",
    "axial_force": "minus the vertical base reaction (N, compression negative)",
}
UNITS = {"t": None, "top_displacement": "m", "top_axial": "m",
         "top_rotation": "rad", "base_shear": "N", "axial_force": "N"}


def columns_of(rows):
    return {name: [r[i] for r in rows] for i, name in enumerate(COLUMNS)}


def half_compare(coarse, fine, stride):
    """Differences at the common points of a run and its half-step rerun."""
    assert len(fine) == (len(coarse) - 1) * stride + 1
    out = {"max_abs_diff": {}, "peak_abs": {}, "relative_to_peak": {}}
    for i, name in enumerate(COLUMNS[1:], start=1):
        diff = max(abs(coarse[k][i] - fine[k * stride][i])
                   for k in range(len(coarse)))
        peak = max(abs(r[i]) for r in coarse)
        out["max_abs_diff"][name] = diff
        out["peak_abs"][name] = peak
        out["relative_to_peak"][name] = diff / peak if peak else None
    return out


def iteration_summary(run):
    it = run["iters"][1:]
    return {"total": sum(it), "per_step_max": max(it), "steps": len(it),
            "per_step": run["iters"],
            "per_step_note": "entry k is the Newton iteration count of the "
                             "step ending at data row k (row 0: none)",
            "axial_prelude": run["prelude_iters"]}


def write_json(name, obj):
    path = os.path.join(HERE, name)
    with open(path, "w") as fh:
        json.dump(obj, fh, separators=(",", ":"))
        fh.write("\n")
    print("wrote", path, os.path.getsize(path), "bytes")


# ---------------------------------------------------------------------------
# Scene drivers
# ---------------------------------------------------------------------------
def make_cyclic(scene, mats):
    coarse = run_cyclic(scene, mats, DU)
    fine = run_cyclic(scene, mats, DU / 2)
    doc = header(scene)
    model = section_model(mats)
    model["protocol"] = {
        "control": "DisplacementControl of node 2, dof 1 (X)",
        "drifts_percent": list(DRIFTS_PCT),
        "amplitudes_m": [d / 100.0 * H for d in DRIFTS_PCT],
        "cycles_per_amplitude": CYCLES_PER_AMPLITUDE,
        "cycle": "0 -> +A -> -A -> 0",
        "lateral_reference_load": "1 N in X at node 2 (load factor = force)",
        "steps": len(coarse["rows"]) - 1,
    }
    doc["model"] = model
    doc["settings"] = settings(scene, {"integrator": "DisplacementControl",
                                "increment": DU,
                                "t_definition": "cumulative path length / "
                                                "%g m" % T_UNIT})
    doc["columns"] = COLUMNS
    doc["units"] = UNITS
    doc["conventions"] = dict(CONVENTIONS, t=(
        "cumulative lateral path length / 0.5 mm; t = 0 is the state after "
        "the axial prelude"))
    doc["data"] = columns_of(coarse["rows"])
    doc["iterations"] = iteration_summary(coarse)
    doc["half_increment"] = dict(half_compare(coarse["rows"], fine["rows"], 2),
                                 increment=DU / 2,
                                 iterations_total=sum(fine["iters"]))
    doc["provenance"] = record_provenance(
        scene, doc["half_increment"], "half the increment (%g m), at the "
        "common points" % (DU / 2))
    write_json(scene + ".json", doc)
    return doc


def make_pulse():
    om = omega1_by_condensation()
    if abs(om["omega1"] - OMEGA1) > 1e-12 * OMEGA1:
        raise RuntimeError("omega1 drifted: computed %.17g, literal %.17g"
                           % (om["omega1"], OMEGA1))
    if abs(RAYLEIGH_A0 - 2.0 * DAMPING_RATIO * OMEGA1) > 1e-15:
        raise RuntimeError("RAYLEIGH_A0 is not 2 zeta OMEGA1")
    trig_err = check_trig_series()
    coarse = run_pulse(PULSE_DT)
    fine = run_pulse(PULSE_DT / 2)
    doc = header("rc_pulse")
    model = section_model("c01")
    model.update({
        "mass": TOP_MASS, "mass_dofs": "X and Y of the top node; rotation "
                                       "massless", "g0": G0,
        "ground_motion": {
            "amplitude": PULSE_AMPLITUDE, "period": PULSE_PERIOD,
            "start": 0.0, "duration": PULSE_END,
            "direction": "X", "a_g": "%r * sin(2 pi t / %r) for 0 <= t <= %r,"
                                     " else 0" % (PULSE_AMPLITUDE,
                                                  PULSE_PERIOD, PULSE_END),
            "opensees": "timeSeries Trig tStart=0 tEnd=%r period=%r -factor "
                        "%r; pattern UniformExcitation dir 1 -accel"
                        % (PULSE_END, PULSE_PERIOD, PULSE_AMPLITUDE),
            "trig_series_max_abs_error": trig_err},
        "damping": {"type": "Rayleigh, mass proportional", "zeta": DAMPING_RATIO,
                    "a0": RAYLEIGH_A0, "omega1": OMEGA1,
                    "omega1_method": "static condensation of the 3x3 tangent "
                                     "of the free top node after the axial "
                                     "prelude onto X and Y, smallest sqrt("
                                     "eig(K_c/m))",
                    "omega1_recomputed": om["omega1"],
                    "omega2_condensed": om["omega2"],
                    "omega1_eigen_fullGenLapack":
                        om["omega1_eigen_fullGenLapack"],
                    "tangent_after_prelude": om["tangent"],
                    "condensed_tangent": om["condensed"]},
        "t_end": PULSE_T_END,
    })
    doc["model"] = model
    doc["settings"] = settings("rc_pulse", {"integrator": "Newmark",
                                "gamma": NEWMARK_GAMMA, "beta": NEWMARK_BETA,
                                "dt": PULSE_DT,
                                "record_dt": PULSE_RECORD_DT})
    doc["columns"] = COLUMNS
    doc["units"] = dict(UNITS, t="s")
    doc["conventions"] = dict(CONVENTIONS, t="time after the axial prelude (s)",
                              top_displacement="X displacement of the top "
                              "node relative to the ground (m)")
    doc["data"] = columns_of(coarse["rows"])
    doc["iterations"] = iteration_summary(coarse)
    doc["iterations"]["per_step_note"] = (
        "entry k is the Newton iteration count of analysis time step k "
        "(dt = %g s; entry 0: none)" % PULSE_DT)
    doc["half_increment"] = dict(
        half_compare(coarse["rows"], fine["rows"], 1), dt=PULSE_DT / 2,
        iterations_total=sum(fine["iters"]))
    doc["provenance"] = record_provenance(
        "rc_pulse", doc["half_increment"], "half the step (dt %g s), at the "
        "common times" % (PULSE_DT / 2))
    write_json("rc_pulse.json", doc)
    return doc


def carried_provenance(name):
    """The ``provenance`` block of the file ``name`` about to be overwritten
    (None when it has none): written by hand after generation, carried over."""
    path = os.path.join(HERE, name)
    if not os.path.exists(path):
        return None
    with open(path) as fh:
        return json.load(fh).get("provenance")


def make_elastica():
    doc = header("elastica")
    provenance = carried_provenance("elastica.json")
    if provenance is not None:
        doc["provenance"] = provenance
    doc["model"] = {
        "L": EL_L, "E": EL_E, "A": EL_A, "I": EL_I, "EI": EL_E * EL_I,
        "EA": EL_E * EL_A, "alphas_PL2_over_EI": list(EL_ALPHAS),
        "meshes": list(EL_MESHES), "kinds": list(EL_KINDS),
        "geom_transf": "Corotational (2-D)",
        "layout": "nodes along +X from (0,0) to (L,0), node 1 fixed, dead "
                  "load P in +Y at the tip",
        "forceBeamColumn": "section Elastic, Lobatto %d points" % EL_FORCE_POINTS,
        "dispBeamColumn": "section Elastic, Legendre %d points" % EL_DISP_POINTS,
    }
    doc["settings"] = {"algorithm": "Newton", "test": "EnergyIncr",
                       "tol": EL_TOL, "max_iter": GLOBAL_MAX_ITER,
                       "integrator": "LoadControl", "steps": EL_STEPS,
                       "element_iter": ELEMENT_MAX_ITER,
                       "element_tol": ELEMENT_TOL, "system": "BandGeneral",
                       "numberer": "Plain", "constraints": "Plain"}
    doc["conventions"] = {
        "along": "tip X coordinate in the deformed state (L + u_x)",
        "across": "tip Y displacement (in the load direction)",
        "rotation": "tip rotation, OpenSees rz (counterclockwise positive)",
        "key": "data[kind][str(n_elements)][repr(alpha)], e.g. [\"forceBeamColumn\"][\"40\"][\"10.0\"]",
        "exact": "inextensible elastica by shooting (RK4, 4000 steps), not "
                 "from OpenSees; orientation only (OpenSees models EA = 1e6)",
    }
    data = {}
    for kind in EL_KINDS:
        data[kind] = {}
        for n in EL_MESHES:
            data[kind][str(n)] = {}
            for a in EL_ALPHAS:
                r = run_elastica(kind, n, a)
                data[kind][str(n)][repr(a)] = r
                print("elastica %-18s n=%2d alpha=%4g along=%.15f across="
                      "%.15f rot=%.15f it=%d" % (kind, n, a, r["along"],
                                                 r["across"], r["rotation"],
                                                 sum(r["iterations"])))
    doc["data"] = data
    doc["exact"] = {repr(a): elastica_exact(a) for a in EL_ALPHAS}
    write_json("elastica.json", doc)
    return doc


def write_manifest():
    names = ["rc_cyclic_c01.json", "rc_cyclic_c02.json", "rc_pulse.json",
             "elastica.json", "generate.py", "time_cyclic.py", "README.md",
             "../requirements.txt"]
    files = {}
    for n in names:
        p = os.path.normpath(os.path.join(HERE, n))
        if os.path.exists(p):
            rel = os.path.relpath(p, os.path.join(HERE, "..", "..", ".."))
            files[rel] = sha256_file(p)
    man = {"schema": "mbdbench.opensees_manifest/1",
           "opensees": OPENSEES_VERSION, "openseespy": OPENSEESPY_VERSION,
           "python": platform.python_version(), "sha256": files}
    provenance = carried_provenance("MANIFEST.json")
    if provenance is not None:
        man["provenance"] = provenance
    write_json("MANIFEST.json", man)


# ---------------------------------------------------------------------------
# Tolerance probe (not part of the regular run)
# ---------------------------------------------------------------------------
def probe_tolerances():
    for tol in (1e-28, 1e-26, 1e-24, 1e-22, 1e-20, 1e-18):
        ok = []
        for scene, mats in (("rc_cyclic_c01", "c01"), ("rc_cyclic_c02", "c02")):
            for du in (DU, DU / 2):
                try:
                    run_cyclic(scene, mats, du, tol=tol)
                    ok.append("%s du=%g ok" % (scene, du))
                except NotConverged as exc:
                    ok.append(str(exc))
        for dt in (PULSE_DT, PULSE_DT / 2):
            try:
                run_pulse(dt, tol=tol)
                ok.append("rc_pulse dt=%g ok" % dt)
            except NotConverged as exc:
                ok.append(str(exc))
        print("tol %g:" % tol)
        for line in ok:
            print("   ", line)
        sys.stdout.flush()


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--only", choices=["rc_cyclic_c01", "rc_cyclic_c02",
                                       "rc_pulse", "elastica"])
    ap.add_argument("--omega1", action="store_true")
    ap.add_argument("--probe-tol", action="store_true")
    ap.add_argument("--manifest", action="store_true")
    ap.add_argument("--strict-newton", action="store_true",
                    help="plain Newton for every scene (c02 then fails)")
    args = ap.parse_args()
    if args.strict_newton:
        for name in ALGORITHM:
            ALGORITHM[name] = ("Newton",)
    if args.omega1:
        om = omega1_by_condensation()
        print(json.dumps(om, indent=1))
        print("omega1 = %.17g  a0 = 2*%g*omega1 = %.17g" % (
            om["omega1"], DAMPING_RATIO, 2.0 * DAMPING_RATIO * om["omega1"]))
        return
    if args.probe_tol:
        probe_tolerances()
        return
    if not args.manifest:
        todo = [args.only] if args.only else ["rc_cyclic_c01", "rc_cyclic_c02",
                                              "rc_pulse", "elastica"]
        for name in todo:
            if name == "rc_cyclic_c01":
                make_cyclic(name, "c01")
            elif name == "rc_cyclic_c02":
                make_cyclic(name, "c02")
            elif name == "rc_pulse":
                make_pulse()
            else:
                make_elastica()
    write_manifest()


if __name__ == "__main__":
    main()
