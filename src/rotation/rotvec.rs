//! `rotvec`: the rotation vector `phi`, `R = exp([phi]x)`, additive, re-charted when its
//! angle passes pi; the translation is additive beside it.
//!
//! Kinematics: `R' = R [omega]x` gives `phi' = dexp_inv(-phi) omega`, the inverse of the right
//! Jacobian `dexp(-phi)` (Iserles et al., Acta Numerica 2000, sec. 2.3; Bullo & Murray,
//! *Proportional derivative control on the Euclidean group*, 1995, eq. 4):
//! `phi' = omega + [phi]x omega / 2 + (1 - (t/2) cot(t/2))/t^2 [phi]x^2 omega`, `t = |phi|`.
//! The coefficient has a pole at `t = 2 pi` (where `exp` collapses the sphere `|phi| = 2 pi`
//! onto the identity), so the conditioning is `1 - |phi|/(2 pi)`.
//!
//! Re-charting (`normalize`): when `|phi| > pi`, `phi <- phi (1 - 2 pi n/|phi|)` with
//! `n = round(|phi|/(2 pi))` (always `n = 1` for steps shorter than pi): the same rotation
//! (`exp` is `2 pi`-periodic along each axis) with `|phi| <= pi`, so the conditioning stays
//! at least 1/2 along a re-charted run. `from_pose` is the principal logarithm (`|phi| <= pi`,
//! `math::so3::log`, accurate up to and including pi). Errors: round-trips are accurate to
//! round-off; re-charting moves `R` by at most a few eps (the factor `1 - 2 pi/|phi|`).
use nalgebra::{Matrix3, Vector3, Vector6};
use std::f64::consts::{PI, TAU};

use super::{Pose, PoseChart};
use crate::math::so3;

/// The `rotvec` chart: coords `phi`, tangent `(phi', xdot)`.
#[derive(Debug, Clone, Copy, Default)]
pub struct RotVec;

impl PoseChart for RotVec {
    const NAME: &'static str = "rotvec";
    type Coords = Pose<Vector3<f64>>;
    /// `(phi', xdot)`.
    type Tangent = Vector6<f64>;
    const LIE: bool = false;
    const SE3: bool = false;
    const CONSTRAINED: bool = false;
    const NORMALIZES: bool = true;

    fn from_pose(r: &Matrix3<f64>, x: &Vector3<f64>) -> Self::Coords {
        Pose {
            rot: so3::log(r),
            x: *x,
        }
    }
    #[inline(always)]
    fn rotation(c: &Self::Coords) -> Matrix3<f64> {
        so3::exp(&c.rot)
    }
    #[inline(always)]
    fn velocity(
        c: &Self::Coords,
        _r: &Matrix3<f64>,
        omega_body: &Vector3<f64>,
        xdot: &Vector3<f64>,
        _spatial: bool,
    ) -> Self::Tangent {
        let p = so3::dexp_inv_apply(&(-c.rot), omega_body);
        Vector6::new(p.x, p.y, p.z, xdot.x, xdot.y, xdot.z)
    }
    #[inline(always)]
    fn retract(c: &Self::Coords, d: &Self::Tangent, _spatial: bool) -> Self::Coords {
        Pose {
            rot: c.rot + d.fixed_rows::<3>(0),
            x: c.x + d.fixed_rows::<3>(3),
        }
    }
    #[inline(always)]
    fn dexp_inv(_theta: &Self::Tangent, v: &Self::Tangent, _spatial: bool) -> Self::Tangent {
        *v
    }
    fn residual(_c: &Self::Coords) -> Option<f64> {
        None
    }
    #[inline]
    fn conditioning(c: &Self::Coords) -> f64 {
        1.0 - c.rot.norm() / TAU
    }
    #[inline(always)]
    fn normalize(c: &mut Self::Coords) -> bool {
        let t = c.rot.norm();
        if t > PI && t.is_finite() {
            let n = (t / TAU).round();
            c.rot *= 1.0 - TAU * n / t;
            true
        } else {
            false
        }
    }
    #[inline]
    fn is_finite(c: &Self::Coords) -> bool {
        c.rot.iter().chain(c.x.iter()).all(|v| v.is_finite())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Re-charting keeps the rotation (geodesic 1e-14), brings the angle to at most pi, fires
    /// only past pi, and is idempotent; including angles just below 2 pi and past 4 pi.
    #[test]
    fn rechart_keeps_rotation() {
        let axis = Vector3::new(0.48, -0.6, 0.64);
        for t in [
            PI - 1e-9,
            PI + 1e-9,
            4.0,
            TAU - 1e-6,
            TAU - 1e-9,
            TAU + 1e-3,
            4.0 * PI + 0.5,
        ] {
            let mut c = Pose {
                rot: axis * t,
                x: Vector3::zeros(),
            };
            let r = RotVec::rotation(&c);
            let applied = RotVec::normalize(&mut c);
            assert_eq!(applied, t > PI, "{t}");
            assert!(c.rot.norm() <= PI * (1.0 + 1e-15));
            assert!(RotVec::conditioning(&c) >= 0.5 - 1e-15);
            let g = so3::geodesic(&r, &RotVec::rotation(&c));
            assert!(g < 1e-14, "{t}: {g:e}");
            let before = c;
            assert!(!RotVec::normalize(&mut c));
            assert_eq!(before.rot, c.rot);
        }
    }
}
