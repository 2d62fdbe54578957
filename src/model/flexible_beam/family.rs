//! The flexible beam's line in the family table: its `model` key, axes, metrics, columns and
//! the table of its variants, each a monomorphised run function. `param` is `none` (the beam
//! is planar); the formulations are `fe_exact` (`fe.rs`), `modal_linear` and
//! `modal_stiffened` (`modal.rs` with their bases, `formulations.rs`); the integrators the
//! structural `newmark`, `hht` (alpha = -0.05) and `gen_alpha` (rho_inf = 0.9) on every
//! formulation, and the rigid core's generic `rk4`, `dopri5`, `dop853`, `implicit_midpoint`
//! and `gauss6` on the modal forms (`ode.rs`; `fe_exact`'s axial element modes, near 1e4
//! rad/s at ten elements, make explicit methods pointless and its size is not registered
//! there).
use super::problem::{BeamProblem, BeamSetup};
use crate::case::{Case, CaseError, Scene};
use crate::integrate::MethodInfo;
use crate::problem::figures::{
    Admit, Figures, FormulationGroup, Measure, PhysicalView, Quantity, Selection, Split,
};
use crate::problem::{Axes, Axis, Column, Family, Metric, Problem, Stepping, Variant};
use crate::run::{Observe, RunOutput};
use crate::structural::method::Method;
use crate::structural::newton::NewtonOptions;

use super::fe::Fe;
use super::formulations;
use super::modal::Modal;
use super::observe::{BeamObs, Beamlike};
use super::ode::{AsOde, run_ode};
use super::run::run_structural;
use crate::methods::second_order::{SecondOrderMethod, VisitSecondOrder};
use crate::methods::{OdeMethod, Visit, Where};
use crate::structural::gen_alpha_i3::GenAlphaI3;
use std::sync::Arc;

/// Every variant, one panel per formulation.
const BY_FORMULATION: Selection = Selection {
    id: "form",
    short: "by formulation",
    describe: "every variant that ran, one panel per formulation.",
    admit: Admit::All,
    legend_axes: &[Axis::Integrator],
    split: Split::Formulation,
};

const FIGURES: Figures = Figures {
    key_text: "How to read the plots: one panel per formulation, colour = integrator. Marks \
        in a red band at the top of a plot are runs that failed (no value; modal_linear \
        diverges on the spin-ups by design). The energy plots draw the energy balance |E - W| \
        over the case's energy_scale (their captions give it; the beam starts at rest). Log axes are labelled at \
        powers of ten (1e-6 = 10^-6).",
    work_precision: &[BY_FORMULATION],
    convergence: &[BY_FORMULATION],
    timeseries: &[
        // The series' energy is the balance's residual E - W (zero at t = 0), not an energy
        // to drift from: drawn as a balance.
        (
            Quantity::Balance {
                books: "|E - W|",
                what: "E is the beam's kinetic plus strain energy, W the work of the hub's drive \
                    or torque; the beam starts at rest, so E - W = 0 exactly. The metric \
                    energy_balance_error_max divides the same residual by each scene's own \
                    energy_scale instead.",
            },
            BY_FORMULATION,
        ),
        (
            Quantity::Constraint {
                what: "The AIGC boundary-constraint residual max |C q| (m) at the score times.",
            },
            BY_FORMULATION,
        ),
        (
            Quantity::Track {
                column: "tip_deflection",
                reference: "tip_deflection_reference",
                id: "tip",
                what: "Tip deflection v_tip (m, in the rotating frame) at the score times, \
                    against the fe_exact reference (black).",
                y_label: "v_tip (m)",
                x: None,
                groups: &[
                    FormulationGroup {
                        id: "stiffened",
                        label: "FE and stiffened modes",
                        formulations: &["fe_exact", "modal_stiffened"],
                    },
                    // Alone: its divergence (|v_tip| up to L) would flatten the others.
                    FormulationGroup {
                        id: "linear",
                        label: "linear modes",
                        formulations: &["modal_linear"],
                    },
                    FormulationGroup {
                        id: "aigc",
                        label: "AIGC",
                        formulations: &[
                            "aigc_baumgarte",
                            "aigc_projection",
                            "aigc_index3",
                            "aigc_baumgarte_soft",
                            "aigc_baumgarte_stiff",
                        ],
                    },
                ],
            },
            BY_FORMULATION,
        ),
    ],
    across_scenes: &[(BY_FORMULATION, Measure::Primary)],
    line_styles: "every line solid (one formulation per panel)",
    draw_failed: true,
    // The formulations differ in physics: the time error (the primary metric, against each
    // formulation's own time-converged run) cannot say which formulation models the beam.
    // The targets are decades and their midpoint in metres of tip deflection, not tuned.
    physical: Some(PhysicalView {
        metric: "tip_deflection_error_max",
        targets: &[1e-2, 3e-3, 1e-3],
        what: "which formulation models the beam: its tip deflection against fe_exact on the \
               reference mesh and step",
        // Met or not decided to 10 % of the target by the reference's own mesh and step
        // error (`BeamProblem::physical_claim`).
        claim_margin: 10.0,
    }),
    // The rigid body's methods keep their colours; these are the beam's own.
    colours: &[
        ("newmark", [120, 105, 0]),     // dark olive
        ("hht", [200, 0, 120]),         // magenta
        ("gen_alpha", [0, 170, 170]),   // teal
        ("gen_alpha_i3", [0, 40, 140]), // navy
    ],
    ..Figures::NONE
};

