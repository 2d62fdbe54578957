//! The rotation charts of the column's nodes: how each node's rotation is stored and how
//! Newton's rotation increment is applied to it.
//!
//! Newton's unknown per node is a spatial rotation increment `dw` (a 3-vector: the new
//! rotation is meant to be `exp([dw]x) R`). Each chart stores `R` in its own numbers and
//! applies `dw` with its own retraction:
//!
//! - `so3`: a unit quaternion, updated on the group, `q <- exp(dw/2) q` (exact; no singular
//!   set);
//! - `quat_proj`: a quaternion updated additively by its kinematic map and projected back to
//!   the unit sphere, `q <- (q + [0, dw/2] q) / |.|`, which rotates by `2 atan(|dw|/2)`
//!   instead of `|dw|` (a first-order retraction);
//! - `rotvec`: the rotation vector `psi` (`R = exp([psi]x)`), updated additively,
//!   `psi <- psi + dexp_inv(psi) dw` (first order), whose map is singular where
//!   `|psi| = 2 pi k`; it is re-charted past `pi` (`psi <- psi (1 - 2 pi/|psi|)`, the same
//!   rotation), so `|psi| <= pi` after every update and the singular set is never reached;
//! - `matrix_proj`: the rotation matrix updated additively, `R <- R + [dw]x R`, and
//!   projected to the nearest rotation (the polar factor, by Higham's Newton iteration
//!   `X <- (X + X^-T)/2`, quadratic).
//!
//! All four retractions agree with `exp(dw) R` to first order in `dw`, so Newton converges to
//! the same equilibrium with each; the charts differ in the iterates (hence iteration counts)
//! and in where their updates are singular. Where it fails: `matrix_proj`'s projection
//! diverges if an increment makes `R + [dw]x R` singular (`|dw|` near 1 along a special
//! direction is not enough; it needs `|dw| >> 1`); Newton's increments are far smaller.
use nalgebra::{Matrix3, Quaternion, UnitQuaternion, Vector3};

use crate::math::so3;

/// A chart of one node's rotation.
///
/// # Example
///
/// Every chart applies a small increment as the exponential does, up to an error of second
/// order in the increment:
///
/// ```
/// use mbdbench::model::fiber_column::chart::{MatrixProj, QuatProj, RotationChart, Rotvec, So3};
/// use nalgebra::Vector3;
///
/// fn check<C: RotationChart>() {
///     let r0 = C::from_matrix(&mbdbench::math::so3::exp(&Vector3::new(0.4, -1.0, 2.5)));
///     let dw = Vector3::new(1e-4, 2e-4, -1e-4);
///     let want = mbdbench::math::so3::exp(&dw) * C::matrix(&r0);
///     let got = C::matrix(&C::retract(&r0, &dw));
///     assert!((got - want).norm() < 2.0 * dw.norm_squared(), "{}", C::NAME);
/// }
/// check::<So3>();
/// check::<QuatProj>();
/// check::<Rotvec>();
/// check::<MatrixProj>();
/// ```
pub trait RotationChart: Send + Sync + 'static {
    /// The variant name on the `param` axis.
    const NAME: &'static str;
    /// The stored numbers.
    type Coords: Copy + std::fmt::Debug + Send + Sync;
    /// The identity rotation.
    fn identity() -> Self::Coords;
    /// The chart's coordinates of a rotation matrix.
    fn from_matrix(r: &Matrix3<f64>) -> Self::Coords;
    /// The rotation matrix.
    fn matrix(c: &Self::Coords) -> Matrix3<f64>;
    /// Applies the spatial increment `dw` with the chart's own update (and projection or
    /// re-charting).
    fn retract(c: &Self::Coords, dw: &Vector3<f64>) -> Self::Coords;
}

/// The rotation group itself: a unit quaternion updated by the exponential.
pub struct So3;

