//! Scoring one run: the metrics of `metrics/` applied to a run's output, and the series file
//! (energy, constraint residual, conditioning and the primary error at the score times).
use crate::model::rigid_body::Observation;
use nalgebra::{Quaternion, UnitQuaternion, Vector3};

use crate::math::so3;
use crate::metrics::{self, Scores};
use crate::model::rigid_body::RigidBody;
use super::reference::Reference;
use crate::run::RunOutput;
use crate::summary::Series;

/// What scoring needs of a scene besides the run.
pub struct ScoreContext<'a> {
    pub body: &'a RigidBody,
    pub energy_scale: f64,
    pub primary_metric: &'a str,
    /// None when no reference applies (e.g. a `--t-end` override): errors are then absent.
    pub reference: Option<&'a Reference>,
}

/// Scores a run and builds its series.
pub fn score(out: &RunOutput<Observation>, cx: &ScoreContext) -> (Scores, Series) {
    let mut s = Scores::default();
    let translates = cx.body.translates();
    if let Some(r) = cx.reference {
        super::trajectory_error::score(out, r, translates, &mut s);
    }
    let energies: Vec<f64> = out.scored().map(|s| cx.body.energy(&s.obs)).collect();
    metrics::energy_drift::score(out, &energies, cx.energy_scale, &mut s);
    super::momentum_drift::score(out, cx.body, &mut s);
    metrics::chart::score(out, &mut s);
    let scored: Vec<_> = out.scored().collect();
    let primary_error = cx.reference.map(|r| {
        scored
            .iter()
            .zip(0..r.t.len())
            .map(|(smp, k)| primary_error_at(cx.primary_metric, smp, r, k))
            .collect()
    });
    let series = Series {
        t: scored.iter().map(|s| s.t).collect(),
        energy: energies,
        constraint: scored.iter().map(|s| s.residual).collect(),
        conditioning: scored.iter().map(|s| s.conditioning).collect(),
        primary_error,
        primary_metric: cx.primary_metric.to_string(),
        tracks: Default::default(),
    };
    (s, series)
}

fn primary_error_at(metric: &str, smp: &crate::run::Sample<Observation>, r: &Reference, k: usize) -> f64 {
    match metric {
        "position_error_max" => (smp.obs.x - Vector3::from(r.position[k])).norm(),
        "velocity_error_max" => (smp.obs.v - Vector3::from(r.velocity[k])).norm(),
        "omega_error_max" => (smp.obs.omega - Vector3::from(r.omega_body[k])).norm(),
        _ => {
            let q = r.quaternion[k];
            let qr = UnitQuaternion::new_unchecked(Quaternion::new(q[0], q[1], q[2], q[3]));
            so3::geodesic_quat(&smp.obs.q, &qr)
        }
    }
}
