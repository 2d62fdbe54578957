//! `so3`: the rotation on the Lie group SO(3), stored as a unit quaternion, with the
//! translation additive beside it (the group SO(3) x R^3).
//!
//! Retract: `q exp(theta/2)` (body, right trivialisation) or `exp(theta/2) q` (spatial, left);
//! the kinematic map is the trivialisation itself (`theta' = omega` body, `w` spatial) and the
//! RKMK correction is `dexp_inv(-theta)` (body) or `dexp_inv(theta)` (spatial) of
//! `math::so3`, both through `so3::exp_quat_dexp_inv` (Taylor polynomials below
//! `|theta| = 0.5`, the closed forms to round-off; one `sin_cos` above). The quaternion is renormalised after every step (`|q| = 1` to round-off;
//! the product of unit quaternions drifts by about 1 ulp per step otherwise). No singular
//! set: conditioning is 1. Order of the integrators is unaffected by the renormalisation,
//! which changes `q` only at round-off level.
use nalgebra::{Matrix3, UnitQuaternion, Vector3, Vector6};

use super::{Pose, PoseChart};
use crate::math::so3;

/// The `so3` chart.
#[derive(Debug, Clone, Copy, Default)]
pub struct So3;

impl PoseChart for So3 {
    const NAME: &'static str = "so3";
    type Coords = Pose<UnitQuaternion<f64>>;
    /// `(theta, dx)`.
    type Tangent = Vector6<f64>;
    const LIE: bool = true;
    const SE3: bool = false;
    const CONSTRAINED: bool = true;
    const NORMALIZES: bool = true;
    const FUSED_RETRACT_DEXP_INV: bool = true;

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
        _c: &Self::Coords,
        r: &Matrix3<f64>,
        omega_body: &Vector3<f64>,
        xdot: &Vector3<f64>,
        spatial: bool,
    ) -> Self::Tangent {
        let w = if spatial { r * omega_body } else { *omega_body };
        Vector6::new(w.x, w.y, w.z, xdot.x, xdot.y, xdot.z)
    }
    #[inline(always)]
    fn retract(c: &Self::Coords, d: &Self::Tangent, spatial: bool) -> Self::Coords {
        let e = so3::exp_quat_dexp_inv(&d.fixed_rows::<3>(0).into_owned()).0;
        act(c, d, &e, spatial)
    }
    #[inline(always)]
    fn dexp_inv(theta: &Self::Tangent, v: &Self::Tangent, spatial: bool) -> Self::Tangent {
        let th = theta.fixed_rows::<3>(0).into_owned();
        let g = so3::exp_quat_dexp_inv(&th).1;
        let signed = if spatial { th } else { -th };
        let r = so3::dexp_inv_apply_coeff(&signed, &v.fixed_rows::<3>(0).into_owned(), g);
        Vector6::new(r.x, r.y, r.z, v[3], v[4], v[5])
    }
    /// Both from one `so3::exp_quat_dexp_inv`; the numbers of `retract` and `dexp_inv`, bit
    /// for bit.
    #[inline(always)]
    fn retract_dexp_inv(
        c: &Self::Coords,
        d: &Self::Tangent,
        spatial: bool,
    ) -> (Self::Coords, impl Fn(&Self::Tangent) -> Self::Tangent) {
        let th = d.fixed_rows::<3>(0).into_owned();
        let (e, g) = so3::exp_quat_dexp_inv(&th);
        let signed = if spatial { th } else { -th };
        (act(c, d, &e, spatial), move |v: &Self::Tangent| {
            let r = so3::dexp_inv_apply_coeff(&signed, &v.fixed_rows::<3>(0).into_owned(), g);
            Vector6::new(r.x, r.y, r.z, v[3], v[4], v[5])
        })
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
        c.rot.coords.iter().all(|v| v.is_finite()) && c.x.iter().all(|v| v.is_finite())
    }
}

/// The pose `c` moved by the rotation `e = exp(theta)` of the increment `d = (theta, dx)`:
/// `q e` (body) or `e q` (spatial), and `x + dx`.
#[inline(always)]
fn act(
    c: &Pose<UnitQuaternion<f64>>,
    d: &Vector6<f64>,
    e: &UnitQuaternion<f64>,
    spatial: bool,
) -> Pose<UnitQuaternion<f64>> {
    // Products of unit quaternions: keep the raw product (normalize() projects).
    let rot = if spatial {
        UnitQuaternion::new_unchecked(e.into_inner() * c.rot.into_inner())
    } else {
        UnitQuaternion::new_unchecked(c.rot.into_inner() * e.into_inner())
    };
    Pose {
        rot,
        x: c.x + d.fixed_rows::<3>(3),
    }
}