const fn column(name: &'static str, unit: &'static str) -> Column {
    Column {
        name,
        width: 1,
        unit,
    }
}

/// The flexible-beam family.
pub static FAMILY: Family = Family {
    model: "flexible_beam",
    axes: Axes {
        params: &["none"],
        integrators: &[
            "newmark",
            "hht",
            "gen_alpha",
            "rk4",
            "dopri5",
            "dop853",
            "implicit_midpoint",
            "gauss6",
            "gen_alpha_i3",
        ],
        formulations: FORMULATIONS,
    },
    metrics: &[
        Metric::smaller_better("tip_time_error_max", "m", true),
        Metric::smaller_better("tip_deflection_error_max", "m", true),
        Metric::smaller_better("hub_rate_error_max", "rad/s", true),
        Metric::smaller_better("energy_balance_error_max", "1", false),
        Metric::smaller_better("momentum_error_max", "1", false),
        Metric::smaller_better("constraint_error_max", "m", false),
        Metric::smaller_better("tip_deflection_max", "m", false),
    ],
    columns: &[
        column("tip_deflection", "m"),
        column("tip_axial", "m"),
        column("hub_angle", "rad"),
        column("hub_rate", "rad/s"),
        column("energy", "J"),
        column("energy_balance", "J"),
        column("momentum", "N m s"),
        column("constraint", "m"),
    ],
    variants: crate::problem::Variants::Table(variants),
    static_na_reason,
    load: super::case::load,
    inputs: super::case::inputs,
    estimate: super::estimate::estimate,
    compile,
    figures: &FIGURES,
    // The explicit method whose limit the search measures and the implicit ones of the
    // structural and ODE forms.
    // The reference (fe_exact with `reference_elements` at `reference_dt`) and its
    // self-convergence tracks do not use the constraint stabilisation of the AIGC forms
    // (their track is aigc_projection's), the divergence bound or the scenes' energy scale.
    settings: &[
        "numerics.baumgarte",
        "numerics.baumgarte_soft",
        "numerics.baumgarte_stiff",
        "numerics.divergence_bound",
        "scene.energy_scale",
    ],
    stability_quick: &["rk4", "newmark", "implicit_midpoint", "gen_alpha_i3"],
    study: None,
    // Its references: `fe_exact` integrated by `mbdbench reference` (numerical).
    references: &[crate::case::ReferenceKind::NUMERICAL],
};

/// The formulations, in report order.
pub const FORMULATIONS: &[&str] = &[
    "fe_exact",
    "modal_stiffened",
    "modal_linear",
    "aigc_baumgarte",
    "aigc_projection",
    "aigc_index3",
    "aigc_baumgarte_soft",
    "aigc_baumgarte_stiff",
];

/// Whether a formulation carries boundary constraints (its `constraint_error_max` applies).
pub fn constrained(formulation: &str) -> bool {
    formulation.starts_with("aigc")
}

fn static_na_reason(_param: &str, integrator: &str, formulation: &str) -> String {
    if formulation == "fe_exact" {
        format!(
            "{integrator} on fe_exact: its axial element modes (about 1e4 rad/s at ten \
             elements) leave an explicit or first-order method nothing to measure; the \
             structural methods run it"
        )
    } else {
        "not registered".into()
    }
}

