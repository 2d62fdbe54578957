//! `quat` and `quat_proj`: the quaternion `q = (w, x, y, z)` as four additive numbers
//! (Euler parameters), with the translation additive beside them; `quat_proj` divides by
//! `|q|` after every step, `quat` never does.
//!
//! Kinematics: `q' = q (x) (0, omega)/2` (body angular velocity; e.g. Shuster 1993, eq. 306),
//! which keeps `|q|` constant in exact arithmetic; a Runge-Kutta step does not, so `|q|`
//! drifts at the method's local error. The rotation of a general `q` is the sandwich
//! `u -> q (x) (0, u) (x) q*`, i.e. the homogeneous quadratic form
//! `R(q) = (w^2 - |v|^2) I + 2 v v^T + 2 w [v]x = |q|^2 R(q/|q|)` (the same formula
//! nalgebra uses for a unit quaternion). So off the unit sphere `R(q)` is a rotation scaled
//! by `|q|^2`: without projection the drift enters the dynamics (forces, torques, the
//! spatial-formulation velocities) rather than being silently normalised away, which is what
//! the unprojected variant measures; `R' = R(q) [omega]x` holds for every `|q|`.
//! `quaternion()` reports the unit quaternion `q/|q|` (sign-canonical), the rotation the
//! numbers stand for. Residual `||q|^2 - 1|`; no singular set except `q = 0` (conditioning 1).
//! The projection `q/|q|` is exact to 1 ulp per component and idempotent to 2 eps.
use nalgebra::{Matrix3, Quaternion, SVector, UnitQuaternion, Vector3};

use super::{Pose, PoseChart};
use crate::math::so3;

/// `R(q) = (w^2 - |v|^2) I + 2 v v^T + 2 w [v]x`, the sandwich `q (.) q*` (module docs).
#[inline(always)]
pub fn sandwich_matrix(q: &Quaternion<f64>) -> Matrix3<f64> {
    let (w, x, y, z) = (q.w, q.i, q.j, q.k);
    let (ww, xx, yy, zz) = (w * w, x * x, y * y, z * z);
    let (xy, xz, yz) = (2.0 * x * y, 2.0 * x * z, 2.0 * y * z);
    let (wx, wy, wz) = (2.0 * w * x, 2.0 * w * y, 2.0 * w * z);
    Matrix3::new(
        ww + xx - yy - zz,
        xy - wz,
        xz + wy,
        xy + wz,
        ww - xx + yy - zz,
        yz - wx,
        xz - wy,
        yz + wx,
        ww - xx - yy + zz,
    )
}

/// `q (x) (0, omega) / 2`.
#[inline(always)]
pub fn body_rate(q: &Quaternion<f64>, omega: &Vector3<f64>) -> Quaternion<f64> {
    q * Quaternion::new(0.0, 0.5 * omega.x, 0.5 * omega.y, 0.5 * omega.z)
}

/// The sign-canonical unit quaternion `q/|q|`.
#[inline]
fn unit(q: &Quaternion<f64>) -> UnitQuaternion<f64> {
    so3::canonical(&UnitQuaternion::new_normalize(*q))
}

/// One quaternion chart; `$proj` says whether it projects after each step.
macro_rules! quat_chart {
    ($t:ident, $name:literal, $proj:literal) => {
        #[doc = concat!("The `", $name, "` chart: tangent `(w', x', y', z', xdot)` (7 numbers).")]
        #[derive(Debug, Clone, Copy, Default)]
        pub struct $t;

        impl PoseChart for $t {
            const NAME: &'static str = $name;
            type Coords = Pose<Quaternion<f64>>;
            /// `(q', xdot)`, `q'` in the order `(w, x, y, z)`.
            type Tangent = SVector<f64, 7>;
            const LIE: bool = false;
            const SE3: bool = false;
            const CONSTRAINED: bool = true;
            const NORMALIZES: bool = $proj;

            fn from_pose(r: &Matrix3<f64>, x: &Vector3<f64>) -> Self::Coords {
                Pose {
                    rot: so3::quat_from_matrix(r).into_inner(),
                    x: *x,
                }
            }
            #[inline(always)]
            fn rotation(c: &Self::Coords) -> Matrix3<f64> {
                sandwich_matrix(&c.rot)
            }
            fn quaternion(c: &Self::Coords) -> UnitQuaternion<f64> {
                unit(&c.rot)
            }
            #[inline(always)]
            fn velocity(
                c: &Self::Coords,
                _r: &Matrix3<f64>,
                omega_body: &Vector3<f64>,
                xdot: &Vector3<f64>,
                _spatial: bool,
            ) -> Self::Tangent {
                let d = body_rate(&c.rot, omega_body);
                SVector::<f64, 7>::from([d.w, d.i, d.j, d.k, xdot.x, xdot.y, xdot.z])
            }
            #[inline(always)]
            fn retract(c: &Self::Coords, d: &Self::Tangent, _spatial: bool) -> Self::Coords {
                Pose {
                    rot: Quaternion::new(
                        c.rot.w + d[0],
                        c.rot.i + d[1],
                        c.rot.j + d[2],
                        c.rot.k + d[3],
                    ),
                    x: c.x + d.fixed_rows::<3>(4),
                }
            }
            #[inline(always)]
            fn dexp_inv(
                _theta: &Self::Tangent,
                v: &Self::Tangent,
                _spatial: bool,
            ) -> Self::Tangent {
                *v
            }
            fn residual(c: &Self::Coords) -> Option<f64> {
                Some((c.rot.norm_squared() - 1.0).abs())
            }
            fn conditioning(_c: &Self::Coords) -> f64 {
                1.0
            }
            #[inline(always)]
            fn normalize(c: &mut Self::Coords) -> bool {
                if $proj {
                    c.rot = so3::renormalize(c.rot);
                }
                $proj
            }
            #[inline]
            fn is_finite(c: &Self::Coords) -> bool {
                c.rot.coords.iter().chain(c.x.iter()).all(|v| v.is_finite())
            }
        }
    };
}

quat_chart!(Quat, "quat", false);
quat_chart!(QuatProj, "quat_proj", true);

#[cfg(test)]
mod tests {
    use super::*;

    /// The sandwich matrix equals nalgebra's rotation on unit quaternions (1e-15) and is
    /// homogeneous of degree 2 off the sphere (R(2q) = 4 R(q) exactly, a power of two).
    #[test]
    fn sandwich_is_homogeneous_rotation() {
        let q = UnitQuaternion::from_quaternion(Quaternion::new(0.3, -0.5, 0.7, 0.2));
        let r = sandwich_matrix(q.quaternion());
        assert!((r - q.to_rotation_matrix().into_inner()).amax() < 1e-15);
        assert_eq!(sandwich_matrix(&(q.into_inner() * 2.0)), r * 4.0);
    }

    /// Without projection a scaled quaternion keeps its scale and its residual; with
    /// projection it is brought back to the unit sphere to 2 eps and reports it.
    #[test]
    fn projection_only_in_quat_proj() {
        let mut c = Pose {
            rot: Quaternion::new(0.3, -0.5, 0.7, 0.2) * 1.7,
            x: Vector3::zeros(),
        };
        let mut p = c;
        assert!(!Quat::normalize(&mut c));
        assert!(Quat::residual(&c).unwrap() > 0.1);
        assert!(QuatProj::normalize(&mut p));
        assert!(QuatProj::residual(&p).unwrap() < 4.5e-16);
        assert!(so3::geodesic_quat(&Quat::quaternion(&c), &QuatProj::quaternion(&p)) < 1e-15);
    }
}
