//! The rigid body's own methods: the integrators that are written for its equations (a free
//! rigid body's momentum, its principal axes, its energy) rather than for any system of a kind,
//! and what they share. Each is registered in the family's table (`registry.rs`) like the
//! generic methods of `integrate/`.
//! - `splitting`: the free rigid body split into rotations about its principal axes;
//! - `lgvi`: the Lie-group variational integrator on the body's discrete Lagrangian;
//! - `lie_gen_alpha`: generalized-alpha on SO(3) x R^3 for the body's Newton-Euler equations;
//! - `simo_wong`, `simo_wong_kahan`: Simo and Wong's energy-momentum scheme, and its form whose
//!   round-off is `O(eps h)` a step;
//! - `compensated`: compensated (Kahan) summation of the rigid state's update
//!   (`implicit_midpoint_kahan`, `gauss6_kahan`);
//! - `body_momentum`, `own_state`: the end-of-step pieces they share (the body rate from the
//!   body momentum; recognising the state a step produced).
//!
//! They live here because they need `RigidSystem` and `RigidBody`; the generic method kinds
//! they instantiate (`integrate::FixedStep`, the implicit RK code of `integrate::implicit_rk`)
//! stay in `integrate/`, which imports no family (docs/architecture.md).
mod body_momentum;
pub mod compensated;
pub mod lgvi;
pub mod lie_gen_alpha;
mod own_state;
pub mod simo_wong;
pub mod simo_wong_kahan;
pub mod splitting;

/// The rigid body: the pose (attitude and position, both without a natural origin) is scaled
/// by the step's own increment, the velocities by their values.
impl<C: crate::rotation::PoseChart, F: crate::rotation::Formulation>
    crate::integrate::adaptive_rk::ErrorScale for super::RigidSystem<C, F>
{
    #[inline(always)]
    fn coords(&self, x: &Self::State) -> Self::Tangent {
        (crate::math::vector::Vector::zero(), x.vel)
    }
}