/// A run's score-grid observations.
pub type Track = Vec<(f64, BeamObs)>;

/// A monomorphised run.
pub type RunFn =
    Arc<dyn Fn(&BeamSetup, Stepping, &Observe) -> Result<RunOutput<BeamObs>, String> + Send + Sync>;

fn newton() -> NewtonOptions {
    NewtonOptions::default()
}

/// A structural method on the model `build` makes.
fn structural<S: Beamlike, M: Method<S>>(
    s: &BeamSetup,
    stepping: Stepping,
    observe: &Observe,
    build: &dyn Fn(super::base::Base) -> Result<S, String>,
    mut method: M,
) -> Result<RunOutput<BeamObs>, String> {
    let Stepping::Dt(h) = stepping else {
        return Err("a structural method needs a fixed step".into());
    };
    run_structural(
        build,
        s.scene.base,
        &s.scene.breakpoints,
        &mut method,
        h,
        &s.grid,
        &s.limits,
        observe,
        s.bound(),
    )
}

/// `fe_exact` with the case's element count.
fn fe_model(s: &BeamSetup) -> impl Fn(super::base::Base) -> Result<Fe, String> + '_ {
    move |base| Fe::new(s.scene.beam, s.numerics.elements, base)
}

/// A modal formulation under a structural method.
fn modal_structural<M: Method<Modal>>(
    s: &BeamSetup,
    st: Stepping,
    o: &Observe,
    formulation: &str,
    method: M,
) -> Result<RunOutput<BeamObs>, String> {
    let build = |base| Ok(formulations::model(formulation, &s.numerics, s.scene.beam, base)?.0);
    structural(s, st, o, &build, method)
}

/// A modal formulation as an ODE of the registered size `D`.
fn ode_sized<const D: usize, M: OdeMethod>(
    s: &BeamSetup,
    st: Stepping,
    o: &Observe,
    formulation: &str,
    m: &M,
) -> Result<RunOutput<BeamObs>, String> {
    let build = |base| formulations::model(formulation, &s.numerics, s.scene.beam, base);
    run_ode::<Modal, D, M>(
        &build,
        s.scene.base,
        &s.scene.breakpoints,
        m,
        st,
        &s.grid,
        &s.limits,
        o,
        s.bound(),
    )
}

/// A modal formulation as an ODE, dispatched on its size (`formulations::ODE_SIZES`).
fn ode<M: OdeMethod>(
    s: &BeamSetup,
    st: Stepping,
    o: &Observe,
    formulation: &str,
    which: &M,
) -> Result<RunOutput<BeamObs>, String> {
    let free = usize::from(matches!(s.scene.base, super::base::Base::Free { .. }));
    let n = formulations::size(formulation, &s.numerics).ok_or("not a modal formulation")? + free;
    match n {
        4 => ode_sized::<10, M>(s, st, o, formulation, which),
        5 => ode_sized::<12, M>(s, st, o, formulation, which),
        6 => ode_sized::<14, M>(s, st, o, formulation, which),
        15 => ode_sized::<32, M>(s, st, o, formulation, which),
        16 => ode_sized::<34, M>(s, st, o, formulation, which),
        n => Err(format!(
            "{formulation} has {n} coordinates, whose state size is not registered"
        )),
    }
}

/// The ODE forms, in table order (`aigc_index3` is a DAE: its structural method alone runs
/// it).
const ODE_FORMS: [&str; 6] = [
    "modal_stiffened",
    "modal_linear",
    "aigc_baumgarte",
    "aigc_baumgarte_soft",
    "aigc_baumgarte_stiff",
    "aigc_projection",
];

/// The built-in generic methods a form does not run (a method from outside the crate runs on
/// every ODE form): explicit Euler nowhere (its growth on the undamped modes leaves nothing to
/// measure); the AIGC studies keep to the methods their comparison needs: the Baumgarte
/// trade-off (soft and stiff) under one explicit and one implicit method (the implicit one's
/// Newton error is what Baumgarte damps), the index-3 form under its structural method only.
fn declines(formulation: &str, integrator: &str) -> bool {
    let declined: &[&str] = match formulation {
        "modal_stiffened" | "modal_linear" => &["euler"],
        "aigc_baumgarte" => &["euler", "dop853", "gauss6"],
        "aigc_baumgarte_soft" | "aigc_baumgarte_stiff" => &["euler", "dopri5", "dop853", "gauss6"],
        "aigc_projection" => &["euler", "implicit_midpoint", "gauss6"],
        _ => return true,
    };
    declined.contains(&integrator)
}

