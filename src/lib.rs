//! mbdbench: a benchmark and verification suite for the numerics of multibody dynamics.
//!
//! Canonical problems (`cases/*.toml`, [`case`]) of several model families ([`model`], each
//! plugged in by one line of the family table, [`catalogue::FAMILIES`]) run with every rotation
//! parameterization ([`rotation`]), formulation and time integrator ([`integrate`]) that
//! applies, scored against stored, cross-checked references ([`reference`], [`refgen`]) on
//! accuracy, energy drift, constraint error and cost ([`metrics`], [`score`]). The binary
//! `mbdbench` wraps this in a command line ([`cli`]). Running one case with one variant,
//! through the seam every family implements ([`problem::Problem`]):
//!
//! ```
//! use mbdbench::problem::{self, Stepping, Want};
//!
//! let cases = mbdbench::catalogue::embedded().unwrap();
//! let c = cases.iter().find(|c| c.name == "nine_spring").unwrap();
//! let family = mbdbench::catalogue::family_of(c);
//! let mut p = (family.compile)(c, c.scene("two_angles").unwrap()).unwrap();
//! p.attach_reference(&mbdbench::cli::default_references()).unwrap();
//! let v = family.find("so3", "rk4", "body").unwrap();
//! let out = p.run(v, Stepping::Dt(1.0e-2), Want::Scored).unwrap();
//! assert!(out.failure.is_none());
//! let err = out.scores.get("rotation_error_max").unwrap();
//! assert!(err < 1e-5 && err > 1e-8, "RKMK4 at 1e-2 s: {err:e}");
//! ```
pub mod advise;
pub mod case;
pub mod catalogue;
pub mod cli;
pub mod cost;
pub mod cpu_clock;
pub mod digest;
pub mod gate;
pub mod integrate;
pub mod math;
pub mod methods;
pub mod metrics;
pub mod model;
pub mod output;
pub mod problem;
pub mod progress;
pub mod quiet;
pub mod read_limited;
pub mod reference;
pub mod report;
pub mod rotation;
pub mod run;
pub mod selection;
pub mod stability;
pub mod structural;
pub mod study;
pub mod suite;
pub mod summary;
