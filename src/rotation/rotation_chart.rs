//! The rotation-only part of a chart: a rotation stored in the chart's own numbers and moved
//! by a spatial rotation increment, for structures whose nodes each carry a rotation (the
//! fiber column's nodes; later the bodies of a spatial mechanism) and whose Newton unknown is
//! the increment `dw` (a 3-vector: the new rotation is meant to be `exp([dw]x) R`).
//!
//! A `PoseChart` describes a body's whole pose; the charts that keep the translation apart
//! (coordinates `Pose<Q>`: `so3`, `quat_proj`, `rotvec`, `matrix_proj`, ...) have a rotation
//! part `Q` of their own, and [`RotationChart`] is that part. Its map to and from a rotation
//! matrix and its normalization (projection or re-charting) are the pose chart's, read on a
//! pose with zero translation, so each is written once; what a chart adds is `advance`, its
//! own first-order update by a spatial increment:
//!
//! - `so3`: `q <- exp(dw/2) q` on the group (exact; no singular set);
//! - `quat_proj`: `q <- q + [0, dw/2] q`, then projected to the unit sphere: a rotation by
//!   `2 atan(|dw|/2)` instead of `|dw|` (first order);
//! - `rotvec`: `psi <- psi + dexp_inv(psi) dw` (first order), re-charted past `pi`, so
//!   `|psi| <= pi` after every update and its singular set `|psi| = 2 pi k` is never reached;
//! - `matrix_proj`: `R <- R + [dw]x R`, then projected to its polar factor: a rotation by
//!   `atan(|dw|)` (first order).
//!
//! All agree with `exp([dw]x) R` to first order in `dw` (error at most `2 |dw|^2`, checked by
//! the conformance suite), so a Newton iteration over `dw` converges to the same solution with
//! each; they differ in the iterates and in where their updates are singular. The SE(3)
//! charts (`se3_hq`, `dual_quat`) move rotation and translation together and have no
//! rotation-only part. Where it fails: `matrix_proj`'s projection leaves the matrix unchanged
//! (not a rotation) when `R + [dw]x R` is singular, which needs `|dw| >> 1`.
use nalgebra::{Matrix3, Quaternion, UnitQuaternion, Vector3};
use std::fmt::Debug;

use super::{MatrixProj, Pose, PoseChart, QuatProj, RotVec, So3};
use crate::math::so3;

/// The rotation part of a pose chart whose translation is kept apart.
///
/// # Example
///
/// Every chart applies a small spatial increment as the exponential does, up to an error of
/// second order in the increment:
///
/// ```
/// use mbdbench::math::so3;
/// use mbdbench::rotation::{MatrixProj, QuatProj, RotVec, RotationChart, So3};
/// use nalgebra::Vector3;
///
/// fn check<C: RotationChart>() {
///     let r0 = C::from_matrix(&so3::exp(&Vector3::new(0.4, -1.0, 2.5)));
///     let dw = Vector3::new(1e-4, 2e-4, -1e-4);
///     let want = so3::exp(&dw) * C::matrix(&r0);
///     let got = C::matrix(&C::rotate(&r0, &dw));
///     assert!((got - want).norm() < 2.0 * dw.norm_squared(), "{}", C::NAME);
/// }
/// check::<So3>();
/// check::<QuatProj>();
/// check::<RotVec>();
/// check::<MatrixProj>();
/// ```
pub trait RotationChart: PoseChart<Coords = Pose<Self::Rot>> {
    /// The stored numbers of the rotation.
    type Rot: Copy + Debug + Send + Sync;

    /// The chart's own first-order update by the spatial increment `dw` (before its
    /// normalization).
    fn advance(c: &Self::Rot, dw: &Vector3<f64>) -> Self::Rot;

    /// The chart's coordinates of a rotation matrix (the pose chart's, principal branch).
    fn from_matrix(r: &Matrix3<f64>) -> Self::Rot {
        Self::from_pose(r, &Vector3::zeros()).rot
    }

    /// The identity rotation.
    fn identity() -> Self::Rot {
        Self::from_matrix(&Matrix3::identity())
    }

    /// The rotation matrix (the pose chart's).
    fn matrix(c: &Self::Rot) -> Matrix3<f64> {
        Self::rotation(&Pose {
            rot: *c,
            x: Vector3::zeros(),
        })
    }

    /// `advance`, then the chart's normalization (projection or re-charting), as after a step.
    fn rotate(c: &Self::Rot, dw: &Vector3<f64>) -> Self::Rot {
        let mut p = Pose {
            rot: Self::advance(c, dw),
            x: Vector3::zeros(),
        };
        Self::normalize(&mut p);
        p.rot
    }
}

impl RotationChart for So3 {
    type Rot = UnitQuaternion<f64>;
    #[inline]
    fn advance(c: &Self::Rot, dw: &Vector3<f64>) -> Self::Rot {
        so3::exp_quat(dw) * c
    }
}

impl RotationChart for QuatProj {
    type Rot = Quaternion<f64>;
    #[inline]
    fn advance(c: &Self::Rot, dw: &Vector3<f64>) -> Self::Rot {
        c + Quaternion::from_imag(dw * 0.5) * c
    }
}

impl RotationChart for RotVec {
    type Rot = Vector3<f64>;
    #[inline]
    fn advance(c: &Self::Rot, dw: &Vector3<f64>) -> Self::Rot {
        c + so3::dexp_inv_apply(c, dw)
    }
}

impl RotationChart for MatrixProj {
    type Rot = Matrix3<f64>;
    #[inline]
    fn advance(c: &Self::Rot, dw: &Vector3<f64>) -> Self::Rot {
        c + so3::hat(dw) * c
    }
}