/// The ODE rows: each method it is handed on every ODE form that runs it, its facts taken on
/// a modal system (they do not depend on the form).
struct OdeRows(Vec<(&'static str, &'static str, MethodInfo, RunFn)>);

impl Visit for OdeRows {
    fn method<M: OdeMethod>(&mut self, name: &'static str, at: Where, m: M) {
        if !at.admits::<AsOde<Modal, 10>>() {
            return;
        }
        let info = m.info::<AsOde<Modal, 10>>();
        let m = Arc::new(m);
        for form in ODE_FORMS {
            if declines(form, name) {
                continue;
            }
            let m = Arc::clone(&m);
            let run: RunFn = Arc::new(move |s, st, o| ode(s, st, o, form, &*m));
            self.0.push((name, form, info, run));
        }
    }
}

/// What the beam makes of a method registered from outside the crate: a first-order method on
/// every ODE form, a structural method on every second-order form.
pub struct Systems;

impl crate::problem::Instantiate for Systems {
    fn ode<M: OdeMethod + Clone>(name: &'static str, at: Where, m: M) -> Vec<Variant> {
        let mut rows = OdeRows(vec![]);
        rows.method(name, at, m);
        crate::problem::none_param_table(rows.0)
    }
    fn second_order<M: SecondOrderMethod + Clone>(name: &'static str, m: M) -> Vec<Variant> {
        let mut rows = StructuralRows(vec![]);
        rows.method(name, m);
        crate::problem::none_param_table(rows.0)
    }
}

/// The second-order forms, in table order: the structural methods run them.
const SECOND_ORDER_FORMS: [&str; 3] = ["fe_exact", "modal_stiffened", "modal_linear"];

/// The structural rows: each method it is handed on every second-order form, its facts taken
/// on `fe_exact` (they do not depend on the form).
struct StructuralRows(Vec<(&'static str, &'static str, MethodInfo, RunFn)>);

impl VisitSecondOrder for StructuralRows {
    fn method<M: SecondOrderMethod>(&mut self, name: &'static str, m: M) {
        let info = Method::<Fe>::info(&m.on::<Fe>());
        let m = Arc::new(m);
        for form in SECOND_ORDER_FORMS {
            let m = Arc::clone(&m);
            let run: RunFn = if form == "fe_exact" {
                Arc::new(move |s, st, o| structural(s, st, o, &fe_model(s), m.on::<Fe>()))
            } else {
                Arc::new(move |s, st, o| modal_structural(s, st, o, form, m.on::<Modal>()))
            };
            self.0.push((name, form, info, run));
        }
    }
}

/// The family's table: the variant and its run function.
pub fn table() -> &'static [Variant] {
    static TABLE: std::sync::OnceLock<Vec<Variant>> = std::sync::OnceLock::new();
    TABLE.get_or_init(|| {
        let mut ode_rows = OdeRows(vec![]);
        crate::methods::builtin::each(&mut ode_rows);
        let mut structural_rows = StructuralRows(vec![]);
        crate::methods::second_order::each(&mut structural_rows);
        // Each form's rows: the structural methods', then the ODE methods', in method order.
        let mut rows: Vec<(&'static str, &'static str, MethodInfo, RunFn)> = vec![];
        for form in SECOND_ORDER_FORMS.iter().chain(&ODE_FORMS[2..]) {
            for r in structural_rows.0.iter().chain(&ode_rows.0).filter(|r| r.1 == *form) {
                rows.push((r.0, r.1, r.2, Arc::clone(&r.3)));
            }
        }
        let i3 = Method::<Modal>::info(&GenAlphaI3::new(0.9, newton()).expect("valid"));
        rows.push((
            "gen_alpha_i3",
            "aigc_index3",
            i3,
            Arc::new(|s, st, o| {
                let build = |base| {
                    Ok(formulations::model("aigc_index3", &s.numerics, s.scene.beam, base)?.0)
                };
                structural(s, st, o, &build, GenAlphaI3::new(0.9, newton())?)
            }),
        ));
        crate::problem::none_param_table(rows)
    })
}

