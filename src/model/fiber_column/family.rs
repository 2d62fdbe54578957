//! The fiber column's line in the family table: its `model` key, axes, metrics, columns and
//! the table of its variants, each a run function monomorphised over the nodal rotation
//! chart. `param` is the chart of the nodes' rotations (`so3`, `quat_proj`, `rotvec`,
//! `matrix_proj`: the rotation module's `RotationChart`s); the formulations are `force_based` (the case's element
//! count), `force_based_fine` (`fine_elements`, the static scenes' mesh check) and the
//! displacement-based rivals `disp_based_n1`, `_n2`, `_n4`, `_n8` (that many elements); the
//! integrators are the static solution algorithms of `structural::equilibrium`:
//! `newton_load` (Newton, load control), `newton_disp`, `newton_disp_ls` (with the energy line
//! search) and `newton_disp_krylov` (Krylov-accelerated, Carlson & Miller) under displacement
//! control, and the structural methods on the pulse (`newmark`, `hht`, `gen_alpha`, the
//! flexible beam's, and the energy-consistent `midpoint`; `dynamic.rs`). Which apply to a
//! scene follows from its loading (`problem.rs`, `na_reason`).
use super::column::Column as Structure;
use super::problem::FiberProblem;
use super::run::{ColumnSetup, Form, Keep, RunOut, run_static};
use super::run_dynamic::Pulse;
use super::run_dynamic::run_dynamic;
use crate::case::{Case, CaseError, Scene};
use crate::integrate::MethodInfo;
use crate::problem::figures::{
    Admit, Figures, FormulationGroup, Measure, Quantity, Selection, Split,
};
use crate::problem::{Axes, Axis, Column, Family, Metric, Problem, Variant};
use crate::rotation::{MatrixProj, PoseChart, QuatProj, RotVec, So3};
use crate::structural::equilibrium::{Equilibrium, Newton, NewtonLineSearch};
use crate::structural::gen_alpha::GenAlpha;
use crate::structural::hht::Hht;
use crate::structural::krylov_newton::KrylovNewton;
use crate::structural::method::Method;
use crate::structural::midpoint::Midpoint;
use crate::structural::newmark::Newmark;
use crate::structural::newton::NewtonOptions;

/// The so3 variants, one panel per formulation: the algorithms and schemes side by side.
/// The other charts reach the same equilibria (the tables and the heat map compare them), so
/// the plots leave them out and the report stays within its size budget.
const SO3_BY_FORMULATION: Selection = Selection {
    id: "so3",
    short: "so3, by formulation",
    describe: "the variants on the so3 chart, one panel per formulation (the other charts are \
        in the tables).",
    admit: Admit::Param("so3"),
    legend_axes: &[Axis::Integrator],
    split: Split::Formulation,
};

const FORMS_FB: FormulationGroup = FormulationGroup {
    id: "fb",
    label: "force-based",
    formulations: &["force_based", "force_based_fine"],
};
const FORMS_DB: FormulationGroup = FormulationGroup {
    id: "db",
    label: "force-based against displacement-based meshes",
    formulations: &[
        "force_based",
        "disp_based_n1",
        "disp_based_n2",
        "disp_based_n4",
        "disp_based_n8",
    ],
};

/// The stepped parameter of a column scene: the load factor (static), the protocol's
/// displacement increments (cyclic), time in seconds (the pulse).
fn t_axis(scene: &crate::case::Scene) -> (&'static str, &'static str) {
    match scene
        .physics::<super::case::ColumnScene>()
        .map(|s| s.loading.kind())
    {
        Some("static") => ("load factor t (1)", "load step dt (load factor)"),
        Some("cyclic") => (
            "protocol increment t (count)",
            "step dt (protocol increments)",
        ),
        _ => crate::problem::figures::seconds(scene),
    }
}

