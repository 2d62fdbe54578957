//! The rigid body's figures in the report (`problem::figures`): three selections that together
//! draw every registered integrator and every parameterization (rk4 on every chart: the charts
//! at equal method; every adaptive method on every chart over its tolerance ladder; every
//! integrator on `so3`, the only chart the geometric methods run on), each split into panels
//! of at most eight lines (rk4 by chart group; the adaptive methods by chart group and
//! formulation; so3 by integrator kind, without the Kahan-compensated twins, which belong to
//! the stability study's long horizon), the energy and
//! quaternion/matrix constraint drift over time, the Euler charts' breakdown across the scenes
//! of a case (error, the chart's conditioning, adaptive cost), and the Euler-angle charts as
//! the group the narrative contrasts with the others (their singular sets).
use crate::problem::Axis;
use crate::problem::figures::{
    Admit, ChartGroup, Figures, Measure, ParamGroup, Quantity, Selection, Split,
};

/// rk4 on every parameterization, both formulations.
const RK4: Selection = Selection {
    id: "rk4",
    short: "rk4",
    describe: "rk4 (classical RK4 on additive charts, RKMK4 on Lie-group charts) on every \
               parameterization that ran, both formulations.",
    admit: Admit::Integrator("rk4"),
    legend_axes: &[Axis::Param, Axis::Formulation],
    split: Split::ParamGroup,
};

/// Every adaptive method on every parameterization, both formulations.
const ADAPTIVE: Selection = Selection {
    id: "adaptive",
    short: "adaptive",
    describe: "every adaptive method (dopri5, dop853) on every parameterization that ran, over \
               its tolerance ladder, both formulations.",
    admit: Admit::Adaptive,
    legend_axes: &[Axis::Param, Axis::Integrator, Axis::Formulation],
    split: Split::ParamGroupFormulation,
};

/// Every integrator on the so3 chart, both formulations.
const SO3: Selection = Selection {
    id: "so3",
    short: "so3",
    describe: "every integrator on the so3 chart (unit quaternion on SO(3)), both \
               formulations (the geometric methods run in the body formulation only; the \
               Kahan-compensated twins are in the stability study's long horizon).",
    admit: Admit::Param("so3"),
    legend_axes: &[Axis::Integrator, Axis::Formulation],
    split: Split::Kind,
};

const CONSTRAINT: Quantity = Quantity::Constraint {
    what: "The chart's own constraint residual (||q|^2 - 1| for quaternions, |R^T R - I| for \
           matrices, the dual quaternion's two) at the score times. ",
};

/// The rigid body's declaration.
pub const FIGURES: Figures = Figures {
    key_text: "How to read the plots: colour = integrator, marker = \
    parameterization (triangles: Euler angles; diamonds: rotvec hollow, so3 filled; circles: \
    quat hollow, quat_proj filled; squares: matrix hollow, matrix_proj filled; x: se3_hq; +: \
    dual_quat), solid line = body formulation, dashed = spatial. Marks in a red band at the \
    top of a plot are runs that failed (no value). Log axes are labelled at powers of ten \
    (1e-6 = 10^-6). Each plot's caption says which variants and which ladder points it draws.",
    work_precision: &[RK4, ADAPTIVE, SO3],
    convergence: &[RK4, SO3],
    timeseries: &[
        (Quantity::Energy, RK4),
        (Quantity::Energy, SO3),
        (CONSTRAINT, RK4),
        (CONSTRAINT, SO3),
    ],
    across_scenes: &[
        (RK4, Measure::Primary),
        (
            RK4,
            Measure::Metric {
                name: "conditioning_min",
                id: "scenes_conditioning",
                what: "the chart's minimum conditioning along the run per scene (0 on its \
                       singular set; charts without one stay at 1)",
            },
        ),
        (ADAPTIVE, Measure::RhsEvals),
    ],
    chart_group: Some(ChartGroup {
        prefix: "euler_",
        label: "Euler-angle charts",
        one: "an Euler chart",
        compare_with: "so3",
    }),
    param_groups: &[
        ParamGroup {
            id: "minimal",
            label: "Euler angles and rotvec",
            params: &["euler_xyz", "euler_zyx", "euler_zxz", "rotvec"],
        },
        ParamGroup {
            id: "embedded",
            label: "quaternions and matrices",
            params: &["quat", "quat_proj", "matrix", "matrix_proj"],
        },
        ParamGroup {
            id: "group",
            label: "Lie-group charts",
            params: &["so3", "se3_hq", "dual_quat"],
        },
    ],
    line_styles: "body formulation solid, spatial dashed",
    colours: &[
        ("euler", [127, 127, 127]),                 // grey
        ("rk4", [31, 119, 180]),                    // blue
        ("dopri5", [255, 127, 14]),                 // orange
        ("dop853", [214, 39, 40]),                  // red
        ("implicit_midpoint", [44, 160, 44]),       // green
        ("gauss6", [148, 103, 189]),                // purple
        ("lie_euler", [140, 86, 75]),               // brown
        ("cg3", [227, 119, 194]),                   // pink
        ("splitting", [23, 190, 207]),              // cyan
        ("lgvi", [188, 189, 34]),                   // olive
        ("simo_wong", [0, 0, 0]),                   // black
        ("lie_gen_alpha", [57, 59, 121]),           // indigo
        ("implicit_midpoint_kahan", [0, 100, 100]), // dark teal
        ("gauss6_kahan", [120, 60, 0]),             // dark brown
        ("simo_wong_kahan", [0, 90, 75]),           // dark sea green
    ],
    ..Figures::NONE
};
