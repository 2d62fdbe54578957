//! Which variants a plot draws. A scene has up to ~150 variants; one plot with all of them is
//! unreadable, so every plot draws one of its family's named selections
//! (`problem::figures::Selection`, declared with the family's figures) and its caption names
//! it. This file applies a selection to the report's variant views.
use super::data::VariantRuns;

pub use crate::problem::figures::Selection;

/// A selection applied to the report's variants.
pub trait Admits {
    /// Whether a variant is drawn.
    fn admits(&self, v: &VariantRuns) -> bool;
}

impl Admits for Selection {
    fn admits(&self, v: &VariantRuns) -> bool {
        self.admit
            .admits(&v.key.param, &v.key.integrator, v.adaptive)
    }
}
