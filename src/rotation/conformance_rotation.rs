//! Conformance suite of the rotation-only charts (`RotationChart`: `so3`, `quat_proj`,
//! `rotvec`, `matrix_proj`), every one against the same invariants:
//! 1. `R -> chart -> R` within 1e-14 (1e-13 for `rotvec`, whose logarithm loses a few digits
//!    near pi) over random rotations and rotations near the identity and near angle pi, and it
//!    agrees with the pose chart's rotation part (`from_pose`, `rotation`) exactly;
//! 2. `rotate(c, dw)` agrees with `exp([dw]x) R` to second order in `dw`
//!    (`<= 2 |dw|^2 + 1e-14`; exact to 1e-14 for the group chart `so3`), and its result
//!    satisfies the chart's constraint (`residual`) to round-off;
//! 3. `rotate(c, 0)` is `c` up to the normalization's round-off (the rotation to 1e-15);
//! 4. accumulating a full turn in 400 increments returns `so3` and `rotvec` to the identity,
//!    and the first-order charts to the rotation their update makes (`2 atan(|dw|/2)` a step
//!    for `quat_proj`, `atan(|dw|)` for `matrix_proj`); `rotvec` stays in `|psi| <= pi`;
//! 5. proptest: (1) and (2) over random rotations and increments.
use nalgebra::{Matrix3, Vector3};
use proptest::prelude::*;
use std::f64::consts::{PI, TAU};

use super::{MatrixProj, Pose, QuatProj, RotVec, RotationChart, So3};
use crate::math::so3;

/// Rotations to check at: a spread over the group and the identity and angle-pi edges.
fn rotations() -> Vec<Matrix3<f64>> {
    let axis = Vector3::new(0.48, -0.6, 0.64);
    let mut out: Vec<Matrix3<f64>> = [PI, PI - 1e-9, 1e-9, 0.0, 1.0, 2.5]
        .iter()
        .map(|t| so3::exp(&(axis * *t)))
        .collect();
    for k in 0..40 {
        let f = k as f64;
        let v = Vector3::new((1.3 * f).sin(), (0.7 * f + 1.0).cos(), (2.1 * f).sin());
        out.push(so3::exp(&(v * (0.08 * f))));
    }
    out
}

/// Check 1: the largest round-trip error, and whether the chart's coordinates and matrix are
/// its pose chart's.
fn round_trip<C: RotationChart>() -> f64
where
    C::Rot: PartialEq,
{
    let mut worst = 0.0_f64;
    for r in rotations() {
        let c = C::from_matrix(&r);
        let pose = C::from_pose(&r, &Vector3::new(1.0, -2.0, 3.0));
        assert!(pose.rot == c, "{}: from_matrix is not from_pose's", C::NAME);
        assert_eq!(C::matrix(&c), C::rotation(&pose), "{}", C::NAME);
        worst = worst.max((C::matrix(&c) - r).norm());
    }
    worst
}

/// Check 2: the largest error of `rotate` against the exponential relative to the bound
/// `2 |dw|^2 + 1e-14`, and the largest constraint residual after a rotation.
fn first_order<C: RotationChart>() -> (f64, f64) {
    let (mut ratio, mut residual) = (0.0_f64, 0.0_f64);
    for (k, r) in rotations().into_iter().enumerate() {
        for s in [1e-2, 1e-4, 1e-6] {
            let f = k as f64;
            let dw = Vector3::new(f.cos(), (2.0 * f).sin(), 0.5) * s;
            let c = C::rotate(&C::from_matrix(&r), &dw);
            let err = (C::matrix(&c) - so3::exp(&dw) * r).norm();
            ratio = ratio.max(err / (2.0 * dw.norm_squared() + 1e-14));
            let pose = Pose {
                rot: c,
                x: Vector3::zeros(),
            };
            residual = residual.max(C::residual(&pose).unwrap_or(0.0));
        }
    }
    (ratio, residual)
}

