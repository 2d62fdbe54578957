//! The rigid body as a second-order system on a Lie group (`integrate::LieSecondOrder`), the
//! kind of system `lie_gen_alpha` advances: configuration `q = (R, x)` on SO(3) x R^3 in the
//! `so3` chart (a unit quaternion and the position), velocity `w = (v, Omega)` in the body
//! formulation (world velocity, body angular velocity: `R' = R [Omega]x`), acceleration the
//! Newton-Euler equations of `RigidSystem::rhs`.
//!
//! - `advance`: `R exp([dOmega]x)` as the quaternion product `q exp_quat(dOmega)` (exact on the
//!   group; the caller renormalizes), `x + dx`; a pinned body (heavy top) keeps its translation
//!   frozen.
//! - `solve_iteration`: the tangent Jacobian is the analytic gyroscopic derivative of the body
//!   rate, `d Omega'/d Omega = J^-1 ([J Omega]x - [Omega]x J)`, and zero for the translation
//!   (the wrench depends on the pose only), so `(I - c df/dw) d = -r` is `-r` on the translation
//!   and a 3x3 LU solve on the rotation (`None` when that matrix is singular).
use nalgebra::{Matrix3, UnitQuaternion, Vector3, Vector6};

use super::So3State;
use crate::integrate::System;
use crate::integrate::lie_second_order::LieSecondOrder;
use crate::math::so3;
use crate::model::rigid_body::{RigidState, RigidSystem};
use crate::rotation::{Body, Pose, So3};

impl LieSecondOrder<6> for RigidSystem<So3, Body> {
    #[inline(always)]
    fn velocity(&self, x: &So3State) -> Vector6<f64> {
        x.vel
    }

    #[inline(always)]
    fn acceleration(&self, t: f64, x: &So3State) -> Vector6<f64> {
        self.rhs(t, x).1
    }

    #[inline(always)]
    fn advance(&self, x: &So3State, dq: &Vector6<f64>, w: &Vector6<f64>) -> So3State {
        let rot = UnitQuaternion::new_unchecked(
            x.pose.rot.into_inner() * so3::exp_quat(&dq.fixed_rows::<3>(3).into_owned()).into_inner(),
        );
        let pos = if self.body.translates() {
            x.pose.x + dq.fixed_rows::<3>(0)
        } else {
            x.pose.x
        };
        RigidState {
            pose: Pose { rot, x: pos },
            vel: *w,
        }
    }

    #[inline(always)]
    fn solve_iteration(&self, x: &So3State, c: f64, r: &Vector6<f64>) -> Option<Vector6<f64>> {
        let b = &self.body;
        let w = x.vel.fixed_rows::<3>(3).into_owned();
        let jw = b.inertia * w;
        let m = Matrix3::identity() - b.inertia_inv * (so3::hat(&jw) - so3::hat(&w) * b.inertia) * c;
        let r_rot = r.fixed_rows::<3>(3).into_owned();
        let d: Vector3<f64> = m.lu().solve(&(-r_rot))?;
        Some(Vector6::new(-r[0], -r[1], -r[2], d.x, d.y, d.z))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::integrate::rigid_test_support as ts;

    /// `solve_iteration` solves `(I - c df/dw) d = -r`: its update satisfies the equation with
    /// `df/dw` taken by central differences of the acceleration in the body rate (the
    /// translation rows are the identity: the wrench does not depend on the velocity).
    #[test]
    fn iteration_matches_finite_difference_jacobian() {
        let (sys, x0) = ts::three_springs();
        let (c, r) = (0.03, Vector6::new(0.1, -0.2, 0.3, 0.5, -0.4, 0.2));
        let d = sys.solve_iteration(&x0, c, &r).unwrap();
        let eps = 1e-6;
        let mut jd = Vector6::zeros();
        for k in 0..6 {
            let (mut p, mut m) = (x0, x0);
            p.vel[k] += eps;
            m.vel[k] -= eps;
            let col = (sys.acceleration(0.0, &p) - sys.acceleration(0.0, &m)) / (2.0 * eps);
            jd += col * d[k];
        }
        let lhs = d - jd * c;
        assert!((lhs + r).amax() < 1e-8, "{:?}", lhs + r);
    }

    /// `advance` moves the attitude by the exponential (a unit quaternion times a unit
    /// quaternion) and the position by the sum, and sets the velocity.
    #[test]
    fn advance_is_the_exponential_and_the_sum() {
        let (sys, x0) = ts::three_springs();
        let dq = Vector6::new(0.01, 0.02, -0.03, 0.2, -0.1, 0.3);
        let w = Vector6::new(1.0, 2.0, 3.0, 4.0, 5.0, 6.0);
        let x1 = sys.advance(&x0, &dq, &w);
        let want = x0.pose.rot.to_rotation_matrix().into_inner()
            * so3::exp(&Vector3::new(0.2, -0.1, 0.3));
        assert!((x1.pose.rot.to_rotation_matrix().into_inner() - want).amax() < 1e-15);
        assert!((x1.pose.rot.norm() - 1.0).abs() < 1e-15);
        assert_eq!(x1.pose.x, x0.pose.x + Vector3::new(0.01, 0.02, -0.03));
        assert_eq!(x1.vel, w);
    }
}
