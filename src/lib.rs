//! mbdbench: a benchmark and verification suite for the numerics of multibody dynamics.
pub mod case;
pub mod integrate;
pub mod math;
pub mod model;
pub mod rotation;
