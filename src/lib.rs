//! mbdbench: a benchmark and verification suite for the numerics of multibody dynamics.
pub mod integrate;
pub mod math;
pub mod model;
pub mod rotation;
pub mod run;
pub mod reference;
pub mod metrics;
pub mod summary;
pub mod registry;
pub mod score;
pub mod baseline;
pub mod cli;
pub mod suite;
