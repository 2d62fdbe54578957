//! `se3_hq`: the pose as an element `g = (R, x)` of the Lie group SE(3) (a homogeneous
//! matrix), with `R` stored as a unit quaternion; rotation and translation move together.
//!
//! Tangent: the twist `xi = (omega, v)`, rotation first (`math::se3`). Body formulation:
//! right trivialisation, `g' = g xi^` with the body twist `xi = (omega_body, R^T xdot)`,
//! retract `g exp(xi)`; spatial formulation: left trivialisation, `g' = xi^ g` with the
//! spatial twist `xi = (w, xdot - w x x)`, `w = R omega_body`, retract `exp(xi) g`. With
//! `exp(xi) = (exp(omega), J(omega) v)` and `(R1, x1)(R2, x2) = (R1 R2, x1 + R1 x2)`:
//! `g exp(xi) = (q e, x + R J v)` and `exp(xi) g = (e q, E x + J v)` (`e` the quaternion of
//! `E = exp(omega)`). The RKMK correction is the SE(3) `dexp_inv` with its coupling block:
//! `dexp_inv(-theta)` (body) or `dexp_inv(theta)` (spatial) (Iserles et al. 2000, sec. 3;
//! Munthe-Kaas 1998). Exact for screw motions; the increment of one step must stay below
//! `|omega| = 2 pi` (the pole of `dexp_inv`), as on SO(3).
//!
//! The quaternion is renormalised after every step (products of unit quaternions drift by
//! about an ulp per step); the residual is `||q|^2 - 1|`. No singular set (conditioning 1).
use nalgebra::{Matrix3, UnitQuaternion, Vector3, Vector6};

use super::{Pose, PoseChart};
use crate::math::{se3, so3};

/// The `se3_hq` chart.
#[derive(Debug, Clone, Copy, Default)]
pub struct Se3Hq;

impl PoseChart for Se3Hq {
    const NAME: &'static str = "se3_hq";
    type Coords = Pose<UnitQuaternion<f64>>;
    /// The twist `(omega, v)`: body twist (`!spatial`) or spatial twist (`spatial`).
    type Tangent = Vector6<f64>;
    const LIE: bool = true;
    const SE3: bool = true;
    const CONSTRAINED: bool = true;
    const NORMALIZES: bool = true;

    fn from_pose(r: &Matrix3<f64>, x: &Vector3<f64>) -> Self::Coords {
        Pose {
            rot: so3::quat_from_matrix(r),
            x: *x,
        }
    }
    #[inline(always)]
    fn rotation(c: &Self::Coords) -> Matrix3<f64> {
        c.rot.to_rotation_matrix().into_inner()
    }
    #[inline(always)]
    fn quaternion(c: &Self::Coords) -> UnitQuaternion<f64> {
        c.rot
    }
    #[inline(always)]
    fn velocity(
        c: &Self::Coords,
        r: &Matrix3<f64>,
        omega_body: &Vector3<f64>,
        xdot: &Vector3<f64>,
        spatial: bool,
    ) -> Self::Tangent {
        if spatial {
            let w = r * omega_body;
            se3::twist(&w, &(xdot - w.cross(&c.x)))
        } else {
            se3::twist(omega_body, &(r.transpose() * xdot))
        }
    }
    #[inline(always)]
    fn retract(c: &Self::Coords, d: &Self::Tangent, spatial: bool) -> Self::Coords {
        let (e, t) = se3::exp_quat(d);
        // Products of unit quaternions: keep the raw product (normalize() projects).
        if spatial {
            Pose {
                rot: UnitQuaternion::new_unchecked(e.into_inner() * c.rot.into_inner()),
                x: e.transform_vector(&c.x) + t,
            }
        } else {
            Pose {
                rot: UnitQuaternion::new_unchecked(c.rot.into_inner() * e.into_inner()),
                x: c.x + c.rot.transform_vector(&t),
            }
        }
    }
    #[inline(always)]
    fn dexp_inv(theta: &Self::Tangent, v: &Self::Tangent, spatial: bool) -> Self::Tangent {
        if spatial {
            se3::dexp_inv_apply(theta, v)
        } else {
            se3::dexp_inv_apply(&(-theta), v)
        }
    }
    fn residual(c: &Self::Coords) -> Option<f64> {
        Some((c.rot.into_inner().norm_squared() - 1.0).abs())
    }
    fn conditioning(_c: &Self::Coords) -> f64 {
        1.0
    }
    #[inline(always)]
    fn normalize(c: &mut Self::Coords) -> bool {
        c.rot = UnitQuaternion::new_unchecked(so3::renormalize(c.rot.into_inner()));
        true
    }
    #[inline]
    fn is_finite(c: &Self::Coords) -> bool {
        c.rot.coords.iter().chain(c.x.iter()).all(|v| v.is_finite())
    }
}
