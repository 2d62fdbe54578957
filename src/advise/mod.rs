//! The recommendation (`mbdbench advise`; README.md, "Commands"): from a summary, per case and
//! target error, the cheapest variant (parameterization x integrator x formulation) that reaches
//! the target on every non-control scene of the case, its runner-up, and what to avoid and why.
//!
//! How it is computed (`rank.rs`), for a case with primary metric `m` and target `e`:
//! - per scene, a variant's cost at `e` is the work of its cheapest ladder point (fixed step
//!   or tolerance) that completed with `m <= e`; work is deterministic: RHS evaluations plus
//!   Newton iterations (`Stats::rhs_evals + Stats::newton_iters`);
//! - the variant's case cost is the sum over the case's scenes that are not controls
//!   (`control = true` in the case file: a result known by construction, such as a chart that
//!   is exact on it); a variant that is `n/a`, failed at every point reaching `e`, or never
//!   reaches `e` on one of them is out;
//! - the cheapest wins; the runner-up and the ratio of its cost to the winner's (`gap`) are
//!   given; every variant whose ranking cost is within `TIE_REL` (5 %) of the winner's is a
//!   tie with it (`tie`, in cost order; the winner is then only the first of equals, the
//!   earlier in the family's order on equal costs), and the advice says "tie" and names them;
//! - a second ranking by median wall time (the sum of the chosen runs' medians) is given when
//!   every chosen run of the work winner took more than 10 ms (`MIN_TIMED_S`); below, timer
//!   noise decides and the advice says so instead.
//!
//! Targets: the case's `advise_targets`, or 1e-3, 1e-6 and 1e-9 (`DEFAULT_TARGETS`), each
//! offered only where it is at least 100x every scene's reference accuracy claim (below, the
//! error measures the reference, not the method); `--target` overrides them.
//!
//! What to avoid (`avoid.rs`), from the data of the non-control scenes: typed failures (kind,
//! scene, how many ladder points), charts whose conditioning fell below 1e-3, and variants
//! whose energy drift at their finest completed ladder point exceeds the case's
//! `advise_max_energy_drift` (default 1e-3), and order fits that are not asymptotic (local
//! slopes spread by more than 1).
//!
//! The JSON (`--json`, schema 1; docs/schemas.md, "advise --json"): `{schema, by, cases: [{case,
//! metric, unit, scenes, controls, targets: [{target, winner, runner_up, gap, tie, by_time, note}],
//! skipped_targets: [{target, reason}], avoid: [{param, integrator, formulation, scene,
//! reason}], robustness: [{scene, param, integrator, formulation, stable, accurate,
//! limited_by}], references: [{scene, reference: {integrator, formulation, step, step_unit,
//! made_by}, agreement, text}]}]}` (`references` only where a scene's reference is itself
//! one of the variants, `reference.rs`; `stable`, `accurate`: `{dt}` or `{tol}` or null) where a pick is
//! `{param, integrator, formulation, settings: {scene: {dt} | {tol}}, cost, rhs_evals,
//! newton_iters, wall_s}` (`wall_s`: the sum of the chosen runs' median wall
//! times, null when a run was not timed). Absent winners are null.
//!
//! Where it fails: a summary of a filtered run advises on the scenes it holds (the advice
//! lists them); a case whose scenes have different primary metrics is not yet split per
//! metric (every catalogue case has one); static scenes (a load step that does not change
//! the elastic result) do not exist yet in the catalogue and get no rule of their own.
//!
//! With `stability.json` beside the summary (`Options::stability`), each case also gets the
//! robustness ranking (`robust.rs`): per scene, the largest stable and accurate step of each
//! variant the study searched.
//!
//! # Example
//!
//! ```
//! use mbdbench::advise::{self, Options};
//!
//! use mbdbench::summary::{Env, Summary};
//!
//! let cases = mbdbench::catalogue::embedded().unwrap();
//! let summary = Summary {
//!     schema: 1,
//!     git_commit: "-".into(),
//!     created_utc: "-".into(),
//!     env: Env::current(1, None),
//!     records: vec![],
//!     fits: vec![],
//!     selection: None,
//!     methods: None,
//!     families: None,
//! };
//! let a = advise::advise(&summary, &advise::specs(&cases, &|_, _| Default::default()), &Options::default());
//! assert!(a.cases.is_empty()); // nothing was run
//! assert!(advise::render(&a).starts_with("Recommendation"));
//! ```
mod avoid;
mod rank;
pub mod reference;
pub mod robust;
#[cfg(test)]
mod tests;
mod text;

use std::collections::BTreeMap;

use serde::Serialize;

use crate::case::Case;
use crate::summary::Summary;

pub use text::render;

/// Target errors when a case sets none.
pub const DEFAULT_TARGETS: [f64; 3] = [1e-3, 1e-6, 1e-9];

