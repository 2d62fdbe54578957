//! The end-of-step piece of the rigid body's momentum methods (`splitting`, `lgvi`, through
//! `split_mechanics`): the body angular velocity recovered from the body angular momentum to
//! round-off.
//!
//! `omega = J^{-1} Pi` with one step of iterative refinement: the computed inverse alone has a
//! fixed rounding error that the next step's `J omega` turns into a drift of `|Pi|` of about
//! one ulp a step (measured: 2e-13 of |L| in 1000 steps with a full inertia); after the
//! refinement `J omega = Pi` holds to round-off.
use nalgebra::Vector3;

use crate::model::rigid_body::RigidBody;

/// `J^{-1} Pi`, refined once so that `J omega = Pi` to round-off.
#[inline(always)]
pub(crate) fn omega_from_pi(b: &RigidBody, pi: &Vector3<f64>) -> Vector3<f64> {
    let mut omega = b.inertia_inv * pi;
    omega += b.inertia_inv * (pi - b.inertia * omega);
    omega
}

#[cfg(test)]
mod tests {
    use super::*;
    use nalgebra::Matrix3;

    /// The refined solve satisfies J omega = Pi to a few ulps on a full, badly scaled inertia.
    #[test]
    fn refined_solve_is_exact_to_round_off() {
        let j = Matrix3::new(800.0, -60.0, 40.0, -60.0, 1000.0, -80.0, 40.0, -80.0, 1e-3);
        let b = RigidBody::new(1.0, j, vec![], None, None).unwrap();
        let pi = Vector3::new(0.3, -1.7, 2.9e-4);
        let w = omega_from_pi(&b, &pi);
        assert!((b.inertia * w - pi).amax() <= 8.0 * f64::EPSILON * pi.amax());
    }
}
