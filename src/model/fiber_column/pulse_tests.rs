//! Tests of the column's dynamic step (Newmark, average acceleration, through the `Dynamic`
//! driver) against the stored OpenSees run of the RC column under the ground-acceleration
//! pulse; the scene's pieces (the column after the axial prelude, the pulse, the damping)
//! shared with `dynamic_tests.rs`.
use nalgebra::DVector;

use crate::rotation::So3;
use super::column::{Algorithm, Column};
use super::dynamic::{Dynamic, Scheme};
use super::rc_tests::{H, P, rc_column, reference, reference_column};

/// The damping coefficient `a0 = 2 zeta omega_1` of the OpenSees script (zeta = 0.02,
/// omega_1 = 14.820708227335706 rad/s after the axial prelude).
pub(super) const A0: f64 = 0.5928283290934282;
pub(super) const G0: f64 = 9.80665;
/// OpenSees' step (s) and number of steps.
pub(super) const DT: f64 = 5e-4;
pub(super) const STEPS: usize = 10_000;

/// The ground acceleration (m/s^2): half a g at 2 Hz for the first second.
pub(super) fn ground(t: f64) -> f64 {
    if t <= 1.0 {
        0.5 * G0 * (std::f64::consts::TAU * t / 0.5).sin()
    } else {
        0.0
    }
}

/// The c01 column after the axial prelude (P in 10 load steps) and its static load.
pub(super) fn prelude() -> (Column<So3>, DVector<f64>) {
    let mut col: Column<So3> = rc_column(false, 1, true);
    let mut f = DVector::zeros(col.dim());
    for k in 1..=10 {
        f[col.top_dof(2)] = -P * k as f64 / 10.0;
        col.step(&f, None, 1e-20, 50, Algorithm::Newton).unwrap();
    }
    (col, f)
}

/// The scene's driver with `scheme` at step `h`.
pub(super) fn driver(scheme: Scheme, h: f64) -> Dynamic<So3> {
    let (col, f) = prelude();
    Dynamic::new(col, f, P / G0, A0, scheme, h).unwrap()
}

// Newmark's average-acceleration rule on the c01 column with the top mass P/g0 and 2 %
// mass-proportional damping, at OpenSees' step 5e-4 s: the peak top displacement and the
// residual one at 5 s lie within 2 % of the peak of OpenSees' Newmark run of the same column
// (measured: the whole record within 2e-12 of the peak).
#[test]
fn rc_pulse_newmark_matches_opensees() {
    let mut d = driver(Scheme::Newmark, DT);
    let mut top = vec![0.0];
    for step in 1..=STEPS {
        d.step(&ground, 1e-20, 50, Algorithm::Newton)
            .unwrap_or_else(|e| panic!("step {step}: {e}"));
        if step % 10 == 0 {
            top.push(d.column().top_displacement().x);
        }
    }
    let r = reference("rc_pulse");
    let want = reference_column(&r, "top_displacement");
    assert_eq!(want.len(), top.len());
    let peak_ref = want.iter().fold(0.0f64, |p, x| p.max(x.abs()));
    let peak = top.iter().fold(0.0f64, |p, x| p.max(x.abs()));
    let (end, end_ref) = (top[top.len() - 1], want[want.len() - 1]);
    let worst = top
        .iter()
        .zip(&want)
        .fold(0.0f64, |w, (x, y)| w.max((x - y).abs()));
    eprintln!(
        "rc_pulse newmark: peak {peak:.6e} vs {peak_ref:.6e} m, residual {end:.6e} vs {end_ref:.6e} m, max difference {:.3e} of the peak, {} iterations (H = {H} m)",
        worst / peak_ref,
        d.iterations
    );
    assert!((peak - peak_ref).abs() < 0.02 * peak_ref);
    assert!((end - end_ref).abs() < 0.02 * peak_ref);
    assert!(worst < 1e-9 * peak_ref);
}
