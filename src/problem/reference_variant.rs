//! A reference that is itself one of the variants: a scene whose stored reference was made by
//! a scheme the suite also runs (the fiber column's pulse: OpenSees' Newmark run of the same
//! column at 5e-4 s, which our `newmark`/`force_based` at 5e-4 s reproduces; the cyclic
//! columns: OpenSees' displacement-controlled Newton run at the protocol's own increment).
//!
//! Against such a reference an "error" is not a distance to the exact solution: the
//! reference's own variant reads the agreement of two codes running the same scheme, and
//! every other variant reads its distance to that scheme, whose own discretisation error
//! (the reference's accuracy claim, e.g. its half-step run) is part of every such number.
//! The report, `advise` and `summary.md` name the reference next to every error measured
//! against it (`advise::reference_notes`). A converged reference (an exact solution, a
//! tolerance-1e-12 run cross-checked by another method) is not declared here.
//!
//! # Example
//!
//! ```
//! use mbdbench::problem::ReferenceVariant;
//!
//! let r = ReferenceVariant {
//!     integrator: "newmark".into(),
//!     formulation: "force_based".into(),
//!     step: 5.0e-4,
//!     step_unit: "s".into(),
//!     made_by: "OpenSees 3.7.1".into(),
//! };
//! assert!(r.is_variant("newmark", "force_based"));
//! assert!(!r.is_variant("hht", "force_based"));
//! assert_eq!(r.label(), "OpenSees 3.7.1's newmark/force_based run at 5e-4 s");
//! ```
use serde::Serialize;

/// The variant (integrator and formulation, on any chart) and step that made a scene's
/// reference, and by which tool.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ReferenceVariant {
    pub integrator: String,
    pub formulation: String,
    /// The reference's step, in the unit of the scene's `dt` (`step_unit`).
    pub step: f64,
    /// `s` for a time step; the family's pseudo-time unit otherwise (a protocol increment).
    pub step_unit: String,
    /// The tool and version that made it (`OpenSees 3.7.1`).
    pub made_by: String,
}

impl ReferenceVariant {
    /// Whether `(integrator, formulation)` is the reference's own scheme (any chart).
    pub fn is_variant(&self, integrator: &str, formulation: &str) -> bool {
        self.integrator == integrator && self.formulation == formulation
    }

    /// Whether a run at `dt` is the reference's own step (to 1e-9 relative).
    pub fn is_step(&self, dt: f64) -> bool {
        (dt - self.step).abs() <= 1e-9 * self.step.abs()
    }

    /// `<made_by>'s <integrator>/<formulation> run at <step> <unit>`.
    pub fn label(&self) -> String {
        format!(
            "{}'s {}/{} run at {} {}",
            self.made_by,
            self.integrator,
            self.formulation,
            step_text(self.step),
            self.step_unit
        )
    }
}

/// A step as the advice prints one: an integer as such (`1`), else `{:e}` (`5e-4`).
fn step_text(x: f64) -> String {
    if x == x.trunc() && x.abs() < 1e6 {
        format!("{x:.0}")
    } else {
        format!("{x:e}")
    }
}