/// A target is offered only this many times above every scene's accuracy claim.
pub const CLAIM_MARGIN: f64 = 100.0;

/// Wall times are ranked only when every chosen run of the work winner took longer (s).
pub const MIN_TIMED_S: f64 = 0.01;

/// Picks whose ranking cost (work, or wall time with `--by time`) lies within this fraction
/// of the winner's are a tie with it: the advice names them all as tied, not the first as
/// the winner "x1.00" ahead (docs/schemas.md, "advise --json": `tie`).
pub const TIE_REL: f64 = 0.05;

/// Below this conditioning a chart is listed to avoid.
pub const MIN_CONDITIONING: f64 = 1e-3;

/// What the recommendation is ranked by.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum By {
    /// Deterministic work: RHS evaluations + Newton iterations.
    #[default]
    Work,
    /// The sum of the chosen runs' median wall times.
    Time,
}

/// Options of `advise`.
#[derive(Debug, Clone, Default)]
pub struct Options {
    /// Only these cases (empty: every case of the summary).
    pub cases: Vec<String>,
    /// Target errors replacing each case's (empty: the case's or `DEFAULT_TARGETS`).
    pub targets: Vec<f64>,
    pub by: By,
    /// The stability study beside the summary, when there is one: the robustness ranking.
    pub stability: Option<Summary>,
}

/// What the recommendation needs to know of a case besides the summary.
#[derive(Debug, Clone)]
pub struct CaseSpec {
    pub case: String,
    pub metric: String,
    pub unit: String,
    pub targets: Vec<f64>,
    pub max_energy_drift: f64,
    /// A target is offered only at this many times every scene's claim or above
    /// (`CLAIM_MARGIN`; a physical view's own, `figures::PhysicalView::claim_margin`).
    pub claim_margin: f64,
    /// What the claim is, for the reason of a target not offered (`accuracy claim`).
    pub claim_name: &'static str,
    pub scenes: Vec<SceneSpec>,
}

/// A scene of a `CaseSpec`.
#[derive(Debug, Clone)]
pub struct SceneSpec {
    pub name: String,
    pub control: bool,
    /// The reference's accuracy claim for the primary metric (None: no reference).
    pub claim: Option<f64>,
    /// The variant that made the reference, when the reference is one of the variants
    /// (`problem::ReferenceVariant`; `reference.rs`).
    pub reference_variant: Option<crate::problem::ReferenceVariant>,
}

/// What the recommendation needs of a scene's stored reference.
#[derive(Debug, Clone, Default)]
pub struct SceneReference {
    /// Its accuracy claim for the metric ranked (None: no reference could be attached).
    pub claim: Option<f64>,
    /// The variant that made it, if it is one (`Problem::reference_variant`).
    pub variant: Option<crate::problem::ReferenceVariant>,
}

/// Which claim of a reference the advice floors its targets on.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Claim {
    /// `Problem::accuracy_claim`: the floor of a step-convergence error.
    Accuracy,
    /// `Problem::physical_claim`: the reference's own error in a ranking of models.
    Physical,
}

/// What the stored reference of `case`'s `scene` under `root` tells the advice for `metric`:
/// the scene is compiled and its reference attached (a scene whose reference cannot be
/// attached has no claim: every target is offered there, and no variant is named).
pub fn stored_reference(
    root: &std::path::Path,
    case: &Case,
    scene: &str,
    metric: &str,
    claim: Claim,
) -> SceneReference {
    let attached = case.scene(scene).and_then(|s| {
        let mut p = (crate::catalogue::family_of(case).compile)(case, s).ok()?;
        p.attach_reference(root).ok()?;
        Some(p)
    });
    match attached {
        Some(p) => SceneReference {
            claim: match claim {
                Claim::Accuracy => p.accuracy_claim(metric),
                Claim::Physical => p.physical_claim(metric),
            },
            variant: p.reference_variant(),
        },
        None => SceneReference::default(),
    }
}

/// The specs of `cases`; `reference(case, scene)` gives what the advice needs of a scene's
/// reference for its primary metric.
pub fn specs(cases: &[Case], reference: &dyn Fn(&Case, &str) -> SceneReference) -> Vec<CaseSpec> {
    cases
        .iter()
        .map(|c| {
            let family = crate::catalogue::family_of(c);
            let unit = family
                .metrics
                .iter()
                .find(|m| m.name == c.primary_metric)
                .map_or("", |m| m.unit);
            CaseSpec {
                case: c.name.clone(),
                metric: c.primary_metric.clone(),
                unit: unit.to_string(),
                targets: c
                    .advise_targets
                    .clone()
                    .unwrap_or_else(|| DEFAULT_TARGETS.to_vec()),
                max_energy_drift: c.advise_max_energy_drift,
                claim_margin: CLAIM_MARGIN,
                claim_name: "accuracy claim",
                scenes: c
                    .scenes
                    .iter()
                    .map(|s| {
                        let r = reference(c, &s.name);
                        SceneSpec {
                            name: s.name.clone(),
                            control: s.control,
                            claim: r.claim,
                            reference_variant: r.variant,
                        }
                    })
                    .collect(),
            }
        })
        .collect()
}