/// The pose chart's rotation part is a rotation chart: round trips, first-order updates on
/// the group's constraint, and a zero increment that changes nothing but round-off, for every
/// rotation-only chart (checks 1 to 3).
#[test]
fn every_rotation_chart_conforms() {
    fn check<C: RotationChart>(trip: f64)
    where
        C::Rot: PartialEq,
    {
        let worst = round_trip::<C>();
        assert!(worst < trip, "{}: round trip {worst:e}", C::NAME);
        let (ratio, residual) = first_order::<C>();
        assert!(ratio <= 1.0, "{}: update error / bound = {ratio}", C::NAME);
        assert!(
            residual < 1e-14,
            "{}: constraint residual {residual:e}",
            C::NAME
        );
        for r in rotations() {
            let c = C::from_matrix(&r);
            let moved = C::matrix(&C::rotate(&c, &Vector3::zeros())) - C::matrix(&c);
            assert!(
                moved.norm() < 1e-15,
                "{}: zero increment moved {:e}",
                C::NAME,
                moved.norm()
            );
        }
    }
    check::<So3>(1e-14);
    check::<QuatProj>(1e-14);
    check::<RotVec>(1e-13);
    check::<MatrixProj>(1e-14);
    // The group chart's update is the exponential itself (check 2's bound is for the others).
    let r = so3::exp(&Vector3::new(0.4, -1.0, 2.5));
    let dw = Vector3::new(0.3, -0.2, 0.1);
    let got = So3::matrix(&So3::rotate(&So3::from_matrix(&r), &dw));
    assert!((got - so3::exp(&dw) * r).norm() < 1e-14);
}

/// Check 4: a full turn in increments comes back as each chart's update says it should, and
/// the rotation vector is re-charted once past pi and stays within `|psi| <= pi`.
#[test]
fn full_turn_in_increments() {
    fn turn<C: RotationChart>(each: &mut dyn FnMut(&C::Rot)) -> Matrix3<f64> {
        let n = 400;
        let dw = Vector3::new(0.0, TAU / n as f64, 0.0);
        let mut c = C::identity();
        for _ in 0..n {
            c = C::rotate(&c, &dw);
            each(&c);
        }
        C::matrix(&c)
    }
    let step = TAU / 400.0;
    let about_y = |angle: f64| so3::exp(&Vector3::new(0.0, angle, 0.0));
    assert!((turn::<So3>(&mut |_| ()) - Matrix3::identity()).norm() < 1e-13);
    let mut widest = 0.0_f64;
    let r = turn::<RotVec>(&mut |psi| widest = widest.max(psi.norm()));
    assert!((r - Matrix3::identity()).norm() < 1e-12);
    assert!(widest <= PI + 1e-12, "rotvec reached |psi| = {widest}");
    // The first-order charts rotate by slightly less than each increment's angle: by
    // 2 atan(|dw|/2) (quat_proj) and atan(|dw|) (matrix_proj) a step, a shortfall of
    // |dw|^3/12 and |dw|^3/3 each, which a Newton iteration corrects on a structure.
    let want = about_y(400.0 * 2.0 * (step / 2.0).atan());
    assert!((turn::<QuatProj>(&mut |_| ()) - want).norm() < 1e-12);
    let want = about_y(400.0 * step.atan());
    assert!((turn::<MatrixProj>(&mut |_| ()) - want).norm() < 1e-12);
}

proptest! {
    /// Check 5: round trips and second-order agreement of the update with the exponential
    /// over random rotations and increments.
    #[test]
    fn rotation_charts_random(x in -3.0..3.0f64, y in -3.0..3.0f64, z in -3.0..3.0f64,
                              a in -1.0..1.0f64, b in -1.0..1.0f64, c in -1.0..1.0f64) {
        let r = so3::exp(&Vector3::new(x, y, z));
        let dw = Vector3::new(a, b, c) * 1e-3;
        let bound = 2.0 * dw.norm_squared() + 1e-14;
        fn errors<C: RotationChart>(r: &Matrix3<f64>, dw: &Vector3<f64>) -> (f64, f64) {
            let c = C::from_matrix(r);
            let trip = (C::matrix(&c) - r).norm();
            let update = (C::matrix(&C::rotate(&c, dw)) - so3::exp(dw) * r).norm();
            (trip, update)
        }
        for (name, (trip, update), tol) in [
            ("so3", errors::<So3>(&r, &dw), 1e-14),
            ("quat_proj", errors::<QuatProj>(&r, &dw), 1e-14),
            ("rotvec", errors::<RotVec>(&r, &dw), 1e-13),
            ("matrix_proj", errors::<MatrixProj>(&r, &dw), 1e-14),
        ] {
            prop_assert!(trip < tol, "{}: round trip {:e}", name, trip);
            prop_assert!(update <= bound, "{}: update {:e} > {:e}", name, update, bound);
        }
        let m = MatrixProj::rotate(&r, &dw);
        prop_assert!((m.transpose() * m - Matrix3::identity()).norm() < 1e-14);
    }
}
