//! The raw (serde) shape of a case file: `[stability]`, the keys every case file and every
//! scene has ([`RawShared`], [`RawGrid`]), and the `case_schema!` macro with which a family
//! declares its own case file around them (cases/README.md, "Case-file keys"). Validation of the
//! values is in `mod.rs` (`Ctx`); this file holds only what the TOML must look like, with
//! `deny_unknown_fields` everywhere so that a misspelt key is an error naming it.
use serde::Deserialize;

use super::{RawGate, RawLadders};

/// `[stability]` as written.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawStability {
    pub(super) periods: Option<f64>,
    pub(super) rotation_error_max: Option<f64>,
    #[serde(default)]
    pub(super) quick: Vec<String>,
}

impl RawStability {
    /// `rotation_error_max` as written (the rigid body requires it, other families reject it).
    pub fn rotation_error_max(&self) -> Option<f64> {
        self.rotation_error_max
    }
}

/// The keys every case file has, as written (split off a family's raw case by
/// [`case_schema!`]).
pub struct RawShared {
    pub schema: i64,
    pub case: String,
    pub title: String,
    pub primary_metric: String,
    pub energy_scale: f64,
    /// As written; resolved against the family's kinds by `Ctx::assemble`.
    pub reference: String,
    pub max_steps: Option<f64>,
    pub max_rhs_evals: Option<f64>,
    pub max_adaptive_rhs_evals: Option<f64>,
    pub max_memory_mib: Option<f64>,
    pub max_work: Option<f64>,
    pub advise_targets: Option<Vec<f64>>,
    pub advise_max_energy_drift: Option<f64>,
    pub ladders: RawLadders,
    pub gates: Vec<RawGate>,
    pub stability: Option<RawStability>,
}

/// The keys every scene has, as written.
pub struct RawGrid {
    pub name: String,
    pub t_end: f64,
    pub sample_every: f64,
    pub score_every: f64,
    pub ladders: Option<RawLadders>,
    /// A control scene (`control = true`): a result known by construction, such as a chart
    /// that is exact on it; left out of the recommendation's "cheapest" (`advise`).
    pub control: bool,
}

/// Declares a family's raw (serde) case file: the struct of the whole file (the shared keys
/// of every case file (cases/README.md, "Shared keys") plus the family's own,
/// `deny_unknown_fields`), the struct of one `[[scene]]` likewise, plain structs of the family's
/// own keys, and `split`, which separates the shared keys ([`RawShared`], [`RawGrid`]) from the
/// family's.
///
/// ```ignore
/// mbdbench::case_schema! {
///     case RawCase / CaseOwn { body: RawBody, #[serde(default)] spring: Vec<RawSpring> }
///     scene RawScene / SceneOwn { euler_xyz: [f64; 3] }
/// }
/// ```
#[macro_export]
macro_rules! case_schema {
    (
        case $Case:ident / $CaseOwn:ident {
            $( $(#[$cfm:meta])* $cf:ident : $ct:ty ),* $(,)?
        }
        scene $Scene:ident / $SceneOwn:ident {
            $( $(#[$sfm:meta])* $sf:ident : $st:ty ),* $(,)?
        }
    ) => {
        /// The whole case file as written.
        #[derive(serde::Deserialize)]
        #[serde(deny_unknown_fields)]
        pub(crate) struct $Case {
            schema: i64,
            case: String,
            title: String,
            #[allow(dead_code)]
            model: String,
            primary_metric: String,
            energy_scale: f64,
            reference: String,
            max_steps: Option<f64>,
            max_rhs_evals: Option<f64>,
            max_adaptive_rhs_evals: Option<f64>,
            max_memory_mib: Option<f64>,
            max_work: Option<f64>,
            advise_targets: Option<Vec<f64>>,
            advise_max_energy_drift: Option<f64>,
            scene: Vec<$Scene>,
            ladders: $crate::case::RawLadders,
            #[serde(default)]
            gates: Vec<$crate::case::RawGate>,
            stability: Option<$crate::case::RawStability>,
            $( $(#[$cfm])* $cf: $ct, )*
        }

        /// One `[[scene]]` as written.
        #[derive(serde::Deserialize)]
        #[serde(deny_unknown_fields)]
        pub(crate) struct $Scene {
            name: String,
            t_end: f64,
            sample_every: f64,
            score_every: f64,
            ladders: Option<$crate::case::RawLadders>,
            #[serde(default)]
            control: bool,
            $( $(#[$sfm])* $sf: $st, )*
        }

        /// The family's own keys of the case file.
        pub(crate) struct $CaseOwn {
            $( pub $cf: $ct, )*
        }

        /// The family's own keys of a scene.
        pub(crate) struct $SceneOwn {
            $( pub $sf: $st, )*
        }

        impl $Case {
            /// The shared keys, the family's own, and each scene split likewise.
            fn split(
                self,
            ) -> (
                $crate::case::RawShared,
                $CaseOwn,
                Vec<($crate::case::RawGrid, $SceneOwn)>,
            ) {
                let scenes = self
                    .scene
                    .into_iter()
                    .map(|s| {
                        (
                            $crate::case::RawGrid {
                                name: s.name,
                                t_end: s.t_end,
                                sample_every: s.sample_every,
                                score_every: s.score_every,
                                ladders: s.ladders,
                                control: s.control,
                            },
                            $SceneOwn { $( $sf: s.$sf, )* },
                        )
                    })
                    .collect();
                (
                    $crate::case::RawShared {
                        schema: self.schema,
                        case: self.case,
                        title: self.title,
                        primary_metric: self.primary_metric,
                        energy_scale: self.energy_scale,
                        reference: self.reference,
                        max_steps: self.max_steps,
                        max_rhs_evals: self.max_rhs_evals,
                        max_adaptive_rhs_evals: self.max_adaptive_rhs_evals,
                        max_memory_mib: self.max_memory_mib,
                        max_work: self.max_work,
                        advise_targets: self.advise_targets,
                        advise_max_energy_drift: self.advise_max_energy_drift,
                        ladders: self.ladders,
                        gates: self.gates,
                        stability: self.stability,
                    },
                    $CaseOwn { $( $cf: self.$cf, )* },
                    scenes,
                )
            }
        }
    };
}