const FIGURES: Figures = Figures {
    key_text: "How to read the plots: the so3 chart, one panel per formulation, colour = \
        solution algorithm or time scheme. Static scenes step the load factor t (0 to 1), cyclic scenes the \
        protocol's 0.5 mm increments, the pulse real time. Marks in a red band at the top of \
        a plot are runs that failed (a typed newton_failure). Log axes are labelled at powers \
        of ten (1e-6 = 10^-6).",
    work_precision: &[SO3_BY_FORMULATION],
    // No convergence plots: a static path's error does not fall with the load step, and the
    // dynamic schemes' order (2.03 for all four, dynamic_tests.rs) shows in work-precision.
    convergence: &[],
    timeseries: &[
        (
            Quantity::Track {
                column: "top_displacement",
                reference: "top_displacement_reference",
                id: "top",
                what: "The top's displacement across the axis (m) at the score times, \
                    against the reference (black): the exact elastica or circle, or \
                    OpenSees' run of the same column.",
                y_label: "u_top (m)",
                groups: &[FORMS_FB, FORMS_DB],
                x: None,
            },
            SO3_BY_FORMULATION,
        ),
        (
            Quantity::Track {
                column: "base_shear",
                reference: "base_shear_reference",
                id: "shear",
                what: "The hysteresis loop: the base shear (N) against the top's displacement \
                    (m) at the score times, against OpenSees' run of the same column (black).",
                y_label: "V (N)",
                groups: &[FORMS_DB],
                x: Some((
                    "top_displacement",
                    "top_displacement_reference",
                    "u_top (m)",
                )),
            },
            SO3_BY_FORMULATION,
        ),
        (
            Quantity::Balance {
                books: "|K + U + D - W|",
                what: "Kinetic, recoverable strain and dissipated energy against the input \
                    work. The pulse's books (the static and cyclic scenes keep none): every \
                    scheme's input and damping work by one trapezoid rule along its own \
                    discrete path, the fibres' work by the trapezoid rule over their strain \
                    increments. The energy-consistent midpoint rule closes the balance by \
                    construction (to round-off); Newmark, HHT and generalized-alpha do not, \
                    and their residual falls as the step squared.",
            },
            SO3_BY_FORMULATION,
        ),
    ],
    across_scenes: &[(SO3_BY_FORMULATION, Measure::Primary)],
    line_styles: "every line solid (one formulation per panel)",
    t_axis,
    // newmark, hht and gen_alpha keep the beam's colours.
    colours: &[
        ("newton_load", [230, 140, 0]),        // amber
        ("newton_disp", [30, 110, 220]),       // blue
        ("newton_disp_ls", [0, 20, 0]),        // near black
        ("newton_disp_krylov", [220, 40, 40]), // red
        ("midpoint", [60, 160, 60]),           // green
    ],
    ..Figures::NONE
};

const fn metric(name: &'static str, unit: &'static str, reference_error: bool) -> Metric {
    Metric {
        name,
        unit,
        reference_error,
        higher_is_better: false,
    }
}

const fn column(name: &'static str, unit: &'static str) -> Column {
    Column {
        name,
        width: 1,
        unit,
    }
}

/// The rotation charts, in report order.
pub const PARAMS: &[&str] = &["so3", "quat_proj", "rotvec", "matrix_proj"];
/// The formulations, in report order.
pub const FORMULATIONS: &[&str] = &[
    "force_based",
    "force_based_fine",
    "disp_based_n1",
    "disp_based_n2",
    "disp_based_n4",
    "disp_based_n8",
];
/// The solution algorithms (static) and schemes (dynamic), in report order.
pub const INTEGRATORS: &[&str] = &[
    "newton_load",
    "newton_disp",
    "newton_disp_ls",
    "newton_disp_krylov",
    "newmark",
    "hht",
    "gen_alpha",
    "midpoint",
];

/// The dynamic schemes, the structural module's methods: HHT with alpha = -0.05 and
/// generalized-alpha with rho_inf = 0.9, as on the flexible beam (their Newton options serve
/// second-order systems; on the column the steps are solved by the column's Newton).
macro_rules! scheme {
    ("newmark") => {
        Newmark::new(NewtonOptions::default()).expect("valid defaults")
    };
    ("hht") => {
        Hht::default()
    };
    ("gen_alpha") => {
        GenAlpha::default()
    };
    ("midpoint") => {
        Midpoint
    };
}

