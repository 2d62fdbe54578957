//! The flexible beam on a moving base (cases/README.md, "flexible_beam"): a planar
//! Euler-Bernoulli beam clamped to a rigid base on the rotation axis, bending and stretching
//! in the plane of rotation, on Kane, Ryan & Banerjee's prescribed spin-up or on a free hub
//! driven by a torque pulse, in several formulations against a geometrically exact reference.
//!
//! Files: `base.rs` the base motions; `corotational.rs` the planar corotational element and
//! `fe.rs` the finite-element model (`fe_exact`, the reference model); `shapes.rs` the assumed
//! mode shapes and `modal.rs` the second-order modal model; `formulations.rs` the modal
//! formulations (`modal_linear`, `modal_stiffened`, the AIGC forms); `observe.rs` what a run
//! observes and the energy balance; `run.rs` the structural methods' run loop and `ode.rs` the
//! ODE form for the generic integrators, both restarting at the scenes' breakpoints;
//! `case.rs`, `family.rs`, `problem.rs`, `reference.rs` the family's case schema, table,
//! scoring and stored reference; `estimate.rs` what a run of a scene needs (its budgets).
pub mod base;
pub mod case;
pub mod corotational;
pub mod estimate;
pub mod family;
#[cfg(test)]
mod family_tests;
pub mod fe;
pub mod formulations;
#[cfg(test)]
mod fe_tests;
pub mod modal;
#[cfg(test)]
mod modal_tests;
pub mod shapes;
pub mod observe;
pub mod ode;
pub mod problem;
pub mod reference;
pub mod reference_check;
pub mod run;
