//! The spring chain's line in the family table: its `model` key, axes, metrics, columns and
//! the table of its six variants (`rk4`, `dopri5`, `stormer_verlet` x `chain_nodal`,
//! `chain_modal`; `param` is `none`), each a monomorphised run function.
use super::problem::{ChainProblem, ChainSetup};
use super::verlet::StormerVerlet;
use super::{ChainObs, ChainSystem, Coordinates, Modal, Nodal};
use crate::case::{Case, CaseError, Estimate, OdeCosts, Scene, ode_estimate};
use crate::integrate::adaptive_rk::AdaptiveRk;
use crate::integrate::explicit_rk::ExplicitRk;
use crate::integrate::{Adaptive, FixedStep};
use crate::problem::figures::{Admit, Figures, Measure, Quantity, Selection, Split};
use crate::problem::{Axes, Axis, Column, Family, Metric, Problem, Stepping, Variant};
use crate::run::{Observe, RunOutput, Watched, run_adaptive, run_fixed};

/// Every variant of the chain in each plot (six lines).
const ALL: Selection = Selection {
    id: "all",
    short: "every variant",
    describe: "every variant that ran.",
    admit: Admit::All,
    legend_axes: &[Axis::Integrator, Axis::Formulation],
    split: Split::Whole,
};

/// The chain's figures: work-precision and convergence of every variant, energy over time.
const FIGURES: Figures = Figures {
    key_text: "How to read the plots: colour = integrator, solid line = chain_nodal, dashed = \
        chain_modal. Marks in a red band at the top of a plot are runs that failed (no value). \
        Log axes are labelled at powers of ten (1e-6 = 10^-6).",
    work_precision: &[ALL],
    convergence: &[ALL],
    timeseries: &[(Quantity::Energy, ALL)],
    across_scenes: &[(ALL, Measure::Primary)],
    line_styles: "chain_nodal solid, chain_modal dashed",
    colours: &[("stormer_verlet", [0, 255, 127])], // spring green
    ..Figures::NONE
};

/// The spring-chain family.
pub static FAMILY: Family = Family {
    model: "spring_chain",
    axes: Axes {
        params: &["none"],
        integrators: &["rk4", "dopri5", "stormer_verlet"],
        formulations: &["chain_nodal", "chain_modal"],
    },
    metrics: &[
        Metric::smaller_better("displacement_error_max", "m", true),
        Metric::smaller_better("velocity_error_max", "m/s", true),
        Metric::smaller_better("energy_drift_max", "1", false),
        Metric::smaller_better("energy_drift_final", "1", false),
    ],
    columns: &[
        Column {
            name: "displacement",
            width: 3,
            unit: "m",
        },
        Column {
            name: "velocity",
            width: 3,
            unit: "m/s",
        },
        Column {
            name: "energy",
            width: 1,
            unit: "J",
        },
    ],
    variants: crate::problem::Variants::Table(variants),
    static_na_reason: |_, _, _| "not registered".into(),
    load: super::case::load,
    inputs: super::case::inputs,
    estimate,
    compile,
    figures: &FIGURES,
    settings: &[],
    stability_quick: &["rk4"],
    study: None,
    // Its references: the chain's closed form (exact).
    references: &[crate::case::ReferenceKind::EXACT],
};

/// A monomorphised run.
pub type RunFn = fn(&ChainSetup, Stepping, &Observe) -> Result<RunOutput<ChainObs>, String>;

fn fixed<C: Coordinates, M: FixedStep<ChainSystem<C>>>(
    s: &ChainSetup,
    stepping: Stepping,
    observe: &Observe,
    mut m: M,
) -> Result<RunOutput<ChainObs>, String> {
    let Stepping::Dt(h) = stepping else {
        return Err("a fixed-step method needs a step".into());
    };
    let sys = ChainSystem::<C>::new(s.chain.clone());
    let x0 = C::state(&s.chain, &s.initial);
    run_fixed(&sys, &mut m, x0, h, &s.grid, &s.limits, observe)
}

fn dopri5<C: Coordinates>(
    s: &ChainSetup,
    stepping: Stepping,
    observe: &Observe,
) -> Result<RunOutput<ChainObs>, String> {
    let Stepping::Tol(tol) = stepping else {
        return Err("an adaptive method needs a tolerance".into());
    };
    let sys = ChainSystem::<C>::new(s.chain.clone());
    let x0 = C::state(&s.chain, &s.initial);
    let mut m = AdaptiveRk::dopri5(tol);
    run_adaptive(&sys, &mut m, x0, &s.grid, &s.limits, observe)
}

/// The family's table: the variant and its run function.
pub fn table() -> &'static [Variant] {
    static TABLE: std::sync::OnceLock<Vec<Variant>> = std::sync::OnceLock::new();
    TABLE.get_or_init(|| {
        let rk4 = FixedStep::<ChainSystem<Nodal>>::info(&ExplicitRk::rk4());
        let verlet = FixedStep::<ChainSystem<Nodal>>::info(&StormerVerlet::new());
        let dp5 = Adaptive::<Watched<ChainSystem<Nodal>>>::info(&AdaptiveRk::dopri5(1e-6));
        let rows: [(&str, &str, _, RunFn); 6] = [
            ("rk4", Nodal::NAME, rk4, |s, h, o| {
                fixed::<Nodal, _>(s, h, o, ExplicitRk::rk4())
            }),
            ("rk4", Modal::NAME, rk4, |s, h, o| {
                fixed::<Modal, _>(s, h, o, ExplicitRk::rk4())
            }),
            ("dopri5", Nodal::NAME, dp5, dopri5::<Nodal>),
            ("dopri5", Modal::NAME, dp5, dopri5::<Modal>),
            ("stormer_verlet", Nodal::NAME, verlet, |s, h, o| {
                fixed::<Nodal, _>(s, h, o, StormerVerlet::new())
            }),
            ("stormer_verlet", Modal::NAME, verlet, |s, h, o| {
                fixed::<Modal, _>(s, h, o, StormerVerlet::new())
            }),
        ];
        crate::problem::none_param_table(rows)
    })
}

fn variants() -> &'static [Variant] {
    table()
}

/// A chain run's costs: three masses, an evaluation of a few dozen flops (counted as 100
/// units), four evaluations a step at most (`rk4`), a sample of two 3-vectors and its
/// scores' share (counted as 200 bytes).
const COSTS: OdeCosts = OdeCosts {
    bytes_per_sample: 200.0,
    rhs_work: 100.0,
    evals_per_step: [1.0, 4.0, 4.0],
};

/// A scene's estimate: the small-state family's (`case::budget::ode_estimate`).
fn estimate(case: &Case, scene: &Scene) -> Estimate {
    ode_estimate(case, scene, &COSTS)
}

fn compile(case: &Case, scene: &Scene) -> Result<Box<dyn Problem>, CaseError> {
    Ok(Box::new(ChainProblem::new(case, scene)?))
}

/// A method registered from outside the crate does not reach the seam test's family (its
/// table is the seam's worked example).
pub struct Systems;

impl crate::problem::Instantiate for Systems {}
