//! Energy drift on the score grid: `energy_drift_max = max_k |E_k - E_0| / max(|E_0|,
//! energy_scale)` and `energy_drift_final` (the last score point). The scale keeps the measure
//! meaningful when `E_0` is near zero. For a conservative model it should be at truncation
//! level (secular for non-symplectic methods, bounded for symplectic ones) or at round-off for
//! energy-conserving schemes. Null when the run failed.
use super::Scores;
use crate::model::rigid_body::RigidBody;
use crate::run::RunOutput;

/// The energy at each score point of `out`.
pub fn energies(out: &RunOutput, body: &RigidBody) -> Vec<f64> {
    out.scored().map(|s| body.energy(&s.obs)).collect()
}

/// Scores the drift given the score-grid energies.
pub fn score<O>(out: &RunOutput<O>, energies: &[f64], energy_scale: f64, s: &mut Scores) {
    if let Some(f) = &out.failure {
        let why = format!("run failed ({:?}) at t = {}", f.kind, f.t);
        s.null("energy_drift_max", why.clone());
        s.null("energy_drift_final", why);
        return;
    }
    let Some(&e0) = energies.first() else {
        s.null("energy_drift_max", "no samples");
        s.null("energy_drift_final", "no samples");
        return;
    };
    let scale = e0.abs().max(energy_scale);
    let mut m = 0.0_f64;
    let mut finite = true;
    for e in energies {
        let d = (e - e0).abs() / scale;
        finite &= d.is_finite();
        m = m.max(d);
    }
    if !finite {
        s.null("energy_drift_max", "non-finite energy");
        s.null("energy_drift_final", "non-finite energy");
        return;
    }
    s.set("energy_drift_max", m);
    s.set(
        "energy_drift_final",
        (energies[energies.len() - 1] - e0).abs() / scale,
    );
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::integrate::{Failure, FailureKind, Stats};
    use crate::model::rigid_body::Observation;
    use crate::run::{RunOutput, Sample};
    use nalgebra::{UnitQuaternion, Vector3};

    fn out(n: usize) -> RunOutput {
        let o = Observation {
            q: UnitQuaternion::identity(),
            x: Vector3::zeros(),
            v: Vector3::zeros(),
            omega: Vector3::zeros(),
        };
        RunOutput {
            samples: (0..n)
                .map(|k| Sample {
                    t: k as f64,
                    obs: o,
                    conditioning: 1.0,
                    residual: None,
                })
                .collect(),
            score_stride: 1,
            failure: None,
            stats: Stats::default(),
            conditioning_min: 1.0,
        }
    }

    /// Drift is the max relative deviation from E0 with the scale floor, the final one is the
    /// last, and a failed run scores null with its reason.
    #[test]
    fn drift_values_and_failure() {
        let mut s = Scores::default();
        score(&out(3), &[10.0, 13.0, 9.0], 1.0, &mut s);
        assert_eq!(s.get("energy_drift_max"), Some(0.3));
        assert_eq!(s.get("energy_drift_final"), Some(0.1));
        let mut s = Scores::default();
        score(&out(3), &[0.0, 1.0, 0.5], 100.0, &mut s);
        assert_eq!(s.get("energy_drift_max"), Some(0.01));
        let mut o = out(3);
        o.failure = Some(Failure::new(FailureKind::NonFinite, 1.5, "x"));
        let mut s = Scores::default();
        score(&o, &[0.0, 1.0, 0.5], 1.0, &mut s);
        assert_eq!(s.values["energy_drift_max"], None);
        assert!(s.reasons["energy_drift_max"].contains("1.5"));
    }
}
