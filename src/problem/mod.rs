//! The seam between the suite and the model families (README.md, "Adding things": a model
//! family). A family (rigid bodies, later the flexible beam, the fiber column, mechanisms) is
//! described once, statically, by a [`Family`] listed in the catalogue's table
//! (`catalogue::FAMILIES`, a module above this one): its case-file `model`
//! key, the names and report order of the three record axes (`param`: how rotations are
//! represented; `formulation`: how the equations of motion are written; `integrator`: how
//! time or load is stepped), its metrics, its trajectory columns and its table of registered
//! variants with the reasons every other combination is `n/a`. One scene of a case compiles
//! into a [`Problem`], the object-safe trait through which the suite, the CLI and the gate
//! run it: `run` is called once per run and dispatches, inside the family, to the same
//! monomorphised hot loop as a direct call (no dynamic dispatch per step). What names the
//! scene and stamps its records (family, case, scene, hashes, primary metric) is one
//! [`SceneHeader`] (`header.rs`) that the problem stores and the trait's getters read.
//!
//! Everything outside a family's folder reads the family's names from here; the variant
//! matrix of [`matrix`] replaces hand-written loops over the three axes.
//!
//! # Example
//!
//! ```
//! use mbdbench::problem::{self, Stepping, Want};
//!
//! let cases = mbdbench::catalogue::embedded().unwrap();
//! let c = cases.iter().find(|c| c.name == "nine_spring").unwrap();
//! let family = mbdbench::catalogue::family_of(c);
//! assert_eq!(family.model, "rigid_body");
//! let mut p = (family.compile)(c, c.scene("two_angles").unwrap()).unwrap();
//! p.attach_reference(&mbdbench::cli::default_references()).unwrap();
//! let v = family.find("so3", "rk4", "body").unwrap();
//! assert!(p.na_reason(v).is_none());
//! let out = p.run(v, Stepping::Dt(1.0e-2), Want::Scored).unwrap();
//! assert!(out.failure.is_none());
//! let err = out.scores.get("rotation_error_max").unwrap();
//! assert!(err < 1e-5 && err > 1e-8, "RKMK4 at 1e-2 s: {err:e}");
//! ```
use std::path::Path;

use crate::case::{Case, CaseError, Scene};
use crate::integrate::{Failure, MethodInfo, Stats};
use crate::metrics::Scores;
use crate::summary::Series;

pub mod figures;
pub mod header;
pub mod matrix;
pub mod reference_variant;

use crate::run::Grid;
pub use crate::run::Stepping;
pub use header::SceneHeader;
pub use matrix::{Cell, Entry, matrix};
pub use reference_variant::ReferenceVariant;

/// One of the three record axes.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Axis {
    Param,
    Integrator,
    Formulation,
}

/// The names of the three record axes of a family, each in report order (colours and
/// markers follow it).
#[derive(Debug, Clone, Copy)]
pub struct Axes {
    pub params: &'static [&'static str],
    pub integrators: &'static [&'static str],
    pub formulations: &'static [&'static str],
}

/// One metric a family reports (docs/schemas.md, "summary.json": `metrics`).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Metric {
    pub name: &'static str,
    pub unit: &'static str,
    /// An error against the stored reference: order fits and baseline comparisons take the
    /// reference's accuracy claim for it (`Problem::accuracy_claim`) as their floor.
    pub reference_error: bool,
    /// Larger is better (a conditioning); for every other metric smaller is better (errors,
    /// drifts). The report's heat map colours by it.
    pub higher_is_better: bool,
}

impl Metric {
    /// A metric for which smaller is better (an error or a drift; everything but a
    /// conditioning), an error against the reference when `reference_error`.
    pub const fn smaller_better(
        name: &'static str,
        unit: &'static str,
        reference_error: bool,
    ) -> Metric {
        Metric {
            name,
            unit,
            reference_error,
            higher_is_better: false,
        }
    }
}

