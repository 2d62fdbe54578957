//! `OwnState`: recognising the state a rigid-body step produced, so that a method can carry
//! information from one step to the next (a force evaluated at the end of a step and reused at
//! the start of the next, "first same as last"; the acceleration-like variables of the
//! generalized-alpha method) without trusting a state it did not make.
//!
//! The caller normalizes the quaternion after each step (`So3::normalize`, a deterministic
//! function), so the state a step returns comes back either unchanged or with exactly the
//! normalized quaternion. Both are recognised, bit for bit; anything else (a new initial state,
//! a state from another method, a perturbed state) is not, and the method then starts afresh.
//! Comparison is exact: no tolerance, so two runs of the same build agree bit for bit.
use nalgebra::UnitQuaternion;

use crate::model::rigid_body::RigidState;
use crate::rotation::{Pose, PoseChart, So3};

/// A rigid-body state with the `so3` chart.
pub(crate) type So3State = RigidState<Pose<UnitQuaternion<f64>>>;

/// The last state a method produced, and its caller-normalized quaternion.
#[derive(Debug, Clone, Copy, Default)]
pub(crate) struct OwnState {
    last: Option<(So3State, UnitQuaternion<f64>)>,
}

impl OwnState {
    /// The quaternion the caller will store after normalizing `s`.
    #[inline]
    pub(crate) fn normalized(s: &So3State) -> UnitQuaternion<f64> {
        let mut p = s.pose;
        So3::normalize(&mut p);
        p.rot
    }

    /// Remembers `s` as the method's output.
    #[inline]
    pub(crate) fn record(&mut self, s: &So3State) {
        self.last = Some((*s, Self::normalized(s)));
    }

    /// Forgets the last output (after a failure).
    #[inline]
    pub(crate) fn clear(&mut self) {
        self.last = None;
    }

    /// Whether `s` is the last output, as returned or as normalized by the caller.
    #[inline]
    pub(crate) fn matches(&self, s: &So3State) -> bool {
        match &self.last {
            None => false,
            Some((o, qn)) => {
                o.pose.x == s.pose.x
                    && o.vel == s.vel
                    && (o.pose.rot.coords == s.pose.rot.coords || qn.coords == s.pose.rot.coords)
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::math::so3;
    use nalgebra::{Quaternion, Vector3, Vector6};

    /// A recorded state is recognised raw and caller-normalized, and a perturbed one is not.
    #[test]
    fn recognises_raw_and_normalized_only() {
        let q = so3::exp_quat(&Vector3::new(0.3, -0.2, 0.9));
        // A slightly non-unit quaternion, as a product of unit quaternions leaves it.
        let raw = UnitQuaternion::new_unchecked(Quaternion::from(q.coords * (1.0 + 3e-16)));
        let s = So3State {
            pose: Pose {
                rot: raw,
                x: Vector3::new(1.0, 2.0, 3.0),
            },
            vel: Vector6::new(0.1, 0.2, 0.3, 0.4, 0.5, 0.6),
        };
        let mut own = OwnState::default();
        assert!(!own.matches(&s));
        own.record(&s);
        assert!(own.matches(&s));
        let mut n = s;
        So3::normalize(&mut n.pose);
        assert!(own.matches(&n));
        let mut p = s;
        p.vel[3] += 1e-15;
        assert!(!own.matches(&p));
        own.clear();
        assert!(!own.matches(&s));
    }
}
