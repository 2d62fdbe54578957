//! `momentum_drift_max`: max over the score grid and over the angular-momentum components the
//! model conserves (`RigidBody::conserved_momenta`: the world vector for a torque-free body; the
//! vertical component about the pivot and the spin for the heavy top) of `|L - L0| / |L0|`.
//! Absent where nothing is conserved (springs), null when the run failed.
use crate::model::rigid_body::Observation;
use crate::metrics::Scores;
use crate::model::rigid_body::RigidBody;
use crate::run::RunOutput;

/// Scores the momentum drift; does nothing when the body conserves no momentum.
pub fn score(out: &RunOutput<Observation>, body: &RigidBody, s: &mut Scores) {
    let Some(first) = out.samples.first() else {
        return;
    };
    let (l0, n, norm0) = body.conserved_momenta(&first.obs);
    if n == 0 {
        return;
    }
    if let Some(f) = &out.failure {
        s.null(
            "momentum_drift_max",
            format!("run failed ({:?}) at t = {}", f.kind, f.t),
        );
        return;
    }
    if norm0 == 0.0 {
        s.null("momentum_drift_max", "zero initial angular momentum");
        return;
    }
    let mut m = 0.0_f64;
    for smp in out.scored() {
        let (l, _, _) = body.conserved_momenta(&smp.obs);
        for i in 0..n {
            let d = (l[i] - l0[i]).abs() / norm0;
            if !d.is_finite() {
                s.null("momentum_drift_max", "non-finite momentum");
                return;
            }
            m = m.max(d);
        }
    }
    s.set("momentum_drift_max", m);
}
