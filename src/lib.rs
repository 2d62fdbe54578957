//! mbdbench: a benchmark and verification suite for the numerics of multibody dynamics.
//!
//! Canonical problems (`cases/*.toml`) run with every rotation parameterization
//! ([`rotation`]) and time integrator ([`integrate`]) that applies ([`registry`]), scored
//! against stored, cross-checked references ([`reference`], [`refgen`]) on accuracy, energy
//! drift, constraint error and cost ([`metrics`], [`score`]). The binary `mbdbench` wraps
//! this in a command line ([`cli`]). Running one case with one variant:
//!
//! ```
//! use mbdbench::{case, plan, reference, registry, score};
//!
//! let cases = case::embedded().unwrap();
//! let c = cases.iter().find(|c| c.name == "nine_spring").unwrap();
//! let p = plan::scene_plan(c, c.scene("two_angles").unwrap()).unwrap();
//! let v = registry::find("so3", "rk4", "body").unwrap();
//! let out = (v.run)(&p.setup, 1.0e-2).unwrap();
//! assert!(out.failure.is_none());
//! let refs = mbdbench::cli::default_references();
//! let r = reference::load(&refs, "nine_spring", "two_angles", &p.inputs_sha256).unwrap();
//! let cx = score::ScoreContext {
//!     body: &p.setup.body,
//!     energy_scale: p.energy_scale,
//!     primary_metric: &p.primary_metric,
//!     reference: Some(&r.reference),
//! };
//! let (scores, _series) = score::score(&out, &cx);
//! let err = scores.get("rotation_error_max").unwrap();
//! assert!(err < 1e-5 && err > 1e-8, "RKMK4 at 1e-2 s: {err:e}");
//! ```
pub mod baseline;
pub mod case;
pub mod cli;
pub mod gate;
pub mod integrate;
pub mod math;
pub mod metrics;
pub mod model;
pub mod plan;
pub mod problem;
pub mod reference;
pub mod refgen;
pub mod registry;
pub mod report;
pub mod rotation;
pub mod run;
pub mod score;
pub mod stability;
pub mod suite;
pub mod summary;
