//! The exact motion of a body spinning at a constant world angular velocity `w` (a spherical
//! body, `gimbal_lock/spin_*`, cases/README.md, `gimbal_lock`): `R(t) = exp(t [w]x) R0`,
//! `omega_body = R0^T w`, constant. Exact up to the rounding of `exp` and of one quaternion
//! product; the quaternion is sign-canonical. Where it fails: it does not check its input (a
//! non-finite `w` or a non-rotation `R0` gives a meaningless result).
use nalgebra::{Matrix3, UnitQuaternion, Vector3};

use crate::math::so3;

/// Constant world angular velocity `w_world` (spherical body, `gimbal_lock/spin_*`):
/// `R(t) = exp(t [w]x) R0` (sign-canonical quaternion) and `omega_body = R0^T w`.
pub fn spin_exact(
    w_world: Vector3<f64>,
    r0: Matrix3<f64>,
    t: f64,
) -> (UnitQuaternion<f64>, Vector3<f64>) {
    let q = so3::exp_quat(&(w_world * t)) * so3::quat_from_matrix(&r0);
    (so3::canonical(&q), r0.transpose() * w_world)
}