/// One named column of a family's trajectories and references: `width` numbers per sample.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Column {
    pub name: &'static str,
    pub width: usize,
    pub unit: &'static str,
}

/// One registered variant of a family: its names on the three axes, its method facts and its
/// run. `index` is its place in the family's table (unique within the family; a key for
/// caches), `runner` the family's own run function of the variant, which only the family
/// reads ([`Runner::get`]): a variant registered from outside the crate carries its run the
/// same way, so the family runs it without a table of its own.
#[derive(Debug, Clone)]
pub struct Variant {
    pub param: &'static str,
    pub integrator: &'static str,
    pub formulation: &'static str,
    pub info: MethodInfo,
    pub index: usize,
    pub runner: Runner,
}

/// Two variants are the same when their names, facts and place agree (the run is what they
/// name).
impl PartialEq for Variant {
    fn eq(&self, o: &Variant) -> bool {
        (
            self.param,
            self.integrator,
            self.formulation,
            self.info,
            self.index,
        ) == (o.param, o.integrator, o.formulation, o.info, o.index)
    }
}

/// A family's run function of one variant, its type known only to the family: one downcast
/// per run, never per step.
///
/// # Example
///
/// ```
/// use mbdbench::problem::Runner;
///
/// type RunFn = fn(f64) -> f64;
/// let r = Runner::new((|h: f64| 2.0 * h) as RunFn);
/// assert_eq!(r.get::<RunFn>().map(|f| f(1.5)), Some(3.0));
/// // Another family's type is not this one's.
/// assert!(r.get::<fn(f64) -> u32>().is_none());
/// ```
#[derive(Clone)]
pub struct Runner(std::sync::Arc<dyn std::any::Any + Send + Sync>);

impl Runner {
    /// Wraps a family's run function (any `'static` value the family reads back by type).
    pub fn new<R: std::any::Any + Send + Sync>(run: R) -> Runner {
        Runner(std::sync::Arc::new(run))
    }
    /// The run function, if it is of the family's type `R`.
    pub fn get<R: std::any::Any>(&self) -> Option<&R> {
        self.0.downcast_ref::<R>()
    }
}

impl std::fmt::Debug for Runner {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str("Runner")
    }
}

impl Variant {
    /// The stepping of ladder value `value` (a tolerance for an adaptive method, else a step).
    pub fn stepping(&self, value: f64) -> Stepping {
        if self.info.adaptive {
            Stepping::Tol(value)
        } else {
            Stepping::Dt(value)
        }
    }

    /// The family's run function of this variant, or an error naming the variant when it
    /// carries another family's (a variant handed to the wrong family's problem).
    pub fn run_fn<R: std::any::Any>(&self) -> Result<&R, String> {
        self.runner.get::<R>().ok_or_else(|| {
            format!(
                "{}/{}/{} carries no run of this family",
                self.param, self.integrator, self.formulation
            )
        })
    }
}