/// The static solution algorithms: `newton_load` and `newton_disp` are Newton under load
/// and displacement control (the scene decides which), `_ls` with the energy line search,
/// `_krylov` Krylov-accelerated.
macro_rules! solver {
    ("newton_disp_ls") => {
        NewtonLineSearch::new
    };
    ("newton_disp_krylov") => {
        KrylovNewton::new
    };
    ($other:literal) => {
        Newton::new
    };
}

/// The fiber-column family.
pub static FAMILY: Family = Family {
    model: "fiber_column",
    axes: Axes {
        params: PARAMS,
        integrators: INTEGRATORS,
        formulations: FORMULATIONS,
    },
    metrics: &[
        metric("tip_error", "1", true),
        metric("tip_error_max", "1", true),
        metric("base_shear_error_rms", "1", true),
        metric("base_shear_error_max", "1", true),
        metric("dissipated_energy_error", "1", true),
        metric("top_displacement_error_max", "1", true),
        metric("peak_displacement_error", "1", true),
        metric("residual_displacement_error", "1", true),
        metric("energy_balance_error_max", "1", false),
        metric("equilibrium_residual_max", "1", false),
    ],
    columns: &[
        column("top_displacement", "m"),
        column("top_axial", "m"),
        column("top_rotation", "rad"),
        column("base_shear", "N"),
        column("axial_force", "N"),
        column("energy_kinetic", "J"),
        column("energy_strain", "J"),
        column("energy_dissipated", "J"),
        column("work_input", "J"),
    ],
    variants: crate::problem::Variants::Table(variants),
    static_na_reason,
    load: super::case::load,
    inputs: super::case::inputs,
    estimate: super::estimate::estimate,
    compile,
    figures: &FIGURES,
    // The four schemes of the pulse and the static scenes' load control.
    // The static scenes' reference is exact and the cyclic and dynamic ones are OpenSees'
    // runs (bound to their model by `reference.rs`): none depends on the column's own
    // solver settings.
    settings: &["numerics"],
    stability_quick: &["newmark", "hht", "gen_alpha", "midpoint", "newton_load"],
    study: None,
    // Its references: the static scenes' elastica (exact), the cyclic and pulse scenes' OpenSees runs (external).
    references: &[
        crate::case::ReferenceKind::EXACT,
        crate::case::ReferenceKind::EXTERNAL,
    ],
};

fn static_na_reason(param: &str, integrator: &str, formulation: &str) -> String {
    if param != "so3"
        && (formulation.starts_with("disp_based") || integrator.starts_with("newton_disp_"))
    {
        "the chart axis is compared on force_based under newton_load and newton_disp; the \
         rival meshes and the accelerated algorithms run on so3 (at the RC top's rotation of at \
         most 0.045 rad the charts converge to the same equilibrium)"
            .into()
    } else if !integrator.starts_with("newton") && formulation != "force_based" {
        format!(
            "{integrator} runs the pulse on force_based, the column the OpenSees reference \
             models; the rival meshes are compared on the cyclic scenes"
        )
    } else if param != "so3" && !integrator.starts_with("newton") {
        format!("the chart axis is compared on the pulse under newmark; {integrator} runs on so3")
    } else if integrator == "newton_load" && formulation.starts_with("disp_based") {
        "newton_load runs the elastic scenes, where a displacement-based element with an \
         elastic section equals the force-based one (tested); the rival meshes run the \
         cyclic scenes"
            .into()
    } else if integrator != "newton_load" && formulation == "force_based_fine" {
        "force_based_fine is the static scenes' mesh check".into()
    } else if integrator.starts_with("newton_disp_") && formulation.starts_with("disp_based") {
        format!(
            "{integrator} is compared with newton_disp on force_based, the formulation whose \
             element iterations meet the c02 cycling step; the rival meshes run newton_disp"
        )
    } else {
        "not registered".into()
    }
}

/// A monomorphised run.
pub type RunFn = fn(&ColumnSetup, f64, Keep) -> Result<RunOut, String>;

