//! `OwnState`: recognising the state a step produced, so that a method can carry information
//! from one step to the next (a force evaluated at the end of a step and reused at the start of
//! the next, "first same as last"; the acceleration-like variables of the generalized-alpha
//! method) without trusting a state it did not make.
//!
//! A run loop may normalize the state after each step (`System::normalize`, a deterministic
//! function: a quaternion brought back to unit length), so the state a step returns comes back
//! either unchanged or exactly normalized. Both are recognised, bit for bit; anything else (a
//! new initial state, a state from another method, a perturbed state) is not, and the method
//! then starts afresh. Comparison is exact (`PartialEq` of the state, no tolerance), so two
//! runs of the same build agree bit for bit; a state holding a NaN never matches.
use super::System;

/// The last state a method produced, and that state as the caller will normalize it.
///
/// # Example
///
/// A state on the unit circle that the caller brings back to unit length: the method's own
/// output is recognised raw and normalized, a perturbed state is not.
///
/// ```
/// # use mbdbench::integrate::{Failure, System};
/// use mbdbench::integrate::own_state::OwnState;
/// use nalgebra::Vector2;
///
/// struct Circle;
/// impl System for Circle {
///     type State = Vector2<f64>;
///     type Tangent = Vector2<f64>;
///     const LIE: bool = false;
///     fn rhs(&self, _t: f64, x: &Vector2<f64>) -> Vector2<f64> { Vector2::new(-x[1], x[0]) }
///     fn retract(&self, x: &Vector2<f64>, dx: &Vector2<f64>) -> Vector2<f64> { x + dx }
///     fn normalize(&self, x: &mut Vector2<f64>) -> bool { *x /= x.norm(); true }
///     fn check(&self, _t: f64, _x: &Vector2<f64>) -> Result<(), Failure> { Ok(()) }
/// }
/// let raw = Vector2::new(0.6, 0.8) * (1.0 + 1e-12);
/// let mut own = OwnState::default();
/// assert!(!own.matches(&raw));
/// own.record(&Circle, &raw);
/// assert!(own.matches(&raw) && own.matches(&(raw / raw.norm())));
/// assert!(!own.matches(&(raw * 2.0)));
/// ```
#[derive(Debug, Clone, Copy)]
pub struct OwnState<St: Copy> {
    last: Option<(St, St)>,
}

impl<St: Copy> Default for OwnState<St> {
    fn default() -> Self {
        OwnState { last: None }
    }
}

/// `s` as the caller will store it after normalizing it.
#[inline]
pub fn normalized<S: System>(sys: &S, s: &S::State) -> S::State
where
    S::State: Copy,
{
    let mut n = *s;
    sys.normalize(&mut n);
    n
}

impl<St: Copy + PartialEq> OwnState<St> {
    /// Remembers `s` as the method's output.
    #[inline]
    pub fn record<S: System<State = St>>(&mut self, sys: &S, s: &St) {
        self.last = Some((*s, normalized(sys, s)));
    }

    /// Forgets the last output (after a failure).
    #[inline]
    pub fn clear(&mut self) {
        self.last = None;
    }

    /// Whether `s` is the last output, as returned or as normalized by the caller.
    #[inline]
    pub fn matches(&self, s: &St) -> bool {
        match &self.last {
            None => false,
            Some((raw, norm)) => raw == s || norm == s,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::integrate::rigid_test_support as ts;
    use crate::math::so3;
    use nalgebra::{Quaternion, UnitQuaternion, Vector3, Vector6};

    /// A recorded rigid state is recognised raw and caller-normalized (its quaternion brought to
    /// unit length by the system), and a perturbed or forgotten one is not.
    #[test]
    fn recognises_raw_and_normalized_only() {
        let (sys, _) = ts::three_springs();
        let q = so3::exp_quat(&Vector3::new(0.3, -0.2, 0.9));
        // A slightly non-unit quaternion, as a product of unit quaternions leaves it.
        let raw = UnitQuaternion::new_unchecked(Quaternion::from(q.coords * (1.0 + 3e-16)));
        let s = ts::St {
            pose: crate::rotation::Pose {
                rot: raw,
                x: Vector3::new(1.0, 2.0, 3.0),
            },
            vel: Vector6::new(0.1, 0.2, 0.3, 0.4, 0.5, 0.6),
        };
        let mut own = OwnState::default();
        assert!(!own.matches(&s));
        own.record(&sys, &s);
        assert!(own.matches(&s));
        let n = normalized(&sys, &s);
        assert_ne!(n.pose.rot.coords, s.pose.rot.coords);
        assert!(own.matches(&n));
        let mut p = s;
        p.vel[3] += 1e-15;
        assert!(!own.matches(&p));
        own.clear();
        assert!(!own.matches(&s));
    }

    /// A state with a NaN never matches, even the one recorded (NaN != NaN).
    #[test]
    fn nan_never_matches() {
        let (sys, x0) = ts::three_springs();
        let mut s = x0;
        s.vel[0] = f64::NAN;
        let mut own = OwnState::default();
        own.record(&sys, &s);
        assert!(!own.matches(&s));
    }
}
