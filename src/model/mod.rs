//! Physical models, one file each.
pub mod linear_modes;
pub mod rigid_body;
pub mod torque_free;
