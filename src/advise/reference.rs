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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::summary::{Record, RunKey};

    fn record(integrator: &str, param: &str, dt: f64, err: f64) -> Record {
        let mut r = Record {
            key: RunKey {
                case: "c".into(),
                scene: "s".into(),
                param: param.into(),
                integrator: integrator.into(),
                formulation: "force_based".into(),
            },
            dt: Some(dt),
            tol: None,
            status: Status::Ok,
            failure: None,
            reason: None,
            metrics: Default::default(),
            metric_reasons: Default::default(),
            stats: Default::default(),
            wall_s: None,
            inputs_sha256: String::new(),
            settings_sha256: None,
            reference_sha256: None,
            series: None,
            series_reason: None,
        };
        r.metrics.insert("m".into(), Some(err));
        r
    }

    /// The agreement is the largest error of the reference's own variant at its own step over
    /// the charts; other steps and other integrators do not count, and without such a run the
    /// note says it was not run.
    #[test]
    fn agreement_is_the_own_variant_at_its_step() {
        let spec = SceneSpec {
            name: "s".into(),
            control: false,
            claim: None,
            reference_variant: Some(ReferenceVariant {
                integrator: "newmark".into(),
                formulation: "force_based".into(),
                step: 5e-4,
                step_unit: "s".into(),
                made_by: "OpenSees 3.7.1".into(),
            }),
        };
        let rs = [
            record("newmark", "so3", 5e-4, 2e-12),
            record("newmark", "rotvec", 5e-4, 3e-12),
            record("newmark", "so3", 1e-3, 1e-4),
            record("hht", "so3", 5e-4, 1e-5),
        ];
        let refs: Vec<&Record> = rs.iter().collect();
        let n = notes(&[&spec], &refs, "m");
        assert_eq!(n.len(), 1);
        assert_eq!(n[0].agreement, Some(3e-12));
        assert!(n[0].text.contains("reproduces it"), "{}", n[0].text);
        let n = notes(&[&spec], &refs[2..], "m");
        assert_eq!(n[0].agreement, None);
        assert!(n[0].text.contains("was not run"), "{}", n[0].text);
    }
}