impl RotationChart for So3 {
    const NAME: &'static str = "so3";
    type Coords = UnitQuaternion<f64>;
    fn identity() -> Self::Coords {
        UnitQuaternion::identity()
    }
    fn from_matrix(r: &Matrix3<f64>) -> Self::Coords {
        so3::quat_from_matrix(r)
    }
    fn matrix(c: &Self::Coords) -> Matrix3<f64> {
        *c.to_rotation_matrix().matrix()
    }
    fn retract(c: &Self::Coords, dw: &Vector3<f64>) -> Self::Coords {
        let q = so3::exp_quat(dw) * c;
        UnitQuaternion::new_unchecked(so3::renormalize(q.into_inner()))
    }
}

/// A quaternion updated additively and projected to the unit sphere.
pub struct QuatProj;

impl RotationChart for QuatProj {
    const NAME: &'static str = "quat_proj";
    type Coords = Quaternion<f64>;
    fn identity() -> Self::Coords {
        Quaternion::identity()
    }
    fn from_matrix(r: &Matrix3<f64>) -> Self::Coords {
        so3::quat_from_matrix(r).into_inner()
    }
    fn matrix(c: &Self::Coords) -> Matrix3<f64> {
        *UnitQuaternion::new_normalize(*c)
            .to_rotation_matrix()
            .matrix()
    }
    fn retract(c: &Self::Coords, dw: &Vector3<f64>) -> Self::Coords {
        let half = Quaternion::from_imag(dw * 0.5);
        let q = c + half * c;
        q / q.norm()
    }
}

/// The rotation vector, updated additively and re-charted past `pi`.
pub struct Rotvec;

impl Rotvec {
    /// The same rotation with `|psi| <= pi`: `psi (1 - 2 pi/|psi|)` past `pi`.
    pub fn rechart(psi: Vector3<f64>) -> Vector3<f64> {
        let t = psi.norm();
        if t > std::f64::consts::PI {
            psi * (1.0 - std::f64::consts::TAU / t)
        } else {
            psi
        }
    }
}

impl RotationChart for Rotvec {
    const NAME: &'static str = "rotvec";
    type Coords = Vector3<f64>;
    fn identity() -> Self::Coords {
        Vector3::zeros()
    }
    fn from_matrix(r: &Matrix3<f64>) -> Self::Coords {
        so3::log(r)
    }
    fn matrix(c: &Self::Coords) -> Matrix3<f64> {
        so3::exp(c)
    }
    fn retract(c: &Self::Coords, dw: &Vector3<f64>) -> Self::Coords {
        Self::rechart(c + so3::dexp_inv_apply(c, dw))
    }
}

/// The rotation matrix, updated additively and projected to its polar factor.
pub struct MatrixProj;

impl MatrixProj {
    /// The nearest rotation to `x` (its orthogonal polar factor), by Newton's iteration
    /// `X <- (X + X^-T)/2` from `x` until the update is below 1e-15.
    pub fn project(x: &Matrix3<f64>) -> Matrix3<f64> {
        let mut r = *x;
        for _ in 0..30 {
            let Some(inv) = r.try_inverse() else { break };
            let next = (r + inv.transpose()) * 0.5;
            let change = (next - r).norm();
            r = next;
            if change < 1e-15 {
                break;
            }
        }
        r
    }
}

