//! The rigid body in the variables of a kick-drift-kick step (`integrate::kick_drift`), the
//! kind of system `splitting` and `lgvi` advance: configuration `(R, x)` on SO(3) x R^3 in the
//! `so3` chart, momenta the body angular momentum `Pi = J omega` and the world velocity `v`.
//!
//! - `force`: the world force `f` of the springs and gravity at `(R, x)` and their torque in
//!   the body frame, `R^T tau` (the frame the momentum is kept in, so the kick needs no `R`);
//! - `kick`: `Pi <- Pi + s R^T tau`, `v <- v + s f / m` (a pinned body's translation stays
//!   frozen);
//! - `close`: the body rate from the momentum, `omega = J^-1 Pi` refined once
//!   (`body_momentum::omega_from_pi`), so that `J omega = Pi` to round-off.
//!
//! Invariant: the phase's quaternion is the product of unit quaternions the free flow made
//! (not renormalized here: the run loop normalizes the state it is handed).
use nalgebra::{Quaternion, UnitQuaternion, Vector3, Vector6};

use super::So3State;
use super::body_momentum::omega_from_pi;
use crate::integrate::kick_drift::SplitMechanics;
use crate::model::rigid_body::{RigidState, RigidSystem};
use crate::rotation::{Body, Pose, So3};

/// The rigid body's step variables.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RigidPhase {
    /// The attitude (a unit quaternion up to rounding).
    pub q: Quaternion<f64>,
    /// The position (m, world).
    pub x: Vector3<f64>,
    /// The world velocity (m/s).
    pub v: Vector3<f64>,
    /// The body angular momentum `J omega`.
    pub pi: Vector3<f64>,
}

impl SplitMechanics for RigidSystem<So3, Body> {
    type Force = (Vector3<f64>, Vector3<f64>);
    type Phase = RigidPhase;

    #[inline(always)]
    fn force(&self, at: &So3State) -> Self::Force {
        let r = at.pose.rot.to_rotation_matrix().into_inner();
        let (f, tau) = self.body.wrench(&r, &at.pose.x);
        (f, r.transpose() * tau)
    }

    #[inline(always)]
    fn open(&self, x: &So3State, carried: Option<&RigidPhase>) -> RigidPhase {
        let omega = x.vel.fixed_rows::<3>(3).into_owned();
        RigidPhase {
            q: x.pose.rot.into_inner(),
            x: x.pose.x,
            v: x.vel.fixed_rows::<3>(0).into_owned(),
            pi: carried.map_or_else(|| self.body.inertia * omega, |p| p.pi),
        }
    }

    #[inline(always)]
    fn kick(&self, f: &Self::Force, p: &mut RigidPhase, s: f64) {
        p.pi += f.1 * s;
        if self.body.translates() {
            p.v += f.0 * (s / self.body.mass);
        }
    }

    #[inline(always)]
    fn configuration(&self, p: &RigidPhase) -> So3State {
        RigidState {
            pose: Pose {
                rot: UnitQuaternion::new_unchecked(p.q),
                x: p.x,
            },
            vel: Vector6::zeros(),
        }
    }

    #[inline(always)]
    fn close(&self, p: &RigidPhase) -> So3State {
        let omega = omega_from_pi(&self.body, &p.pi);
        RigidState {
            pose: Pose {
                rot: UnitQuaternion::new_unchecked(p.q),
                x: p.x,
            },
            vel: Vector6::new(p.v.x, p.v.y, p.v.z, omega.x, omega.y, omega.z),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::integrate::rigid_test_support as ts;

    /// Opening and closing a state gives it back (the body rate through `J omega` and back to
    /// round-off), and carried momenta replace the computed ones.
    #[test]
    fn open_close_round_trip() {
        let (sys, x0) = ts::three_springs();
        let p = sys.open(&x0, None);
        let x1 = sys.close(&p);
        assert_eq!(x1.pose, x0.pose);
        assert!((x1.vel - x0.vel).amax() < 1e-15, "{:?}", x1.vel - x0.vel);
        let other = RigidPhase {
            pi: Vector3::new(1.0, 2.0, 3.0),
            ..p
        };
        assert_eq!(sys.open(&x0, Some(&other)).pi, other.pi);
    }

    /// The kick adds the impulse: the body torque `R^T tau` to the momentum and `f / m` to
    /// the velocity, scaled by the kick's time.
    #[test]
    fn kick_is_the_impulse() {
        let (sys, x0) = ts::three_springs();
        let f = sys.force(&x0);
        let mut p = sys.open(&x0, None);
        let p0 = p;
        sys.kick(&f, &mut p, 0.25);
        let r = x0.pose.rot.to_rotation_matrix().into_inner();
        let (force, tau) = sys.body.wrench(&r, &x0.pose.x);
        assert!((p.pi - p0.pi - r.transpose() * tau * 0.25).amax() < 1e-14);
        assert!((p.v - p0.v - force * (0.25 / sys.body.mass)).amax() < 1e-14);
        assert_eq!((p.q, p.x), (p0.q, p0.x));
    }
}
