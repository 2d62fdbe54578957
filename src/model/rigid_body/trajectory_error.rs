//! Accuracy against the stored reference, on the score grid: `position_error_max` (m, max
//! Euclidean distance), `rotation_error_max` (rad, max geodesic angle between computed and
//! reference rotation), `velocity_error_max` (m/s, world velocity of the reference point),
//! `omega_error_max` (rad/s, body angular velocity). Position and velocity errors are absent
//! when the body does not translate; all four are absent when no reference applies (e.g. a
//! `--t-end` override), and null when the run failed before `t_end`.
//!
//! A metric is only as good as the reference: values below about 100x the reference's
//! accuracy claim say nothing about the method (the order fits exclude them).
use crate::model::rigid_body::Observation;
use nalgebra::{Quaternion, UnitQuaternion, Vector3};

use crate::metrics::Scores;
use crate::math::so3;
use crate::model::rigid_body::reference::Reference;
use crate::run::RunOutput;

/// Scores a run against a reference sampled on the same score grid.
pub fn score(out: &RunOutput<Observation>, reference: &Reference, translates: bool, s: &mut Scores) {
    let names: &[&str] = if translates {
        &[
            "position_error_max",
            "rotation_error_max",
            "velocity_error_max",
            "omega_error_max",
        ]
    } else {
        &["rotation_error_max", "omega_error_max"]
    };
    if let Some(f) = &out.failure {
        for n in names {
            s.null(n, format!("run failed ({:?}) at t = {}", f.kind, f.t));
        }
        return;
    }
    let scored: Vec<_> = out.scored().collect();
    if scored.len() != reference.t.len() {
        for n in names {
            s.null(
                n,
                format!(
                    "run has {} score points, reference {}",
                    scored.len(),
                    reference.t.len()
                ),
            );
        }
        return;
    }
    let (mut ep, mut er, mut ev, mut ew) = (0.0_f64, 0.0_f64, 0.0_f64, 0.0_f64);
    for (k, smp) in scored.iter().enumerate() {
        if (smp.t - reference.t[k]).abs() > 1e-9 * reference.t[k].abs().max(1.0) {
            for n in names {
                s.null(
                    n,
                    format!(
                        "score time {} differs from reference {}",
                        smp.t, reference.t[k]
                    ),
                );
            }
            return;
        }
        let q = reference.quaternion[k];
        let qr = UnitQuaternion::new_unchecked(Quaternion::new(q[0], q[1], q[2], q[3]));
        er = er.max(so3::geodesic_quat(&smp.obs.q, &qr));
        ew = ew.max((smp.obs.omega - Vector3::from(reference.omega_body[k])).norm());
        ep = ep.max((smp.obs.x - Vector3::from(reference.position[k])).norm());
        ev = ev.max((smp.obs.v - Vector3::from(reference.velocity[k])).norm());
    }
    // NaN-safe: max() ignores NaN, so a non-finite state would read as 0; runs with a
    // non-finite state have already failed, but guard anyway.
    let all_finite = scored.iter().all(|x| {
        x.obs
            .q
            .coords
            .iter()
            .chain(x.obs.omega.iter())
            .all(|v| v.is_finite())
    });
    if !all_finite {
        for n in names {
            s.null(n, "non-finite sample");
        }
        return;
    }
    if translates {
        s.set("position_error_max", ep);
        s.set("velocity_error_max", ev);
    }
    s.set("rotation_error_max", er);
    s.set("omega_error_max", ew);
}