/// A family's variant table: each row `(param, integrator, formulation, info, run)` becomes
/// its `Variant`, numbered in row order (`index` is its place in the table), carrying its run
/// function.
pub fn variant_table<R: Clone + std::any::Any + Send + Sync>(
    rows: impl IntoIterator<Item = (&'static str, &'static str, &'static str, MethodInfo, R)>,
) -> Vec<Variant> {
    rows.into_iter()
        .enumerate()
        .map(
            |(index, (param, integrator, formulation, info, run))| Variant {
                param,
                integrator,
                formulation,
                info,
                index,
                runner: Runner::new(run),
            },
        )
        .collect()
}

/// [`variant_table`] of a family whose only parameterization is `none`: rows
/// `(integrator, formulation, info, run)`.
pub fn none_param_table<R: Clone + std::any::Any + Send + Sync>(
    rows: impl IntoIterator<Item = (&'static str, &'static str, MethodInfo, R)>,
) -> Vec<Variant> {
    variant_table(
        rows.into_iter()
            .map(|(i, f, info, run)| ("none", i, f, info, run)),
    )
}

/// What a family makes of a method registered from outside the crate
/// (`catalogue::Catalogue::with_method`, `with_structural_method`): its variants on each of the
/// family's systems of the method's kind, numbered from 0 in the family's order, built as the
/// family builds its own table from the built-ins. None by default: a family without systems of
/// that kind. Each family implements it on `family::Systems` (`model::families!` calls it).
pub trait Instantiate {
    /// A first-order method on the family's first-order systems.
    fn ode<M: crate::methods::OdeMethod + Clone>(
        name: &'static str,
        at: crate::methods::Where,
        m: M,
    ) -> Vec<Variant> {
        let _ = (name, at, m);
        vec![]
    }
    /// A structural method on the family's second-order systems.
    fn second_order<M: crate::methods::second_order::SecondOrderMethod + Clone>(
        name: &'static str,
        m: M,
    ) -> Vec<Variant> {
        let _ = (name, m);
        vec![]
    }
}

/// Compiles one scene of a validated case into a runnable problem.
pub type Compile = fn(&Case, &Scene) -> Result<Box<dyn Problem>, CaseError>;

/// Where a family's variants come from: its own table (built once, on first use), or that
/// table extended by a catalogue with methods registered from outside
/// (`catalogue::Catalogue::with_method`).
#[derive(Clone, Copy)]
pub enum Variants {
    Table(fn() -> &'static [Variant]),
    Extended(&'static [Variant]),
}

/// A model family, described statically.
#[derive(Clone)]
pub struct Family {
    /// The case file's `model` key.
    pub model: &'static str,
    pub axes: Axes,
    /// Every metric the family can report; `primary_metric` is one of them.
    pub metrics: &'static [Metric],
    /// The trajectory and reference columns after `t`.
    pub columns: &'static [Column],
    /// The registered variants ([`Family::variants`]).
    pub variants: Variants,
    /// Why a combination of axis names absent from the table is `n/a`.
    pub static_na_reason: fn(&str, &str, &str) -> String,
    /// Parses and validates a whole case file of this family (`catalogue::load_str` dispatches
    /// on its `model` key): `(file label, text)`.
    pub load: fn(&str, &str) -> Result<Case, CaseError>,
    /// The family's physics of a scene in the physics hash (`case::hash`): every key that
    /// changes the physics, plus the numerical settings its stored reference is made with;
    /// never one of `case::hash::RESERVED_INPUT_KEYS` (refused when a case is loaded).
    pub inputs: fn(&Case, &Scene) -> serde_json::Map<String, serde_json::Value>,
    /// The case-file keys (dotted paths without array indices, a scene's keys under
    /// `scene.`, a table's path covering its keys) that change a run's result but not the
    /// stored reference: the numerical settings of the family's formulations and solvers
    /// that the reference does not use. They are in every record's `settings_sha256` and
    /// not in `inputs_sha256`; every other key of the family's case files (less the
    /// presentation keys, `case::hash::PRESENTATION_KEYS`, and the shared settings,
    /// `case::hash::SHARED_SETTINGS`) is physics and must move `inputs_sha256`.
    /// `case/hash_tests.rs` holds every family to this for every key of its case files.
    pub settings: &'static [&'static str],
    /// What one run of a scene needs (memory, steps, work), estimated from the loaded case's
    /// numbers before anything that grows with them exists: `catalogue::load_str` checks it
    /// against the case's budgets for every scene and refuses the case above one, naming
    /// the key (cases/README.md, "Budgets"). Required, so no family skips it; for it to come before
    /// any large allocation, a family's `load` keeps only what the file says (a count, not
    /// what it counts) and `compile` and the runs build the rest.
    pub estimate: fn(&Case, &Scene) -> crate::case::Estimate,
    /// Compiles one scene of a validated case.
    pub compile: Compile,
    /// The family's figures in the report.
    pub figures: &'static figures::Figures,
    /// The integrators the quick tier of the seam's step search covers
    /// (`study::seam_search`; the full tier searches every fixed-step integrator). A
    /// family with a study of its own (the rigid body) leaves it empty.
    pub stability_quick: &'static [&'static str],
    /// The family's own stability study (the rigid body's), run on its cases instead of the
    /// seam's step search; None: the seam's search (`study::seam_search`).
    pub study: Option<crate::stability::Study>,
    /// The reference kinds its problems can attach (`reference` in a case file); a case
    /// naming another is refused at load, by that key.
    pub references: &'static [crate::case::ReferenceKind],
}

impl std::fmt::Debug for Family {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "Family({})", self.model)
    }
}

