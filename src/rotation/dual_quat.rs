//! `dual_quat`: the pose as a unit dual quaternion `p + eps d` (8 numbers) on the Lie group
//! SE(3), never normalised: it reports its own drift.
//!
//! A pose `(R, x)` is `p` = the unit quaternion of `R`, `d = (0, x) (x) p / 2`; back,
//! `x = 2 d (x) p*` (vector part) and `R` is the sandwich `u -> p (0, u) p*` (as in `quat`,
//! homogeneous: off the unit sphere the stored numbers are used as they are). The product
//! `(p1 + eps d1)(p2 + eps d2) = p1 p2 + eps (p1 d2 + d1 p2)` is the SE(3) product
//! (Kenwright, *A beginner's guide to dual-quaternions*, WSCG 2012, sec. 4; Selig,
//! *Geometric Fundamentals of Robotics*, 2005, ch. 9). The two constraints of a unit dual
//! quaternion are `|p|^2 = 1` and `p . d = 0`; the residual is
//! `max(||p|^2 - 1|, 2 |p . d|)` (`2 p . d` is the rate of change of `|p + eps d|^2`'s dual
//! part, so both terms are dimensionless-comparable for `|x| ~ 1`).
//!
//! Tangent, trivialisations and RKMK correction exactly as in `se3_hq`: the twist
//! `(omega, v)`, retract `g exp(xi)` (body twist) or `exp(xi) g` (spatial twist), where the
//! dual-quaternion exponential of `xi` is `e + eps (0, J(omega) v) e / 2`, `e = exp_quat(omega)`,
//! and `dexp_inv` of SE(3). Products of unit dual quaternions stay unit up to round-off, so
//! the drift grows like the accumulated rounding (~ sqrt(steps) eps). No singular set.
use nalgebra::{DualQuaternion, Matrix3, Quaternion, UnitQuaternion, Vector3, Vector6};

use super::PoseChart;
use super::quat::sandwich_matrix;
use crate::math::{se3, so3};

/// `(0, v)` as a quaternion.
#[inline(always)]
fn pure(v: &Vector3<f64>) -> Quaternion<f64> {
    Quaternion::new(0.0, v.x, v.y, v.z)
}

/// The dual quaternion of the pose `(q, x)`.
#[inline(always)]
pub fn from_parts(q: &Quaternion<f64>, x: &Vector3<f64>) -> DualQuaternion<f64> {
    DualQuaternion::from_real_and_dual(*q, pure(x) * q * 0.5)
}

/// `x = 2 d (x) p*` (vector part).
#[inline(always)]
pub fn translation(g: &DualQuaternion<f64>) -> Vector3<f64> {
    (g.dual * g.real.conjugate()).imag() * 2.0
}

impl super::Translation for DualQuaternion<f64> {
    #[inline(always)]
    fn translation(&self) -> Vector3<f64> {
        translation(self)
    }
}

/// The `dual_quat` chart.
#[derive(Debug, Clone, Copy, Default)]
pub struct DualQuat;

impl PoseChart for DualQuat {
    const NAME: &'static str = "dual_quat";
    /// `real` = `p`, `dual` = `d`.
    type Coords = DualQuaternion<f64>;
    /// The twist `(omega, v)`: body twist (`!spatial`) or spatial twist (`spatial`).
    type Tangent = Vector6<f64>;
    const LIE: bool = true;
    const SE3: bool = true;
    const CONSTRAINED: bool = true;
    const NORMALIZES: bool = false;

    fn from_pose(r: &Matrix3<f64>, x: &Vector3<f64>) -> Self::Coords {
        from_parts(so3::quat_from_matrix(r).quaternion(), x)
    }
    #[inline(always)]
    fn rotation(c: &Self::Coords) -> Matrix3<f64> {
        sandwich_matrix(&c.real)
    }
    fn quaternion(c: &Self::Coords) -> UnitQuaternion<f64> {
        so3::canonical(&UnitQuaternion::new_normalize(c.real))
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
            se3::twist(&w, &(xdot - w.cross(&translation(c))))
        } else {
            se3::twist(omega_body, &(r.transpose() * xdot))
        }
    }
    #[inline(always)]
    fn retract(c: &Self::Coords, d: &Self::Tangent, spatial: bool) -> Self::Coords {
        let (e, t) = se3::exp_quat(d);
        let g = from_parts(e.quaternion(), &t);
        if spatial { g * c } else { c * g }
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
        let p = &c.real.coords;
        let d = &c.dual.coords;
        Some((p.norm_squared() - 1.0).abs().max(2.0 * p.dot(d).abs()))
    }
    fn conditioning(_c: &Self::Coords) -> f64 {
        1.0
    }
    #[inline(always)]
    fn normalize(_c: &mut Self::Coords) -> bool {
        false
    }
    #[inline]
    fn is_finite(c: &Self::Coords) -> bool {
        c.real
            .coords
            .iter()
            .chain(c.dual.coords.iter())
            .all(|v| v.is_finite())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The dual-quaternion product is the SE(3) product: (R1, x1)(R2, x2) =
    /// (R1 R2, x1 + R1 x2) to 1e-15, and a pose's residual is at round-off (<= 4.5e-16).
    #[test]
    fn product_is_se3_product() {
        let q1 = so3::exp_quat(&Vector3::new(0.3, -1.0, 0.4));
        let q2 = so3::exp_quat(&Vector3::new(-2.0, 0.1, 0.7));
        let x1 = Vector3::new(1.0, -2.0, 0.5);
        let x2 = Vector3::new(-0.3, 0.4, 2.0);
        let g = from_parts(q1.quaternion(), &x1) * from_parts(q2.quaternion(), &x2);
        let r = (q1 * q2).to_rotation_matrix().into_inner();
        assert!((DualQuat::rotation(&g) - r).amax() < 1e-15);
        assert!((translation(&g) - (x1 + q1 * x2)).amax() < 1e-15 * 4.0);
        assert!(DualQuat::residual(&g).unwrap() <= 4.5e-16 * 2.0);
    }
}