fn variants() -> &'static [Variant] {
    table()
}

fn compile(case: &Case, scene: &Scene) -> Result<Box<dyn Problem>, CaseError> {
    Ok(Box::new(BeamProblem::new(case, scene)?))
}

/// The reference's cross-check by another formulation and integrator, when one is
/// registered: its method and its score-grid track.
/// `modal_stiffened` (the case's modes, `dop853` at tolerance 1e-10): another formulation,
/// another integrator and no mesh.
pub fn cross_check(s: &BeamSetup) -> Result<(String, Result<Track, String>), String> {
    let v = FAMILY
        .find("none", "dop853", "modal_stiffened")
        .ok_or("dop853/modal_stiffened is not registered")?;
    Ok((
        format!(
            "modal_stiffened ({} bending, {} rod modes), dop853 at tolerance 1e-10",
            s.numerics.bending_modes, s.numerics.axial_modes
        ),
        track(s, v, Stepping::Tol(1.0e-10))?,
    ))
}

/// A run of `v` on the score grid: Err when it cannot start, Ok(Err) with the failure's
/// kind, time and message when it failed.
pub fn track(s: &BeamSetup, v: &Variant, st: Stepping) -> Result<Result<Track, String>, String> {
    let mut g = s.clone();
    g.grid.sample_every = g.grid.score_every;
    let out = BeamProblem::run_with(&g, v, st, &Observe::Grid)?;
    Ok(match out.failure {
        Some(f) => Err(format!("{} at t = {}: {}", f.kind.name(), f.t, f.message)),
        None => Ok(out.scored().map(|x| (x.t, x.obs)).collect()),
    })
}

/// How a formulation's self-convergence track (`reference.rs`) is computed.
#[derive(Debug, Clone, Copy)]
pub enum SelfPlan {
    /// An adaptive method at two tolerances: the tighter run is the track, their difference
    /// its error estimate (conservative by about the tolerance ratio).
    Tolerances(f64, f64),
    /// A symmetric order-2 method at `h`, `h/2`, `h/4`, extrapolated twice
    /// (`R(h) = (4 y(h/2) - y(h)) / 3`, error `O(h^4)`): the track is `R(h/2)`, the estimate
    /// `|R(h/2) - R(h)|` (about 15 times its error).
    Richardson(f64),
}

/// The self-convergence plan of a formulation on a scene whose reference step is `h_ref`:
/// the variant, the plan and a description. `fe_exact`: Newmark extrapolated from `h`, `h/2`,
/// `h/4` with `h = min(h_ref, 1e-3 s)` (at flexsat's 5e-3 s the rod's modes, `h omega` near 1,
/// are not yet asymptotic and the estimate is 3.5e-7 m, against 1e-10 at 1e-3 s; Newmark is the trapezoidal rule on the first-order form, whose error
/// expands in even powers of the step on each smooth segment); the modal forms: `dop853` at
/// tolerances 1e-13 and 1e-12; every AIGC form: `aigc_projection` under `dop853` likewise
/// (with consistent initial values the Baumgarte, projected and index-3 forms share the
/// constrained solution).
pub fn self_convergence(
    formulation: &str,
    h_ref: f64,
) -> Option<(&'static Variant, SelfPlan, String)> {
    let (integrator, form, plan) = match formulation {
        "fe_exact" => (
            "newmark",
            "fe_exact",
            SelfPlan::Richardson(h_ref.min(1.0e-3)),
        ),
        "modal_linear" | "modal_stiffened" => (
            "dop853",
            formulation,
            SelfPlan::Tolerances(1.0e-13, 1.0e-12),
        ),
        // Every AIGC form converges to the one solution of the constrained equations.
        f if constrained(f) => (
            "dop853",
            "aigc_projection",
            SelfPlan::Tolerances(1.0e-13, 1.0e-12),
        ),
        _ => return None,
    };
    let v = FAMILY.find("none", integrator, form)?;
    let what = match plan {
        SelfPlan::Tolerances(a, b) => {
            format!("{integrator}/{form} at tolerance {a:e}, checked against {b:e}")
        }
        SelfPlan::Richardson(h) => format!(
            "{integrator}/{form} at {h:e}, {:e}, {:e} s, extrapolated twice (Richardson, order 4)",
            h / 2.0,
            h / 4.0
        ),
    };
    Some((v, plan, what))
}