impl Family {
    /// The registered variants, in table order.
    pub fn variants(&self) -> &'static [Variant] {
        match self.variants {
            Variants::Table(table) => table(),
            Variants::Extended(all) => all,
        }
    }

    /// A registered variant by its three names.
    pub fn find(
        &self,
        param: &str,
        integrator: &str,
        formulation: &str,
    ) -> Option<&'static Variant> {
        self.variants().iter().find(|v| {
            v.param == param && v.integrator == integrator && v.formulation == formulation
        })
    }

    /// The primary metric of a case whose file and fits are unknown: the family's first
    /// error against the reference (else its first metric).
    pub fn default_primary(&self) -> &'static str {
        self.metrics
            .iter()
            .find(|m| m.reference_error)
            .or(self.metrics.first())
            .map_or("", |m| m.name)
    }

    /// Whether `name` is a metric of this family.
    pub fn has_metric(&self, name: &str) -> bool {
        self.metrics.iter().any(|m| m.name == name)
    }
}

/// The case loader's view of a family (`case::CaseFamily`): a loaded case keeps its family
/// through it.
impl crate::case::CaseFamily for Family {
    fn model(&self) -> &'static str {
        self.model
    }
    fn metric_names(&self) -> Vec<&'static str> {
        self.metrics.iter().map(|m| m.name).collect()
    }
    fn formulations(&self) -> &'static [&'static str] {
        self.axes.formulations
    }
    fn references(&self) -> &'static [crate::case::ReferenceKind] {
        self.references
    }
    fn inputs(&self, case: &Case, scene: &Scene) -> serde_json::Map<String, serde_json::Value> {
        (self.inputs)(case, scene)
    }
    fn estimate(&self, case: &Case, scene: &Scene) -> crate::case::Estimate {
        (self.estimate)(case, scene)
    }
}

/// What a run keeps.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Want {
    /// Nothing but the work: the timing pass observes only the final state.
    Timing,
    /// The scores against the attached reference and the series at the score times.
    Scored,
    /// The scores, the series and every sample as named columns (`mbdbench trajectory`).
    Trajectory,
}

impl Want {
    /// When a run that keeps this observes its state: only at the ends for the timing pass,
    /// on the scene's grid otherwise.
    pub fn observe(self) -> crate::run::Observe {
        match self {
            Want::Timing => crate::run::Observe::Final,
            Want::Scored | Want::Trajectory => crate::run::Observe::Grid,
        }
    }
}

/// Samples as named columns (`t` first), each a flat list of `width` numbers per sample.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Columns {
    pub t: Vec<f64>,
    pub columns: Vec<(&'static str, usize, Vec<f64>)>,
}

/// What one run returns.
#[derive(Debug, Clone, Default)]
pub struct Outcome {
    pub stats: Stats,
    pub failure: Option<Failure>,
    /// Empty for `Want::Timing`.
    pub scores: Scores,
    /// None for `Want::Timing`.
    pub series: Option<Series>,
    /// Some for `Want::Trajectory`.
    pub columns: Option<Columns>,
}

impl Outcome {
    /// The work and the failure of a run, nothing scored yet (all that `Want::Timing` keeps).
    pub fn of_run<O>(out: &crate::run::RunOutput<O>) -> Self {
        Outcome {
            stats: out.stats,
            failure: out.failure.clone(),
            ..Outcome::default()
        }
    }
}

