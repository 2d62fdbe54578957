//! Energy drift on the score grid: `energy_drift_max = max_k |E_k - E_0| / max(|E_0|,
//! energy_scale)` and `energy_drift_final` (the last score point). The scale keeps the measure
//! meaningful when `E_0` is near zero. For a conservative model it should be at truncation
//! level (secular for non-symplectic methods, bounded for symplectic ones) or at round-off for
//! energy-conserving schemes. Null when the run failed.
use super::Scores;
use crate::run::RunOutput;

/// The relative drift of each energy from the first, the one expression of the summary, the
/// references, the long-horizon study and the report: `|E_k - E_0| / max(|E_0|, energy_scale)`.
/// With a zero denominator (`E_0 = 0` and no scale, as a report of a case it does not know)
/// the absolute drift `|E_k - E_0|`. Empty for no energies.
///
/// # Example
///
/// ```
/// use mbdbench::metrics::energy_drift::relative;
///
/// let d: Vec<f64> = relative(&[-2.0, -2.5, -1.0], 4.0).collect();
/// assert_eq!(d, vec![0.0, 0.125, 0.25]); // the scale 4 J exceeds |E0| = 2 J
/// assert_eq!(relative(&[10.0, 11.0], 1.0).last(), Some(0.1));
/// ```
pub fn relative(energies: &[f64], energy_scale: f64) -> impl Iterator<Item = f64> + '_ {
    let e0 = energies.first().copied().unwrap_or(0.0);
    let d = e0.abs().max(energy_scale);
    let scale = if d > 0.0 { d } else { 1.0 };
    energies.iter().map(move |e| (e - e0).abs() / scale)
}

/// The largest relative drift (`relative`), 0 for no energies.
pub fn max_relative(energies: &[f64], energy_scale: f64) -> f64 {
    relative(energies, energy_scale).fold(0.0, f64::max)
}

/// Scores the drift given the score-grid energies.
pub fn score<O>(out: &RunOutput<O>, energies: &[f64], energy_scale: f64, s: &mut Scores) {
    if let Some(f) = &out.failure {
        let why = format!("run failed ({:?}) at t = {}", f.kind, f.t);
        s.null("energy_drift_max", why.clone());
        s.null("energy_drift_final", why);
        return;
    }
    if energies.is_empty() {
        s.null("energy_drift_max", "no samples");
        s.null("energy_drift_final", "no samples");
        return;
    }
    let mut m = 0.0_f64;
    let mut last = 0.0;
    let mut finite = true;
    for d in relative(energies, energy_scale) {
        finite &= d.is_finite();
        m = m.max(d);
        last = d;
    }
    if !finite {
        s.null("energy_drift_max", "non-finite energy");
        s.null("energy_drift_final", "non-finite energy");
        return;
    }
    s.set("energy_drift_max", m);
    s.set("energy_drift_final", last);
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::integrate::{Failure, FailureKind, Stats};
    use crate::model::rigid_body::Observation;
    use crate::run::{RunOutput, Sample};
    use nalgebra::{UnitQuaternion, Vector3};

    fn out(n: usize) -> RunOutput<Observation> {
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
