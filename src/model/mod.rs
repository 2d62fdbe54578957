//! Physical models, one file each.
pub mod rigid_body;
pub mod torque_free;