/// The facts of a static algorithm under its integrator name: the solver's (implicit,
/// structural, order 2 as the step ladders' class: a static path has no time-discretisation
/// order and its error against the reference does not fall with the load step).
fn static_info<E: Equilibrium<Structure<So3>>>(name: &'static str, solver: E) -> MethodInfo {
    MethodInfo {
        name,
        ..solver.info()
    }
}

/// The facts of a dynamic scheme: the structural method's (order 2, `dynamic_tests.rs`;
/// the midpoint rule energy-conserving).
fn dynamic_info<M: Method<Pulse<So3>>>(method: M) -> MethodInfo {
    method.info()
}

fn form(formulation: &str) -> Form {
    match formulation {
        "force_based_fine" => Form::ForceBasedFine,
        "disp_based_n1" => Form::DispBased(1),
        "disp_based_n2" => Form::DispBased(2),
        "disp_based_n4" => Form::DispBased(4),
        "disp_based_n8" => Form::DispBased(8),
        _ => Form::ForceBased,
    }
}

/// One row per static `(integrator, formulation)` on chart `C`.
macro_rules! static_rows {
    ($rows:ident, $C:ty, $int:tt, [$($form:literal),*]) => {
        $(
            $rows.push((<$C>::NAME, $int, $form, static_info($int, solver!($int)(1.0, 1).expect("valid")), |s, dt, k| {
                run_static::<$C, _>(s, form($form), solver!($int), dt, k)
            }));
        )*
    };
}

/// The chart axis is compared on the force-based column under the plain algorithms; `so3`
/// also carries the rival meshes and the accelerated algorithms (compared where they matter:
/// the force-based element's path through c02's cycling step).
macro_rules! chart_rows {
    ($rows:ident, $C:ty) => {
        static_rows!(
            $rows,
            $C,
            "newton_load",
            ["force_based", "force_based_fine"]
        );
        static_rows!($rows, $C, "newton_disp", ["force_based"]);
        dynamic_rows!($rows, $C, ["newmark"]);
    };
}

/// One row per dynamic scheme on chart `C`, force-based.
macro_rules! dynamic_rows {
    ($rows:ident, $C:ty, [$($int:tt),*]) => {
        $(
            $rows.push((<$C>::NAME, $int, "force_based", dynamic_info(scheme!($int)), |s, dt, k| {
                run_dynamic::<$C, _>(s, Form::ForceBased, scheme!($int), dt, k)
            }));
        )*
    };
}

macro_rules! so3_rows {
    ($rows:ident) => {
        dynamic_rows!($rows, So3, ["newmark", "hht", "gen_alpha", "midpoint"]);
        static_rows!(
            $rows,
            So3,
            "newton_load",
            ["force_based", "force_based_fine"]
        );
        static_rows!(
            $rows,
            So3,
            "newton_disp",
            [
                "force_based",
                "disp_based_n1",
                "disp_based_n2",
                "disp_based_n4",
                "disp_based_n8"
            ]
        );
        static_rows!($rows, So3, "newton_disp_ls", ["force_based"]);
        static_rows!($rows, So3, "newton_disp_krylov", ["force_based"]);
    };
}

/// The family's table: the variant and its run function.
pub fn table() -> &'static [Variant] {
    static TABLE: std::sync::OnceLock<Vec<Variant>> = std::sync::OnceLock::new();
    TABLE.get_or_init(|| {
        let mut rows: Vec<(&'static str, &'static str, &'static str, MethodInfo, RunFn)> = vec![];
        so3_rows!(rows);
        chart_rows!(rows, QuatProj);
        chart_rows!(rows, RotVec);
        chart_rows!(rows, MatrixProj);
        crate::problem::variant_table(rows)
    })
}

fn variants() -> &'static [Variant] {
    table()
}

fn compile(case: &Case, scene: &Scene) -> Result<Box<dyn Problem>, CaseError> {
    Ok(Box::new(FiberProblem::new(case, scene)?))
}

/// No system of the method faces' kinds: the column's schemes run on path-dependent
/// structures, its algorithms on load paths (a method registered from outside the crate does
/// not reach it).
pub struct Systems;

impl crate::problem::Instantiate for Systems {}
