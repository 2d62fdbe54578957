//! The flexible beam on a moving base (in progress: its physics; the family joins the table
//! when its run loop, references and figures do).
//!
//! A planar Euler-Bernoulli beam clamped to a rigid base on the rotation axis, bending and
//! stretching in the plane of rotation: the spin-up of Kane, Ryan & Banerjee (prescribed base
//! motion) and a free hub driven by a torque pulse. `base.rs` holds the base motions,
//! `corotational.rs` the planar corotational element and `fe.rs` the finite-element model
//! (`fe_exact`), the family's reference.
pub mod base;
pub mod corotational;
pub mod fe;
#[cfg(test)]
mod fe_tests;