/// The `Problem` methods of a family whose scene keeps its `header`, a `setup` holding the
/// `grid`, its `ladders` and `quick` ladders, and `reference: Option<(R, sha256)>` attached by
/// `SceneHeader::load_reference`, and that rules out no registered variant on any scene
/// (`na_reason` is `None`): `header` to `reference_sha256`, written once for the families
/// built so (flexible_beam among them). Invoked inside their `impl Problem`.
macro_rules! scene_problem_methods {
    () => {
        fn header(&self) -> &$crate::problem::SceneHeader {
            &self.header
        }
        fn header_mut(&mut self) -> &mut $crate::problem::SceneHeader {
            &mut self.header
        }
        fn grid(&self) -> &$crate::run::Grid {
            &self.setup.grid
        }
        // The attached reference's times are the old grid's: dropped.
        fn set_t_end(&mut self, t_end: f64) {
            self.setup.grid.t_end = t_end;
            self.reference = None;
        }
        fn ladder(&self, quick: bool, info: &$crate::integrate::MethodInfo) -> &[f64] {
            if quick { &self.quick } else { &self.ladders }.for_method(info)
        }
        fn na_reason(&self, _v: &$crate::problem::Variant) -> Option<String> {
            None
        }
        fn attach_reference(&mut self, root: &std::path::Path) -> Result<(), String> {
            self.reference = Some(self.header.load_reference(root, &self.setup.grid)?);
            Ok(())
        }
        fn reference_sha256(&self) -> Option<&str> {
            self.reference.as_ref().map(|(_, sha)| sha.as_str())
        }
    };
}
pub(crate) use scene_problem_methods;

