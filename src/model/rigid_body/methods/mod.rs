//! The rigid body's own methods: the integrators that are written for its equations (a free
//! rigid body's momentum, its principal axes, its energy) rather than for any system of a kind,
//! and what they share. Each is registered in the family's table (`registry.rs`) like the
//! generic methods of `integrate/`.
//! - `splitting`: the free flow of the body's kinetic energy as rotations about its principal
//!   axes (`PrincipalRotor`), run by the generic kick-drift-kick of `integrate::kick_drift`;
//! - `lgvi`: the discrete free flow of the body's discrete Lagrangian (`MoserVeselov`), run by
//!   the same kick-drift-kick: the Lie-group variational integrator;
//! - `split_mechanics`: the body in the variables of that kick-drift-kick
//!   (`integrate::kick_drift::SplitMechanics`: its force, momenta and kick);
//! - `simo_wong`, `simo_wong_kahan`: Simo and Wong's energy-momentum scheme, and its form whose
//!   round-off is `O(eps h)` a step;
//! - `compensated`: compensated (Kahan) summation of the rigid state's update
//!   (`implicit_midpoint_kahan`, `gauss6_kahan`);
//! - `body_momentum`: the end-of-step piece they share (the body rate from the body momentum);
//! - `lie_second_order`: the body as an `integrate::LieSecondOrder` system (its retraction on
//!   SO(3) x R^3 and its gyroscopic tangent Jacobian), on which the generic Lie-group
//!   generalized-alpha method `integrate::lie_gen_alpha` runs.
//!
//! They live here because they need `RigidSystem` and `RigidBody`; the generic method kinds
//! they instantiate (`integrate::FixedStep`, the implicit RK code of `integrate::implicit_rk`,
//! `integrate::lie_gen_alpha`, `integrate::kick_drift`) and what they share with them (`integrate::own_state`,
//! `integrate::newton_stop`) stay in `integrate/`, which imports no family
//! (docs/architecture.md).
mod body_momentum;
pub mod compensated;
pub mod lgvi;
mod lie_second_order;
pub mod split_mechanics;
pub mod simo_wong;
pub mod simo_wong_kahan;
pub mod splitting;

/// A rigid-body state with the `so3` chart.
pub(crate) type So3State = super::RigidState<crate::rotation::Pose<nalgebra::UnitQuaternion<f64>>>;

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

