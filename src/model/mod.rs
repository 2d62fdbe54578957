//! Physical models, one file each.
pub mod rigid_body;