/// One compiled scene of a case, ready to run any of its family's variants.
///
/// A family stores the scene's [`SceneHeader`] and gives it out through `header`, and gives
/// out the grid its runs step on through `grid`; the getters of the header's fields (`family`
/// to `primary_metric`) and of the grid's (`t_end`, `score_every`, `sample_every`) are
/// provided and read them. `set_t_end` is the family's: a new horizon also invalidates what
/// the family attached (its reference, and any other copy of the grid it keeps).
pub trait Problem: Send + Sync {
    /// The scene's header: its family, names, hashes and primary metric.
    fn header(&self) -> &SceneHeader;
    /// The header to change: a catalogue binds a compiled problem to its own copy of the
    /// family (`catalogue::Catalogue::problems`), whose variants include the methods it
    /// registered.
    fn header_mut(&mut self) -> &mut SceneHeader;
    /// The time grid the family's runs step on (its run setup's: one copy).
    fn grid(&self) -> &Grid;
    fn family(&self) -> &'static Family {
        self.header().family
    }
    fn case(&self) -> &str {
        &self.header().case
    }
    fn scene(&self) -> &str {
        &self.header().scene
    }
    /// The SHA-256 of the scene's physics and its reference's numerical settings
    /// (cases/README.md, "Physics hash").
    fn inputs_sha256(&self) -> &str {
        &self.header().inputs_sha256
    }
    /// The SHA-256 of every other case-file key that can change a result (`case::hash`):
    /// the scene's `Scene::settings_sha256`, stamped on every record.
    fn settings_sha256(&self) -> &str {
        &self.header().settings_sha256
    }
    /// The case's primary error metric.
    fn primary_metric(&self) -> &str {
        &self.header().primary_metric
    }
    /// The horizon (s, or the load parameter's end for a static scene).
    fn t_end(&self) -> f64 {
        self.grid().t_end
    }
    /// Replaces the horizon (`--t-end`); errors against references are then absent.
    fn set_t_end(&mut self, t_end: f64);
    /// The score grid spacing (a `--t-end` must be a multiple of it).
    fn score_every(&self) -> f64 {
        self.grid().score_every
    }
    /// The sample spacing (at most `case::MAX_SAMPLES` samples per run).
    fn sample_every(&self) -> f64 {
        self.grid().sample_every
    }
    /// The ladder (steps, or tolerances for an adaptive method) of a method in a tier.
    fn ladder(&self, quick: bool, info: &MethodInfo) -> &[f64];
    /// Whether one of the case's gates names the ladder point `value` of `v` on this scene
    /// (`case::GateWhere::names_point`): such a point always runs.
    fn gated(&self, v: &Variant, value: f64) -> bool {
        let h = self.header();
        h.gated.iter().any(|f| {
            f.names_point(
                &h.scene,
                [v.param, v.integrator, v.formulation],
                v.info.adaptive,
                value,
            )
        })
    }
    /// Why a registered variant does not apply to this scene, if it does not.
    fn na_reason(&self, v: &Variant) -> Option<String>;
    /// Loads the stored reference of the scene from `root` and checks it (staleness, form).
    fn attach_reference(&mut self, root: &Path) -> Result<(), String>;
    /// The SHA-256 of the attached reference file.
    fn reference_sha256(&self) -> Option<&str>;
    /// The attached reference's accuracy claim for `metric` (the floor of order fits).
    fn accuracy_claim(&self, metric: &str) -> Option<f64>;
    /// The claim for `metric` as it applies to the runs of one formulation (a family whose
    /// reference holds one self-convergence track per formulation); the scene's claim by
    /// default.
    fn accuracy_claim_for(&self, metric: &str, formulation: &str) -> Option<f64> {
        let _ = formulation;
        self.accuracy_claim(metric)
    }
    /// The attached reference's own error for `metric` where it serves a ranking of models
    /// (`figures::PhysicalView`): what separates it from the exact physics of its model, not
    /// its distance to another model. The accuracy claim by default; a family whose claim
    /// includes a cross-check against another formulation (which measures that
    /// formulation's model error, the very thing the ranking ranks) gives the rest.
    fn physical_claim(&self, metric: &str) -> Option<f64> {
        self.accuracy_claim(metric)
    }
    /// The variant and step that made the attached reference, when the reference is itself
    /// one of the variants (`reference_variant.rs`); None for a converged or exact reference.
    fn reference_variant(&self) -> Option<ReferenceVariant> {
        None
    }
    /// The period (s) of the scene's first (slowest) elastic mode: the time scale of the
    /// seam's step search (`study::seam_search`), whose horizon is a number of these
    /// periods. None for a family with a study of its own (the rigid body's linearised modes,
    /// `model::rigid_body::stability::search`) or a scene without such a mode.
    fn first_period(&self) -> Option<f64> {
        None
    }
    /// For a static scene whose `t` is a load parameter from 0 to `t_end` (not time): makes
    /// the whole path one sample and score interval, so that every load step dividing `t_end`
    /// runs (errors against references are then absent), and returns true. The seam's step
    /// search then finds the scene's largest converging load step, up to the whole path in
    /// one step (`study::seam_search`). Scenes stepped in time return false, unchanged.
    fn as_load_path(&mut self) -> bool {
        false
    }
    /// One run. `Err` when the run cannot start (e.g. its step count is over the budget).
    fn run(&self, v: &Variant, stepping: Stepping, want: Want) -> Result<Outcome, String>;
    /// Computes the scene's reference (its primary trajectory, the cross-check by a run that
    /// differs in integrator, parameterization and formulation, the accuracy claim) and
    /// writes it under `root` (cases/README.md, "References and how they are checked"); returns a
    /// line saying how it was made and what the cross-check found.
    fn make_reference(&self, root: &Path) -> Result<String, String>;
    /// `reference --check`: recomputes the reference and compares it with the one stored
    /// under `root`; whether it lies within the stored accuracy claim, and a line with the
    /// differences.
    fn check_reference(&self, root: &Path) -> Result<(bool, String), String>;
}
