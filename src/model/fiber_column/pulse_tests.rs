//! Tests of the column's dynamic step (Newmark, average acceleration) against the stored
//! OpenSees run of the RC column under the ground-acceleration pulse.
use nalgebra::DVector;

use super::chart::So3;
use super::column::{Algorithm, Column, Inertia};
use super::rc_tests::{H, P, rc_column, reference, reference_column};

/// The damping coefficient `a0 = 2 zeta omega_1` of the OpenSees script (zeta = 0.02,
/// omega_1 = 14.820708227335706 rad/s after the axial prelude).
const A0: f64 = 0.5928283290934282;
const G0: f64 = 9.80665;

fn ground(t: f64) -> f64 {
    if t <= 1.0 {
        0.5 * G0 * (std::f64::consts::TAU * t / 0.5).sin()
    } else {
        0.0
    }
}

// Newmark's average-acceleration rule on the c01 column with the top mass P/g0 and 2 %
// mass-proportional damping, at OpenSees' step 5e-4 s: the peak top displacement and the
// residual one at 5 s lie within 2 % of the peak of OpenSees' Newmark run of the same column.
#[test]
fn rc_pulse_newmark_matches_opensees() {
    let mut col: Column<So3> = rc_column(false, 1, true);
    let dim = col.dim();
    let mut f = DVector::zeros(dim);
    for k in 1..=10 {
        f[col.top_dof(2)] = -P * k as f64 / 10.0;
        col.step(&f, None, 1e-20, 50, Algorithm::Newton).unwrap();
    }
    let m = P / G0;
    let mut mass = DVector::zeros(dim);
    mass[col.top_dof(0)] = m;
    mass[col.top_dof(2)] = m;
    let (beta, gamma, h) = (0.25, 0.5, 5e-4);
    let n = 10_000;
    let mut u = DVector::zeros(dim);
    u[col.top_dof(2)] = col.top_displacement().z;
    let mut v = DVector::zeros(dim);
    let mut a = DVector::zeros(dim);
    let mut top = vec![0.0];
    let mut iterations = 0;
    for step in 1..=n {
        let t = step as f64 * h;
        let u_pred = &u + &v * h + &a * (h * h * (0.5 - beta));
        let v_pred = &v + &a * (h * (1.0 - gamma));
        f[col.top_dof(0)] = -m * ground(t);
        let inertia = Inertia::newmark(
            &mass,
            A0,
            1.0 / (beta * h * h),
            gamma * h,
            &u_pred,
            &v_pred,
        );
        let (c, _) = col
            .step_dynamic(&f, None, Some(inertia), 1e-20, 50, Algorithm::Newton)
            .unwrap_or_else(|e| panic!("step {step}: {e}"));
        iterations += c.iterations;
        let d = col.top_displacement();
        for (i, x) in [(col.top_dof(0), d.x), (col.top_dof(2), d.z)] {
            u[i] = x;
            a[i] = (x - u_pred[i]) / (beta * h * h);
            v[i] = v_pred[i] + gamma * h * a[i];
        }
        if step % 10 == 0 {
            top.push(d.x);
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
        "rc_pulse newmark: peak {peak:.6e} vs {peak_ref:.6e} m, residual {end:.6e} vs {end_ref:.6e} m, max difference {:.3e} of the peak, {iterations} iterations (H = {H} m)",
        worst / peak_ref
    );
    assert!((peak - peak_ref).abs() < 0.02 * peak_ref);
    assert!((end - end_ref).abs() < 0.02 * peak_ref);
}
