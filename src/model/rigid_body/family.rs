//! The rigid-body family's line in the family table (`catalogue::FAMILIES`): its case-file key
//! `rigid_body`, the three record axes in report order (the 11 pose charts, the integrators
//! of the rigid core, the `body` / `spatial` Newton-Euler formulations), its metrics
//! (cases/README.md, "Rigid-body metrics") and trajectory columns, and the registered variants of
//! `registry.rs` as the family-independent [`Variant`] the suite dispatches through.
use crate::case::{Case, CaseError, Estimate, OdeCosts, ReferenceKind, Scene, ode_estimate};
use crate::problem::{Axes, Column, Family, Metric, Problem, Variant};
use crate::model::rigid_body::registry;

/// The rigid-body family.
pub static FAMILY: Family = Family {
    model: "rigid_body",
    axes: Axes {
        params: registry::PARAMS,
        integrators: registry::INTEGRATORS,
        formulations: registry::FORMULATIONS,
    },
    metrics: METRICS,
    columns: COLUMNS,
    variants: crate::problem::Variants::Table(variants),
    static_na_reason: registry::static_na_reason,
    load: super::case::load,
    inputs: super::case::inputs,
    estimate,
    compile,
    figures: &super::figures::FIGURES,
    // Every rigid-body key is physics: the references are integrated or exact from the
    // body, springs and initial state alone.
    settings: &[],
    stability_quick: &[],
    study: Some(super::stability::study),
    // Its references: integrated by `mbdbench reference` (numerical) or the torque-free closed form (exact).
    references: &[crate::case::ReferenceKind::NUMERICAL, crate::case::ReferenceKind::EXACT],
};

/// The metrics of rigid-body cases (cases/README.md, "Rigid-body metrics").
pub const METRICS: &[Metric] = &[
    Metric::smaller_better("position_error_max", "m", true),
    Metric::smaller_better("rotation_error_max", "rad", true),
    Metric::smaller_better("velocity_error_max", "m/s", true),
    Metric::smaller_better("omega_error_max", "rad/s", true),
    Metric::smaller_better("energy_drift_max", "1", false),
    Metric::smaller_better("energy_drift_final", "1", false),
    Metric::smaller_better("momentum_drift_max", "1", false),
    Metric::smaller_better("constraint_error_max", "1", false),
    Metric {
        name: "conditioning_min",
        unit: "1",
        reference_error: false,
        higher_is_better: true,
    },
];

/// The trajectory and reference columns after `t` (docs/schemas.md, "Trajectory files").
pub const COLUMNS: &[Column] = &[
    Column {
        name: "position",
        width: 3,
        unit: "m",
    },
    Column {
        name: "quaternion",
        width: 4,
        unit: "1",
    },
    Column {
        name: "velocity",
        width: 3,
        unit: "m/s",
    },
    Column {
        name: "omega_body",
        width: 3,
        unit: "rad/s",
    },
    Column {
        name: "energy",
        width: 1,
        unit: "J",
    },
];

/// The registered variants, in the order of `registry::variants()` (`index` into it), each
/// carrying its registry entry as its run.
fn variants() -> &'static [Variant] {
    static TABLE: std::sync::OnceLock<Vec<Variant>> = std::sync::OnceLock::new();
    TABLE.get_or_init(|| seam_variants(registry::variants().iter().cloned()))
}

/// The registry's variants as the seam's, numbered from 0.
fn seam_variants(vs: impl Iterator<Item = registry::Variant>) -> Vec<Variant> {
    vs.enumerate()
        .map(|(index, v)| Variant {
            param: v.param,
            integrator: v.integrator,
            formulation: v.formulation,
            info: v.info,
            index,
            runner: crate::problem::Runner::new(v),
        })
        .collect()
}

/// What the rigid body makes of a method registered from outside the crate: a first-order
/// method on every chart and formulation where it applies; no second-order system.
pub struct Systems;

impl crate::problem::Instantiate for Systems {
    fn ode<M: crate::methods::OdeMethod + Clone>(
        name: &'static str,
        at: crate::methods::Where,
        m: M,
    ) -> Vec<Variant> {
        seam_variants(registry::instantiate(name, at, m).into_iter())
    }
}

/// A rigid-body run's costs, measured on the catalogue's quick tier (this machine, one job):
/// an evaluation of the equations of motion takes 60 to 580 ns (the nine springs' dearest),
/// counted as 600 units; per step, explicit methods take their stages, the implicit ones up
/// to 17.6 evaluations (`implicit_midpoint`, order 2) and 48 (`gauss6`); a sample with its
/// scores', series' and trajectory columns' share holds 364 bytes in a run (1e5 samples:
/// 36 MB, `tests/estimates.rs`), counted as 400.
const COSTS: OdeCosts = OdeCosts {
    bytes_per_sample: 400.0,
    rhs_work: 600.0,
    evals_per_step: [1.0, 18.0, 50.0],
};

/// A scene's estimate (`case::budget::ode_estimate`), and a numerical reference's `gauss6`
/// run over the horizon at its fine step (`reference` makes it, `reference --check` remakes
/// it), named by the scene's `t_end`.
fn estimate(case: &Case, scene: &Scene) -> Estimate {
    let e = ode_estimate(case, scene, &COSTS);
    let Some(c) = super::case::RigidCase::of(case) else {
        return e;
    };
    if case.reference != ReferenceKind::NUMERICAL {
        return e;
    }
    let grid = crate::run::Grid::of_scene(scene);
    let h = super::refgen::reference_step(&grid, c.body.pivot_com.is_some());
    let key = format!("scene[{}].t_end", scene.index);
    let bytes = (scene.n_score + 1) as f64 * COSTS.bytes_per_sample;
    e.max(Estimate::run(
        bytes,
        &key,
        scene.t_end / h,
        &key,
        COSTS.evals_per_step[2] * COSTS.rhs_work,
        &key,
    ))
}

fn compile(case: &Case, scene: &Scene) -> Result<Box<dyn Problem>, CaseError> {
    let plan = crate::model::rigid_body::plan::scene_plan(case, scene)?;
    Ok(Box::new(super::problem::RigidProblem::new(
        plan,
        case.reference,
    )))
}
