//! mbdbench: a benchmark and verification suite for the numerics of multibody dynamics.
pub mod baseline;
pub mod case;
pub mod cli;
pub mod integrate;
pub mod math;
pub mod metrics;
pub mod model;
pub mod plan;
pub mod reference;
pub mod refgen;
pub mod registry;
pub mod rotation;
pub mod run;
pub mod score;
pub mod suite;
pub mod summary;
