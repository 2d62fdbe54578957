//! The notes of the scenes whose reference is itself one of the variants
//! (`problem::ReferenceVariant`): which variant and step made it, how closely our own run of
//! that variant at that step reproduces it (the agreement of two codes running one scheme, the
//! largest primary error over the charts that ran it), and the sentence every rendering of
//! the advice (text, `--json`, the report's blocks, `summary.md`) puts next to the errors
//! measured against it: the other variants' "errors" are distances to that scheme, which
//! carry its own discretisation error, not distances to the exact solution.
//!
//! Where it fails: a selection that did not run the reference's own step (the quick tier of
//! the pulse runs 1e-3 s only) gives no agreement, and the note says so.
use serde::Serialize;

use super::SceneSpec;
use crate::problem::ReferenceVariant;
use crate::summary::{Record, Status};

/// A scene whose errors are distances to one of the variants.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ReferenceNote {
    pub scene: String,
    pub reference: ReferenceVariant,
    /// The largest primary error of our runs of the reference's own variant at its own step
    /// over the charts that completed it (None: not run, or not completed, in this summary).
    pub agreement: Option<f64>,
    /// The sentence the renderings show.
    pub text: String,
}

/// The notes of `scenes` (those whose spec names a reference variant), from `records` of the
/// case, on the primary `metric`.
pub fn notes(scenes: &[&SceneSpec], records: &[&Record], metric: &str) -> Vec<ReferenceNote> {
    scenes
        .iter()
        .filter_map(|s| {
            let reference = s.reference_variant.clone()?;
            let agreement = records
                .iter()
                .filter(|r| r.key.scene == s.name && r.status == Status::Ok)
                .filter(|r| reference.is_variant(&r.key.integrator, &r.key.formulation))
                .filter(|r| r.dt.is_some_and(|dt| reference.is_step(dt)))
                .filter_map(|r| r.metrics.get(metric).copied().flatten())
                .reduce(f64::max);
            let text = sentence(&s.name, &reference, agreement, metric);
            Some(ReferenceNote {
                scene: s.name.clone(),
                reference,
                agreement,
                text,
            })
        })
        .collect()
}

fn sentence(scene: &str, r: &ReferenceVariant, agreement: Option<f64>, metric: &str) -> String {
    let own = format!("{}/{}", r.integrator, r.formulation);
    let agrees = match agreement {
        Some(e) => format!(
            "our {own} at that step reproduces it to {metric} = {e:.2e} (two codes, one scheme)"
        ),
        None => format!("our {own} at that step was not run in this summary"),
    };
    format!(
        "{scene}: the reference is {}, itself one of the variants; {agrees}. Every other \
         error on {scene} is a distance to that scheme (its own step error included), not to \
         the exact solution.",
        r.label()
    )
}