impl RotationChart for MatrixProj {
    const NAME: &'static str = "matrix_proj";
    type Coords = Matrix3<f64>;
    fn identity() -> Self::Coords {
        Matrix3::identity()
    }
    fn from_matrix(r: &Matrix3<f64>) -> Self::Coords {
        *r
    }
    fn matrix(c: &Self::Coords) -> Matrix3<f64> {
        *c
    }
    fn retract(c: &Self::Coords, dw: &Vector3<f64>) -> Self::Coords {
        Self::project(&(c + so3::hat(dw) * c))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    fn round_trip<C: RotationChart>(psi: Vector3<f64>) -> f64 {
        let r = so3::exp(&psi);
        (C::matrix(&C::from_matrix(&r)) - r).norm()
    }

    fn retract_error<C: RotationChart>(psi: Vector3<f64>, dw: Vector3<f64>) -> f64 {
        let c = C::from_matrix(&so3::exp(&psi));
        let got = C::matrix(&C::retract(&c, &dw));
        (got - so3::exp(&dw) * so3::exp(&psi)).norm()
    }

    proptest! {
        // Every chart's coordinates give back the rotation they were made from.
        #[test]
        fn charts_round_trip(x in -3.0..3.0f64, y in -3.0..3.0f64, z in -3.0..3.0f64) {
            let psi = Vector3::new(x, y, z);
            prop_assert!(round_trip::<So3>(psi) < 1e-14);
            prop_assert!(round_trip::<QuatProj>(psi) < 1e-14);
            prop_assert!(round_trip::<Rotvec>(psi) < 1e-13);
            prop_assert!(round_trip::<MatrixProj>(psi) < 1e-15);
        }

        // Every retraction agrees with the exponential to second order in the increment
        // (error <= C |dw|^2 with C of order 1), and the result is a rotation.
        #[test]
        fn retractions_are_first_order(x in -3.0..3.0f64, y in -3.0..3.0f64, z in -3.0..3.0f64,
                                       a in -1.0..1.0f64, b in -1.0..1.0f64, c in -1.0..1.0f64) {
            let psi = Vector3::new(x, y, z);
            let dw = Vector3::new(a, b, c) * 1e-3;
            let bound = 2.0 * dw.norm_squared() + 1e-14;
            prop_assert!(retract_error::<So3>(psi, dw) < 1e-14);
            prop_assert!(retract_error::<QuatProj>(psi, dw) <= bound);
            prop_assert!(retract_error::<Rotvec>(psi, dw) <= bound);
            prop_assert!(retract_error::<MatrixProj>(psi, dw) <= bound);
            let m = MatrixProj::retract(&so3::exp(&psi), &dw);
            prop_assert!((m.transpose() * m - Matrix3::identity()).norm() < 1e-14);
        }
    }

    // Accumulating an in-plane rotation of 2 pi in small increments brings every chart back
    // to the identity, and the rotation vector stays within |psi| <= pi throughout (it is
    // re-charted once, past pi).
    #[test]
    fn full_turn_in_increments() {
        fn turn<C: RotationChart>() -> (Matrix3<f64>, usize) {
            let mut c = C::identity();
            let n = 400;
            let dw = Vector3::new(0.0, std::f64::consts::TAU / n as f64, 0.0);
            for _ in 0..n {
                c = C::retract(&c, &dw);
            }
            (C::matrix(&c), n)
        }
        let (r, _) = turn::<So3>();
        assert!((r - Matrix3::identity()).norm() < 1e-13);
        let (r, _) = turn::<Rotvec>();
        assert!((r - Matrix3::identity()).norm() < 1e-12);
        // The first-order charts rotate by slightly less than each increment's angle: by
        // 2 atan(|dw|/2) (quat_proj) and atan(|dw|) (matrix_proj) per step, a shortfall of
        // |dw|^3/12 and |dw|^3/3 each, which Newton would correct on a real structure.
        let (r, n) = turn::<QuatProj>();
        let step = std::f64::consts::TAU / n as f64;
        let want = so3::exp(&Vector3::new(
            0.0,
            n as f64 * 2.0 * (step / 2.0).atan(),
            0.0,
        ));
        assert!((r - want).norm() < 1e-12);
        let (r, _) = turn::<MatrixProj>();
        let want = so3::exp(&Vector3::new(0.0, n as f64 * step.atan(), 0.0));
        assert!((r - want).norm() < 1e-12);
        let mut psi = Rotvec::identity();
        let dw = Vector3::new(0.0, std::f64::consts::TAU / 400.0, 0.0);
        for _ in 0..400 {
            psi = Rotvec::retract(&psi, &dw);
            assert!(psi.norm() <= std::f64::consts::PI + 1e-12);
        }
    }
}