/// The whole recommendation.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Advice {
    pub schema: u32,
    pub by: &'static str,
    pub cases: Vec<CaseAdvice>,
}

/// The recommendation of one case.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct CaseAdvice {
    pub case: String,
    pub metric: String,
    pub unit: String,
    /// The non-control scenes the advice covers (those of the summary).
    pub scenes: Vec<String>,
    /// The control scenes left out.
    pub controls: Vec<String>,
    pub targets: Vec<TargetAdvice>,
    pub skipped_targets: Vec<Skipped>,
    pub avoid: Vec<Avoid>,
    /// At what step: the stability study's largest stable and accurate steps per variant
    /// (`robust.rs`; empty without `stability.json`).
    pub robustness: Vec<robust::Robust>,
    /// The scenes whose reference is itself one of the variants, each with its sentence
    /// (`reference.rs`); absent from the JSON when empty.
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub references: Vec<reference::ReferenceNote>,
}

/// The cheapest variants at one target.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct TargetAdvice {
    pub target: f64,
    pub winner: Option<Pick>,
    pub runner_up: Option<Pick>,
    /// Runner-up's cost / winner's cost.
    pub gap: Option<f64>,
    /// The variants after the winner whose ranking cost is within [`TIE_REL`] of the
    /// winner's, in cost order (empty: the winner stands alone).
    pub tie: Vec<Pick>,
    /// The winner by median wall time, when the work winner's runs are long enough to time.
    pub by_time: Option<Pick>,
    /// Why something is absent (no variant reaches the target, runs too short to time).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub note: Option<String>,
}

/// A target not offered, and why.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Skipped {
    pub target: f64,
    pub reason: String,
}

/// One ladder value.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Setting {
    Dt(f64),
    Tol(f64),
}

/// A variant with the settings that reach a target on every scene, and what they cost.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Pick {
    pub param: String,
    pub integrator: String,
    pub formulation: String,
    pub settings: BTreeMap<String, Setting>,
    /// RHS evaluations + Newton iterations over the chosen runs.
    pub cost: u64,
    pub rhs_evals: u64,
    pub newton_iters: u64,
    /// The sum of the chosen runs' median wall times (None: a run was not timed).
    pub wall_s: Option<f64>,
}

impl Pick {
    /// `param/integrator/formulation`.
    pub fn name(&self) -> String {
        format!("{}/{}/{}", self.param, self.integrator, self.formulation)
    }
}

/// A variant (or a whole chart: integrator and formulation None) to avoid, and why.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Avoid {
    pub param: String,
    pub integrator: Option<String>,
    pub formulation: Option<String>,
    pub scene: String,
    pub reason: String,
}

/// The recommendation for every case of `specs` that `summary` holds runs of.
pub fn advise(summary: &Summary, specs: &[CaseSpec], opts: &Options) -> Advice {
    let cases = specs
        .iter()
        .filter(|c| opts.cases.is_empty() || opts.cases.contains(&c.case))
        .filter_map(|spec| {
            let records: Vec<_> = summary
                .records
                .iter()
                .filter(|r| r.key.case == spec.case)
                .collect();
            if records.is_empty() {
                return None;
            }
            let present = |s: &SceneSpec| records.iter().any(|r| r.key.scene == s.name);
            let scenes: Vec<&SceneSpec> = spec
                .scenes
                .iter()
                .filter(|s| !s.control && present(s))
                .collect();
            let controls = spec
                .scenes
                .iter()
                .filter(|s| s.control && present(s))
                .map(|s| s.name.clone())
                .collect();
            let wanted = if opts.targets.is_empty() {
                &spec.targets
            } else {
                &opts.targets
            };
            let (targets, skipped_targets) =
                rank::targets(spec, &scenes, wanted, &records, opts.by);
            Some(CaseAdvice {
                case: spec.case.clone(),
                metric: spec.metric.clone(),
                unit: spec.unit.clone(),
                scenes: scenes.iter().map(|s| s.name.clone()).collect(),
                controls,
                targets,
                skipped_targets,
                avoid: avoid::avoid(
                    spec,
                    &scenes,
                    &records,
                    &summary
                        .fits
                        .iter()
                        .filter(|f| f.key.case == spec.case)
                        .collect::<Vec<_>>(),
                ),
                robustness: opts
                    .stability
                    .as_ref()
                    .map(|st| robust::robustness(&spec.case, st))
                    .unwrap_or_default(),
                references: reference::notes(&scenes, &records, &spec.metric),
            })
        })
        .collect();
    Advice {
        schema: 1,
        by: match opts.by {
            By::Work => "work",
            By::Time => "time",
        },
        cases,
    }
}
